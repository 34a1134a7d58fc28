// Polytope model: hulls equal the known hulls, explicit faces are validated, bad input is refused
// with a message, and support mapping by hill climbing agrees with brute force.
#include "geometry_oracles.hpp"

#include <catch2/catch.hpp>

using namespace gdc;
using namespace gdc::testing;

namespace {

std::vector<Vec3> cubeCorners(double h) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
    return corners;
}

std::vector<Vec3> icosahedron() {
    const double phi = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vec3> v;
    for (double s : {-1.0, 1.0})
        for (double t : {-1.0, 1.0}) {
            v.emplace_back(0, s, t * phi);
            v.emplace_back(s, t * phi, 0);
            v.emplace_back(t * phi, 0, s);
        }
    return v;
}

std::vector<Vec3> fibonacciSphere(int count) {
    std::vector<Vec3> points;
    const double golden = M_PI * (3 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        double z = 1 - 2 * (i + 0.5) / count, r = std::sqrt(1 - z * z);
        points.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
    }
    return points;
}

void requireInvalid(const std::function<void()>& build, const std::string& fragment) {
    try {
        build();
        FAIL("expected gdc::InvalidInput mentioning \"" << fragment << "\"");
    } catch (const InvalidInput& error) {
        INFO(error.what());
        CHECK(std::string(error.what()).find(fragment) != std::string::npos);
    }
}

}  // namespace

TEST_CASE("hull of a cube's corners plus interior, face and edge points is the cube") {
    std::vector<Vec3> points = cubeCorners(0.5);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> inside(-0.49, 0.49);
    for (int i = 0; i < 50; ++i) points.emplace_back(inside(random), inside(random), inside(random));
    points.emplace_back(0.5, 0, 0);     // a face centre
    points.emplace_back(0.5, 0.5, 0);   // an edge midpoint
    points.emplace_back(0, -0.5, 0.2);  // on a face
    Polytope cube = Polytope::fromPoints(points);
    CHECK(cube.vertices().size() == 8);
    CHECK(cube.faces().size() == 6);
    CHECK(cube.edges().size() == 12);
    CHECK(cube.volume() == Approx(1.0).epsilon(1e-12));
    CHECK(cube.centroid().norm() < 1e-12);
    for (const auto& face : cube.faces()) {
        CHECK(face.count == 4);
        CHECK(face.offset == Approx(0.5).epsilon(1e-12));
        CHECK(face.normal.cwiseAbs().maxCoeff() == Approx(1.0).epsilon(1e-12));
    }
}

TEST_CASE("hull of a hexagonal prism has two hexagons and six rectangles") {
    std::vector<Vec3> points;
    for (int i = 0; i < 6; ++i)
        for (double z : {-0.3, 0.3}) points.emplace_back(std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), z);
    Polytope prism = Polytope::fromPoints(points);
    CHECK(prism.vertices().size() == 12);
    CHECK(prism.faces().size() == 8);
    int hexagons = 0, rectangles = 0;
    for (const auto& face : prism.faces()) hexagons += face.count == 6, rectangles += face.count == 4;
    CHECK(hexagons == 2);
    CHECK(rectangles == 6);
    CHECK(prism.volume() == Approx(6 * std::sqrt(3.0) / 4 * 0.6).epsilon(1e-12));  // hexagon area × height
}

TEST_CASE("hull of an icosahedron's vertices is the icosahedron") {
    Polytope ico = Polytope::fromPoints(icosahedron());
    CHECK(ico.vertices().size() == 12);
    CHECK(ico.faces().size() == 20);
    CHECK(ico.edges().size() == 30);
    for (const auto& face : ico.faces()) CHECK(face.count == 3);
    for (std::size_t v = 0; v < 12; ++v)
        CHECK(ico.neighborOffsets()[v + 1] - ico.neighborOffsets()[v] == 5);
}

TEST_CASE("faces are counter-clockwise seen from outside and contain their vertices") {
    Polytope ico = Polytope::fromPoints(icosahedron());
    for (const auto& face : ico.faces()) {
        const Vec3& a = ico.vertices()[ico.faceVertices()[face.first]];
        const Vec3& b = ico.vertices()[ico.faceVertices()[face.first + 1]];
        const Vec3& c = ico.vertices()[ico.faceVertices()[face.first + 2]];
        CHECK((b - a).cross(c - a).dot(face.normal) > 0);
        CHECK(face.normal.dot(a) == Approx(face.offset));
    }
}

TEST_CASE("explicit faces: a box built by hand equals Polytope::box") {
    Polytope box = Polytope::box(Vec3(1, 2, 3));
    CHECK(box.vertices().size() == 8);
    CHECK(box.faces().size() == 6);
    CHECK(box.volume() == Approx(48));
    Polytope again = Polytope::fromFaces(box.vertices(), [&] {
        std::vector<std::vector<int>> faces;
        for (const auto& face : box.faces())
            faces.emplace_back(box.faceVertices().begin() + face.first,
                               box.faceVertices().begin() + face.first + face.count);
        return faces;
    }());
    CHECK(again.volume() == Approx(48));
}

TEST_CASE("explicit triangulated faces of a cube are merged into six quads") {
    std::vector<Vec3> corners = cubeCorners(1);
    // Each quad of Polytope::box split into two triangles.
    std::vector<std::vector<int>> quads = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    std::vector<std::vector<int>> triangles;
    for (const auto& q : quads) triangles.push_back({q[0], q[1], q[2]}), triangles.push_back({q[0], q[2], q[3]});
    Polytope cube = Polytope::fromFaces(corners, triangles);
    CHECK(cube.faces().size() == 6);
    CHECK(cube.edges().size() == 12);
}

// Issue 21: qhull's triangulated output split such hulls into triangles and the tiny one was
// refused as "zero area"; every point set that spans a volume is a valid hull.
TEST_CASE("a tetrahedron with a corner cut by 1e-6 of its size is accepted with its tiny face") {
    const Polytope cut = Polytope::fromPoints({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0.999999),
                                               Vec3(1e-6, 0, 0.999999), Vec3(0, 1e-6, 0.999999)});
    CHECK(cut.vertices().size() == 6);
    CHECK(cut.faces().size() == 5);
    CHECK(cut.edges().size() == 9);
    CHECK(cut.volume() == Approx(1.0 / 6).epsilon(1e-9));
    bool hasTinyTop = false;
    for (const auto& face : cut.faces()) hasTinyTop |= face.normal.isApprox(Vec3::UnitZ(), 1e-9);
    CHECK(hasTinyTop);
}

TEST_CASE("hulls with features down to 1e-12 of their size, anywhere, are accepted") {
    for (double cut : {1e-2, 1e-5, 1e-7, 1e-9, 1e-12})
        for (double scale : {1e-3, 1.0, 1e3})
            for (double away : {0.0, 1e3}) {
                CAPTURE(cut, scale, away);
                const Vec3 shift(away, -away, 0.5 * away);
                std::vector<Vec3> points;
                for (int i = 0; i < 8; ++i) {  // a box whose +x+y+z corner is cut
                    const Vec3 c(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
                    if (i != 7) {
                        points.push_back(scale * c + shift);
                        continue;
                    }
                    for (const Vec3& towards : {Vec3(-1, 1, 1), Vec3(1, -1, 1), Vec3(1, 1, -1)})
                        points.push_back(scale * (c + cut * (towards - c)) + shift);
                }
                const Polytope hull = Polytope::fromPoints(points);
                CHECK(hull.volume() == Approx(8 * scale * scale * scale).epsilon(1e-6));
                for (const auto& face : hull.faces())
                    for (const Vec3& v : hull.vertices()) CHECK(face.normal.dot(v) <= face.offset + 1e-9 * scale);
            }
}

TEST_CASE("a tetrahedron 2e-9 of its size thick spans a volume and is accepted") {
    const Polytope flat = Polytope::fromPoints({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 2e-9)});
    CHECK(flat.faces().size() == 4);
    CHECK(flat.volume() == Approx(2e-9 / 6).epsilon(1e-6));
}

TEST_CASE("bad point sets are refused with a message") {
    requireInvalid([] { Polytope::fromPoints({}); }, "at least 4 points");
    requireInvalid([] { Polytope::fromPoints({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)}); },
                   "no 3-D hull");
    requireInvalid([] { Polytope::fromPoints({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(0.5, 0.2, 0)}); },
                   "no 3-D hull");
    requireInvalid([] { Polytope::fromPoints({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(NAN, 0, 1)}); },
                   "not finite");
    requireInvalid([] { Polytope::fromPoints(std::vector<Vec3>(6, Vec3(1, 1, 1))); }, "no 3-D hull");
    requireInvalid([] { Polytope::fromPoints({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, INFINITY, 0), Vec3(0, 0, 1)}); },
                   "not finite");
    requireInvalid([] { Polytope::fromPoints({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}); }, "at least 4 points");
}

TEST_CASE("bad explicit faces are refused with a message naming the problem") {
    std::vector<Vec3> corners = cubeCorners(1);
    std::vector<std::vector<int>> quads = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    SECTION("all faces clockwise") {
        auto reversed = quads;
        for (auto& q : reversed) std::reverse(q.begin(), q.end());
        requireInvalid([&] { Polytope::fromFaces(corners, reversed); }, "clockwise");
    }
    SECTION("one face wound the wrong way") {
        auto wrong = quads;
        std::reverse(wrong[3].begin(), wrong[3].end());
        requireInvalid([&] { Polytope::fromFaces(corners, wrong); }, "same direction");
    }
    SECTION("a missing face: not closed") {
        auto open = quads;
        open.pop_back();
        requireInvalid([&] { Polytope::fromFaces(corners, open); }, "not closed");
    }
    SECTION("a dented vertex: not convex") {
        auto dented = corners;
        dented[7] = Vec3(0.2, 0.2, 0.2);  // the +x+y+z corner pushed inside
        std::vector<std::vector<int>> triangles;
        for (const auto& q : quads) triangles.push_back({q[0], q[1], q[2]}), triangles.push_back({q[0], q[2], q[3]});
        requireInvalid([&] { Polytope::fromFaces(dented, triangles); }, "convex");
    }
    SECTION("a self-intersecting (bow-tie) face") {
        auto bowTie = quads;
        bowTie[1] = {1, 7, 3, 5};  // the +x face's corners in crossing order
        requireInvalid([&] { Polytope::fromFaces(corners, bowTie); }, "self-intersecting");
    }
    SECTION("a face that winds twice (a pentagram)") {
        std::vector<Vec3> prism;
        for (double z : {0.0, 1.0})
            for (int i = 0; i < 5; ++i) prism.emplace_back(std::cos(i * 2 * M_PI / 5), std::sin(i * 2 * M_PI / 5), z);
        std::vector<std::vector<int>> faces = {{4, 3, 2, 1, 0}, {5, 7, 9, 6, 8}};
        for (int i = 0; i < 5; ++i) faces.push_back({i, (i + 1) % 5, (i + 1) % 5 + 5, i + 5});
        requireInvalid([&] { Polytope::fromFaces(prism, faces); }, "not a convex polygon");
    }
    SECTION("a vertex index out of range") {
        auto bad = quads;
        bad[0][1] = 42;
        requireInvalid([&] { Polytope::fromFaces(corners, bad); }, "does not exist");
    }
    SECTION("zero-size and NaN boxes") {
        requireInvalid([] { Polytope::box(Vec3(1, 0, 1)); }, "positive");
        requireInvalid([] { Polytope::box(Vec3(1, -1, 1)); }, "positive");
        requireInvalid([] { Polytope::box(Vec3(NAN, 1, 1)); }, "finite");
    }
}

TEST_CASE("hill-climbing support agrees with brute force on a 4096-vertex near-sphere") {
    Polytope sphere = Polytope::fromPoints(fibonacciSphere(4096));
    REQUIRE(sphere.vertices().size() == 4096);
    std::mt19937 random(3);
    std::normal_distribution<double> gauss;
    for (int i = 0; i < 500; ++i) {
        Vec3 direction(gauss(random), gauss(random), gauss(random));
        int climbed = sphere.supportVertex(direction, 0);
        int brute = sphere.supportVertex(direction, 1 << 30);
        CHECK(sphere.vertices()[climbed].dot(direction) == Approx(sphere.vertices()[brute].dot(direction)).epsilon(1e-15));
    }
}

TEST_CASE("a box's closed-form support agrees with brute force over its vertices") {
    Polytope box = Polytope::box(Vec3(0.3, 1.1, 2.0));
    REQUIRE(box.isBox());
    std::mt19937 random(12);
    std::normal_distribution<double> gauss;
    for (int i = 0; i < 200; ++i) {
        Vec3 direction(gauss(random), gauss(random), gauss(random));
        double best = -INFINITY;
        for (const Vec3& v : box.vertices()) best = std::max(best, v.dot(direction));
        CHECK(box.vertices()[box.supportVertex(direction)].dot(direction) == Approx(best).epsilon(1e-15));
    }
}

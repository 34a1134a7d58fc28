// The whole pipeline against exact answers: analytic contact polygons, hand-computed feature
// pairs, touching and separated pairs, swap symmetry and invariance under translation and scale.
#include "contact_checks.hpp"

using namespace gdc;
using namespace gdc::testing;

namespace {

const Polytope& unitCube() {
    static const Polytope cube = Polytope::box(Vec3(0.5, 0.5, 0.5));
    return cube;
}

Settings allContacts() {
    Settings s;
    s.maxContacts = kMaxManifoldPoints;
    return s;
}

std::vector<Vec2> squareCorners(double half, const Vec2& centre, double yaw) {
    std::vector<Vec2> corners;
    for (const Vec2& c : {Vec2(-half, -half), Vec2(half, -half), Vec2(half, half), Vec2(-half, half)})
        corners.push_back(centre + Eigen::Rotation2Dd(yaw) * c);
    return corners;
}

// A tilted face's contact region (tests of spanContactRegion): the expected points, two of them
// at the sink depth along the deepest edge and two at depth 0 where the region ends.
void checkTiltedRegion(const Manifold& m, const std::vector<Vec3>& expected, double sink) {
    CHECK(sameSets(positions(m), expected, 1e-9));
    int deep = 0, touching = 0;
    for (int i = 0; i < m.pointCount; ++i) {
        deep += std::abs(m.points[i].depth - sink) < 1e-12;
        touching += std::abs(m.points[i].depth) < 1e-12;
    }
    CHECK(deep == 2);
    CHECK(touching == 2);
}

}  // namespace

TEST_CASE("box on box at random yaw and offset: the analytic intersection polygon, exact depth and normal") {
    const Polytope base = Polytope::box(Vec3(0.8, 0.6, 0.5));
    std::mt19937 random(2024);
    std::uniform_real_distribution<double> yaw(-M_PI, M_PI), offset(-1.0, 1.0), sink(0, 0.01);
    int checked = 0;
    for (int trial = 0; trial < 400; ++trial) {
        double angle = yaw(random), depth = sink(random);
        Vec2 centre(offset(random), offset(random));
        Pose top = makePose(Vec3(centre.x(), centre.y(), 1.0 - depth), rotationAbout(Vec3::UnitZ(), angle));
        Manifold m = collide(base, Pose{}, unitCube(), top, allContacts());
        std::vector<Vec2> rectangle = {Vec2(-0.8, -0.6), Vec2(0.8, -0.6), Vec2(0.8, 0.6), Vec2(-0.8, 0.6)};
        std::vector<Vec2> polygon = convexPolygonIntersection(rectangle, squareCorners(0.5, centre, angle));
        double area = 0;  // skip slivers where a corner barely touches: their vertex order is ill-posed
        for (std::size_t i = 0; i < polygon.size(); ++i) area += std::abs(polygon[i].x() * polygon[(i + 1) % polygon.size()].y());
        if (polygon.size() < 3 || area < 1e-6) continue;
        ++checked;
        INFO("trial " << trial << " yaw " << angle << " centre " << centre.transpose());
        REQUIRE(m.pointCount == static_cast<int>(polygon.size()));
        CHECK((m.normal - Vec3::UnitZ()).norm() < 1e-12);
        std::vector<Vec3> expected;
        for (const Vec2& p : polygon) expected.emplace_back(p.x(), p.y(), 0.5 - depth / 2);
        CHECK(sameSets(positions(m), expected, 1e-9 * 2));
        for (int i = 0; i < m.pointCount; ++i) CHECK(m.points[i].depth == Approx(depth).margin(1e-12));
        requireValidContacts(m, base, Pose{}, unitCube(), top, 1e-9);
        requireOnSurfaces(m, base, Pose{}, unitCube(), top, 1e-9);
    }
    CHECK(checked > 300);
}

TEST_CASE("spanContactRegion: a face tilted 0.2°–2° onto a face gives the analytic contact region up to its zero-depth line") {
    // Cube B tilted by θ about x over cube A, its lower bottom edge sunk by d: B's bottom face is
    // below A's top (z = 0.5) for t ∈ [−0.5, t0] along its tilted side, t0 = d / sin θ − 0.5, so the
    // contact region is the rectangle x ∈ [±0.5], y ∈ [y(−0.5), y(t0)], y(t) = 0.5·sin θ + t·cos θ,
    // with depth d along its low side and 0 along its high side. The whole scene is placed in a
    // generic world frame.
    const Pose world = makePose(Vec3(3.0, -2.0, 1.5), rotationAbout(Vec3(1, 2, 3), 0.7));
    Settings spanning = allContacts();
    spanning.spanContactRegion = true;
    for (double degrees : {0.2, 0.5, 1.0, 2.0}) {
        const double theta = degrees * M_PI / 180, sink = 0.3 * std::sin(theta);
        const double height = 0.5 + 0.5 * std::cos(theta) + 0.5 * std::sin(theta) - sink;
        const Pose top = makePose(Vec3(0, 0, height), rotationAbout(Vec3::UnitX(), theta));
        const Pose poseB{world.rotation * top.rotation, world.apply(top.position)};
        const Manifold m = collide(unitCube(), world, unitCube(), poseB, spanning);
        INFO("tilt " << degrees << "°");
        REQUIRE(m.pointCount == 4);
        CHECK((m.normal - world.rotation * Vec3::UnitZ()).norm() < 1e-12);
        const double edgeT = sink / std::sin(theta) - 0.5;
        auto y = [&](double t) { return 0.5 * std::sin(theta) + t * std::cos(theta); };
        std::vector<Vec3> expected;
        for (double x : {-0.5, 0.5}) {
            expected.push_back(world.apply(Vec3(x, y(-0.5), 0.5 - sink / 2)));
            expected.push_back(world.apply(Vec3(x, y(edgeT), 0.5)));
        }
        checkTiltedRegion(m, expected, sink);
        requireOnSurfaces(m, unitCube(), world, unitCube(), poseB, 1e-9);
        // Off (the default), as dBoxBox: only the overlapping corners, the two of the deepest edge.
        const Manifold corners = collide(unitCube(), world, unitCube(), poseB, allContacts());
        REQUIRE(corners.pointCount == 2);
        for (int i = 0; i < corners.pointCount; ++i) CHECK(corners.points[i].depth == Approx(sink).margin(1e-12));
    }
}

TEST_CASE("edge on face: a cube rolled 45° about x rests its edge on a cube, clipped to the face") {
    const double sink = 0.003, shift = 0.3;
    Pose top = makePose(Vec3(shift, 0, 0.5 + std::sqrt(0.5) - sink), rotationAbout(Vec3::UnitX(), M_PI / 4));
    Manifold m = collide(unitCube(), Pose{}, unitCube(), top, allContacts());
    CHECK(m.featureA.type == FeatureType::Face);
    CHECK(m.featureB.type == FeatureType::Edge);
    CHECK((m.normal - Vec3::UnitZ()).norm() < 1e-12);
    CHECK(sameSets(positions(m), {Vec3(-0.2, 0, 0.5 - sink / 2), Vec3(0.5, 0, 0.5 - sink / 2)}, 1e-9));
    for (int i = 0; i < m.pointCount; ++i) CHECK(m.points[i].depth == Approx(sink).margin(1e-12));
}

TEST_CASE("edge on edge, crossing: one point at the crossing") {
    const double sink = 0.002, h = std::sqrt(0.5);
    Pose bottom = makePose(Vec3::Zero(), rotationAbout(Vec3::UnitY(), M_PI / 4));  // top edge along y
    Pose top = makePose(Vec3(0.1, -0.2, 2 * h - sink), rotationAbout(Vec3::UnitX(), M_PI / 4));  // bottom edge along x
    Manifold m = collide(unitCube(), bottom, unitCube(), top, allContacts());
    CHECK(m.featureA.type == FeatureType::Edge);
    CHECK(m.featureB.type == FeatureType::Edge);
    REQUIRE(m.pointCount == 1);
    CHECK((m.normal - Vec3::UnitZ()).norm() < 1e-12);
    CHECK((m.points[0].position - Vec3(0, -0.2, h - sink / 2)).norm() < 1e-9);
    CHECK(m.points[0].depth == Approx(sink).margin(1e-12));
}

TEST_CASE("edge on edge, parallel: two points spanning the overlap") {
    const double sink = 0.002, h = std::sqrt(0.5);
    Pose bottom = makePose(Vec3::Zero(), rotationAbout(Vec3::UnitX(), M_PI / 4));
    Pose top = makePose(Vec3(0.4, 0, 2 * h - sink), rotationAbout(Vec3::UnitX(), M_PI / 4));
    Manifold m = collide(unitCube(), bottom, unitCube(), top, allContacts());
    CHECK(m.featureA.type == FeatureType::Edge);
    CHECK(m.featureB.type == FeatureType::Edge);
    CHECK((m.normal - Vec3::UnitZ()).norm() < 1e-12);
    CHECK(sameSets(positions(m), {Vec3(-0.1, 0, h - sink / 2), Vec3(0.5, 0, h - sink / 2)}, 1e-9));
}

TEST_CASE("vertex on face: a cube standing on its corner touches at that corner") {
    const double sink = 0.001;
    // Rotate the (−1,−1,−1) corner to point straight down.
    Mat3 rotation = Eigen::Quaterniond::FromTwoVectors(Vec3(-1, -1, -1).normalized(), -Vec3::UnitZ()).toRotationMatrix();
    const double cornerDistance = std::sqrt(0.75);
    Pose top = makePose(Vec3(0.1, 0.2, 0.5 + cornerDistance - sink), rotation);
    Manifold m = collide(unitCube(), Pose{}, unitCube(), top, allContacts());
    CHECK(m.featureA.type == FeatureType::Face);
    CHECK(m.featureB.type == FeatureType::Vertex);
    REQUIRE(m.pointCount == 1);
    CHECK((m.points[0].position - Vec3(0.1, 0.2, 0.5 - sink / 2)).norm() < 1e-9);
    CHECK(m.points[0].depth == Approx(sink).margin(1e-12));
}

TEST_CASE("separated pairs give no contacts, exactly touching pairs give depth 0 and a unit normal") {
    std::mt19937 random(4);
    for (int trial = 0; trial < 100; ++trial) {
        Mat3 yaw = rotationAbout(Vec3::UnitZ(), std::uniform_real_distribution<double>(-3, 3)(random));
        Vec3 lateral(std::uniform_real_distribution<double>(-0.6, 0.6)(random), 0.3, 0);
        CHECK(collide(unitCube(), Pose{}, unitCube(), makePose(lateral + Vec3(0, 0, 1.0 + 1e-6), yaw)).empty());
        Pose touching = makePose(lateral + Vec3(0, 0, 1.0), yaw);
        Manifold m = collide(unitCube(), Pose{}, unitCube(), touching);
        REQUIRE_FALSE(m.empty());
        CHECK((m.normal - Vec3::UnitZ()).norm() < 1e-12);
        for (int i = 0; i < m.pointCount; ++i) CHECK(std::abs(m.points[i].depth) < 1e-12);
    }
    CHECK(collide(unitCube(), Pose{}, unitCube(), makePose(Vec3(3, 0, 0))).empty());
}

TEST_CASE("swap symmetry: collide(B, A) is collide(A, B) with the normal negated") {
    const Polytope prism = Polytope::fromPoints({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0.7),
                                                 Vec3(1, 0, 0.7), Vec3(0, 1, 0.7)});
    std::mt19937 random(77);
    std::uniform_real_distribution<double> coordinate(-0.9, 0.9);
    int compared = 0;
    for (int trial = 0; trial < 500; ++trial) {
        Pose poseA = makePose(Vec3(coordinate(random), coordinate(random), coordinate(random)), randomRotation(random));
        Pose poseB = makePose(Vec3(coordinate(random), coordinate(random), coordinate(random)), randomRotation(random));
        Manifold ab = collide(prism, poseA, unitCube(), poseB, allContacts());
        Manifold ba = collide(unitCube(), poseB, prism, poseA, allContacts());
        REQUIRE(ab.empty() == ba.empty());
        if (ab.empty()) continue;
        ++compared;
        INFO("trial " << trial);
        CHECK((ab.normal + ba.normal).norm() < 1e-9);
        CHECK(sameSets(positions(ab), positions(ba), 1e-9));
        CHECK(ab.maxDepth() == Approx(ba.maxDepth()).margin(1e-9));
        requireValidContacts(ab, prism, poseA, unitCube(), poseB, 1e-8);
    }
    CHECK(compared > 100);
}

TEST_CASE("the manifold is invariant under translation by 1e5 and uniform scale 1e-3…1e3") {
    std::mt19937 random(31);
    std::uniform_real_distribution<double> coordinate(-0.8, 0.8);
    for (int trial = 0; trial < 100; ++trial) {
        Pose poseB = makePose(Vec3(coordinate(random), coordinate(random), coordinate(random)), randomRotation(random));
        Manifold reference = collide(unitCube(), Pose{}, unitCube(), poseB, allContacts());
        if (reference.empty()) continue;
        const Vec3 shift(1e5, -1e5, 1e5);
        Manifold far = collide(unitCube(), makePose(shift), unitCube(), makePose(poseB.position + shift, poseB.rotation),
                               allContacts());
        REQUIRE(far.pointCount == reference.pointCount);
        CHECK((far.normal - reference.normal).norm() < 1e-9);
        std::vector<Vec3> shifted;
        for (const Vec3& p : positions(far)) shifted.push_back(p - shift);
        CHECK(sameSets(shifted, positions(reference), 1e-9));
        for (double scale : {1e-3, 1e3}) {
            const Polytope cube = Polytope::box(Vec3::Constant(0.5 * scale));
            Manifold scaled = collide(cube, Pose{}, cube, makePose(scale * poseB.position, poseB.rotation), allContacts());
            REQUIRE(scaled.pointCount == reference.pointCount);
            CHECK((scaled.normal - reference.normal).norm() < 1e-9);
            std::vector<Vec3> unscaled;
            for (const Vec3& p : positions(scaled)) unscaled.push_back(p / scale);
            CHECK(sameSets(unscaled, positions(reference), 1e-9));
            CHECK(scaled.maxDepth() / scale == Approx(reference.maxDepth()).margin(1e-9));
        }
    }
}

TEST_CASE("every contact of random hull pairs is valid: unit normal, finite, on both surfaces") {
    std::mt19937 random(8);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<Vec3> pa, pb;
        for (int i = 0; i < 12; ++i) pa.emplace_back(unit(random), unit(random), unit(random));
        for (int i = 0; i < 20; ++i) pb.emplace_back(unit(random), 0.5 * unit(random), unit(random));
        Polytope a = Polytope::fromPoints(pa), b = Polytope::fromPoints(pb);
        Pose poseB = makePose(1.2 * Vec3(unit(random), unit(random), unit(random)), randomRotation(random));
        Manifold m = collide(a, Pose{}, b, poseB);
        requireValidContacts(m, a, Pose{}, b, poseB, 1e-8);
        for (int i = 0; i < m.pointCount; ++i) CHECK(m.points[i].depth >= -1e-9);
        CHECK(m.pointCount <= Settings{}.maxContacts);
    }
}

TEST_CASE("normalMethod = SeparatingAxis: the normal of least overlap over every axis of a brute-force SAT") {
    // The oracle tries every face normal and every edge pair's cross product (no Gauss-map
    // pruning) on world vertices; the manifold's normal must need exactly the least translation.
    auto overlapAlong = [](const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB, const Vec3& n) {
        double highA = -INFINITY, lowB = INFINITY;
        for (const Vec3& v : a.vertices()) highA = std::max(highA, n.dot(poseA.apply(v)));
        for (const Vec3& v : b.vertices()) lowB = std::min(lowB, n.dot(poseB.apply(v)));
        return highA - lowB;
    };
    std::mt19937 random(81);
    std::uniform_real_distribution<double> unit(-1, 1);
    Settings settings = allContacts();
    settings.normalMethod = NormalMethod::SeparatingAxis;
    int compared = 0;
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<Vec3> pa, pb;
        for (int i = 0; i < 12; ++i) pa.emplace_back(unit(random), unit(random), unit(random));
        for (int i = 0; i < 20; ++i) pb.emplace_back(unit(random), 0.5 * unit(random), unit(random));
        const Polytope a = Polytope::fromPoints(pa), b = Polytope::fromPoints(pb);
        const Pose poseA = makePose(Vec3(unit(random), unit(random), unit(random)), randomRotation(random));
        const Pose poseB = makePose(poseA.position + 1.2 * Vec3(unit(random), unit(random), unit(random)),
                                    randomRotation(random));
        std::vector<Vec3> axes;
        for (const auto& f : a.faces()) axes.push_back(poseA.rotation * f.normal);
        for (const auto& f : b.faces()) axes.push_back(poseB.rotation * f.normal);
        for (const auto& ea : a.edges())
            for (const auto& eb : b.edges()) {
                const Vec3 axis = (poseA.rotation * (a.vertices()[ea.head] - a.vertices()[ea.tail]))
                                      .cross(poseB.rotation * (b.vertices()[eb.head] - b.vertices()[eb.tail]));
                if (axis.norm() > 1e-9) axes.push_back(axis.normalized());
            }
        double least = INFINITY;
        for (const Vec3& axis : axes)
            least = std::min({least, overlapAlong(a, poseA, b, poseB, axis), overlapAlong(a, poseA, b, poseB, -axis)});
        const Manifold m = collide(a, poseA, b, poseB, settings);
        INFO("trial " << trial);
        if (least < -1e-9) {  // separated along some axis
            CHECK(m.empty());
            continue;
        }
        REQUIRE_FALSE(m.empty());
        ++compared;
        CHECK(overlapAlong(a, poseA, b, poseB, m.normal) == Approx(least).margin(1e-9));
        CHECK(m.maxDepth() == Approx(least).epsilon(0.01));  // ODE's contract allows 4 %
        requireValidContacts(m, a, poseA, b, poseB, 1e-8);
    }
    CHECK(compared > 50);
}

TEST_CASE("coincident centres: a valid normal along the smallest overlap") {
    const Polytope plank = Polytope::box(Vec3(2, 1, 0.1));
    Manifold m = collide(plank, Pose{}, unitCube(), Pose{});
    REQUIRE_FALSE(m.empty());
    CHECK(std::abs(m.normal.z()) == Approx(1).margin(1e-12));  // thinnest direction
    CHECK(m.maxDepth() == Approx(0.6).margin(1e-9));
}

TEST_CASE("reduction keeps the deepest point and the largest area") {
    const Polytope base = Polytope::box(Vec3(2, 2, 0.5));
    // A cube tilted 1° about y on a large face: 4 points with distinct depths.
    Pose top = makePose(Vec3(0, 0, 0.99), rotationAbout(Vec3(1, 1, 0), 0.0174) * rotationAbout(Vec3::UnitZ(), 0.3));
    Settings full = allContacts();
    Manifold all = collide(base, Pose{}, unitCube(), top, full);
    REQUIRE(all.pointCount >= 3);
    for (int maxCount : {1, 2, 3}) {
        Settings s;
        s.maxContacts = maxCount;
        Manifold reduced = collide(base, Pose{}, unitCube(), top, s);
        REQUIRE(reduced.pointCount == std::min(maxCount, all.pointCount));
        CHECK(reduced.maxDepth() == Approx(all.maxDepth()).margin(1e-12));
    }
}

TEST_CASE("a polytope on a half-space: a resting face gives its corners, a tilted one its lowest vertex") {
    const HalfSpace ground{Vec3(0, 0, 2), 0};  // the normal is normalised
    Manifold flat = collide(unitCube(), makePose(Vec3(3, 4, 0.497), rotationAbout(Vec3::UnitZ(), 0.7)), ground);
    REQUIRE(flat.pointCount == 4);
    CHECK((flat.normal + Vec3::UnitZ()).norm() < 1e-12);  // from A into the solid
    for (int i = 0; i < 4; ++i) {
        CHECK(flat.points[i].depth == Approx(0.003).margin(1e-12));
        CHECK(flat.points[i].position.z() == Approx(-0.0015).margin(1e-12));
    }
    Manifold tilted = collide(unitCube(), makePose(Vec3(0, 0, 0.6), rotationAbout(Vec3(1, 2, 0), 0.5)), ground);
    REQUIRE(tilted.pointCount >= 1);
    CHECK(tilted.maxDepth() > 0);
    CHECK(collide(unitCube(), makePose(Vec3(0, 0, 0.51)), ground).empty());
}

TEST_CASE("spanContactRegion: a box tilted 0.2°–2° on a half-space gives its deepest edge and the zero-depth line across its face") {
    // A unit cube tilted by θ about x, its lower bottom edge sunk by d below the plane z = 0: the
    // face is below the plane for t ∈ [−0.5, t0] along its tilted side, t0 = d / sin θ − 0.5.
    const Pose world = makePose(Vec3(-1.0, 4.0, 2.0), rotationAbout(Vec3(3, -1, 2), 1.1));
    const Vec3 up = world.rotation * Vec3::UnitZ();
    const HalfSpace ground{up, up.dot(world.position)};  // the plane z = 0 of the local frame
    Settings spanning = allContacts();
    spanning.spanContactRegion = true;
    for (double degrees : {0.2, 0.5, 1.0, 2.0}) {
        const double theta = degrees * M_PI / 180, sink = 0.3 * std::sin(theta);
        const double height = 0.5 * std::cos(theta) + 0.5 * std::sin(theta) - sink;
        const Pose local = makePose(Vec3(0, 0, height), rotationAbout(Vec3::UnitX(), theta));
        const Pose pose{world.rotation * local.rotation, world.apply(local.position)};
        const Manifold m = collide(unitCube(), pose, ground, spanning);
        INFO("tilt " << degrees << "°");
        REQUIRE(m.pointCount == 4);
        CHECK((m.normal + up).norm() < 1e-12);
        const double edgeT = sink / std::sin(theta) - 0.5;
        auto y = [&](double t) { return 0.5 * std::sin(theta) + t * std::cos(theta); };
        std::vector<Vec3> expected;
        for (double x : {-0.5, 0.5}) {
            expected.push_back(world.apply(Vec3(x, y(-0.5), -sink / 2)));
            expected.push_back(world.apply(Vec3(x, y(edgeT), 0)));
        }
        checkTiltedRegion(m, expected, sink);
    }
}

TEST_CASE("bad input to collide is refused with a message") {
    Pose bad = makePose(Vec3(NAN, 0, 0));
    CHECK_THROWS_AS(collide(unitCube(), bad, unitCube(), Pose{}), InvalidInput);
    CHECK_THROWS_AS(collide(unitCube(), Pose{}, unitCube(), bad), InvalidInput);
    CHECK_THROWS_AS(collide(unitCube(), Pose{}, HalfSpace{Vec3::Zero(), 0}), InvalidInput);
    CHECK_THROWS_AS(collide(unitCube(), bad, HalfSpace{}), InvalidInput);
}

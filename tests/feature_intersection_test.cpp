// Stage 3: feature intersection in the contact plane against brute-force polygon intersection,
// and each point's own depth against the analytic heights of tilted planes.
#include "contact/feature_intersection.hpp"
#include "geometry_oracles.hpp"

#include <catch2/catch.hpp>

using namespace gdc;
using namespace gdc::testing;
using namespace gdc::detail;

namespace {

// A random convex polygon: points on a circle at sorted random angles, counter-clockwise.
std::vector<Vec2> randomConvexPolygon(std::mt19937& random, const Vec2& centre, double radius) {
    std::uniform_real_distribution<double> angle(0, 2 * M_PI);
    int count = std::uniform_int_distribution<int>(3, 9)(random);
    std::vector<double> angles;
    for (int i = 0; i < count; ++i) angles.push_back(angle(random));
    std::sort(angles.begin(), angles.end());
    std::vector<Vec2> polygon;
    for (double a : angles) polygon.push_back(centre + radius * Vec2(std::cos(a), std::sin(a)));
    return polygon;
}

// A face in the plane z = height + slope·x, wound counter-clockwise seen from +z (A's side) or −z.
FeatureGeometry face(const std::vector<Vec2>& polygon, double height, double slope, bool facingUp) {
    FeatureGeometry f;
    f.type = FeatureType::Face;
    std::vector<Vec3> loop;
    for (const Vec2& p : polygon) loop.emplace_back(p.x(), p.y(), height + slope * p.x());
    if (!facingUp) std::reverse(loop.begin(), loop.end());
    for (const Vec3& p : loop) f.points.push_back(p);
    f.planeNormal = Vec3(-slope, 0, 1).normalized() * (facingUp ? 1 : -1);
    f.planeOffset = f.planeNormal.dot(loop[0]);
    return f;
}

}  // namespace

TEST_CASE("face–face intersection equals the brute-force polygon intersection, with per-point depths") {
    std::mt19937 random(21);
    std::uniform_real_distribution<double> shift(-0.8, 0.8), slope(-0.02, 0.02);
    int nonEmpty = 0;
    for (int trial = 0; trial < 500; ++trial) {
        auto p = randomConvexPolygon(random, Vec2::Zero(), 1.0);
        auto q = randomConvexPolygon(random, Vec2(shift(random), shift(random)), 0.8);
        double slopeA = slope(random), slopeB = slope(random);
        // A's face on top of A facing up (normal +z = from A towards B); B's face facing down.
        FeatureGeometry a = face(p, 0.0, slopeA, true), b = face(q, -0.01, slopeB, false);
        LiftedPoints points = intersectFeatures(a, b, Vec3::UnitZ(), 1e-12);
        std::vector<Vec2> expected = convexPolygonIntersection(p, q);
        std::vector<Vec3> actual3, expected3;
        for (const auto& point : points) actual3.emplace_back(point.position.x(), point.position.y(), 0);
        for (const Vec2& e : expected) expected3.emplace_back(e.x(), e.y(), 0);
        if (expected.size() >= 3) {
            ++nonEmpty;
            CHECK(sameSets(actual3, expected3, 1e-9));
        }
        for (const auto& point : points) {
            double x = point.position.x();
            double heightA = slopeA * x, heightB = -0.01 + slopeB * x;
            CHECK(point.depth == Approx(heightA - heightB).margin(1e-12));
            CHECK(point.position.z() == Approx(0.5 * (heightA + heightB)).margin(1e-12));
        }
    }
    CHECK(nonEmpty > 200);
}

TEST_CASE("edge–face intersection is the edge clipped by the face") {
    FeatureGeometry a = face({Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)}, 0, 0, true);
    FeatureGeometry b;
    b.type = FeatureType::Edge;
    b.points.push_back(Vec3(-3, 0.5, -0.1));
    b.points.push_back(Vec3(0.2, 0.5, 0.02));
    LiftedPoints points = intersectFeatures(a, b, Vec3::UnitZ(), 1e-12);
    REQUIRE(points.size() == 2);
    std::vector<Vec3> actual = {points[0].position, points[1].position};
    // The edge enters the square at x = −1 (edge height −0.1 + 2/3.2·0.12) and ends at x = 0.2.
    double heightAtEntry = -0.1 + (2.0 / 3.2) * 0.12;
    CHECK(sameSets(actual, {Vec3(-1, 0.5, heightAtEntry / 2), Vec3(0.2, 0.5, 0.01)}, 1e-12));
    for (const auto& p : points) CHECK(p.depth == Approx(-2 * p.position.z()).margin(1e-12));
}

TEST_CASE("crossing edges meet in one point, parallel overlapping edges in two") {
    FeatureGeometry a, b;
    a.type = b.type = FeatureType::Edge;
    a.points.push_back(Vec3(-1, 0, 0)), a.points.push_back(Vec3(1, 0, 0));
    b.points.push_back(Vec3(0.3, -1, -0.2)), b.points.push_back(Vec3(0.3, 1, 0));
    LiftedPoints crossing = intersectFeatures(a, b, Vec3::UnitZ(), 1e-12);
    REQUIRE(crossing.size() == 1);
    CHECK((crossing[0].position - Vec3(0.3, 0, -0.05)).norm() < 1e-12);
    CHECK(crossing[0].depth == Approx(0.1));

    FeatureGeometry c;
    c.type = FeatureType::Edge;
    c.points.push_back(Vec3(0.4, 0, -0.1)), c.points.push_back(Vec3(2.4, 0, -0.1));
    LiftedPoints parallel = intersectFeatures(a, c, Vec3::UnitZ(), 1e-12);
    REQUIRE(parallel.size() == 2);
    std::vector<Vec3> actual = {parallel[0].position, parallel[1].position};
    CHECK(sameSets(actual, {Vec3(0.4, 0, -0.05), Vec3(1, 0, -0.05)}, 1e-12));
}

TEST_CASE("a vertex inside a face projects to one point, outside it to none") {
    FeatureGeometry a = face({Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)}, 0, 0, true);
    FeatureGeometry v;
    v.type = FeatureType::Vertex;
    v.points.push_back(Vec3(0.2, -0.7, -0.03));
    LiftedPoints inside = intersectFeatures(a, v, Vec3::UnitZ(), 1e-12);
    REQUIRE(inside.size() == 1);
    CHECK(inside[0].depth == Approx(0.03));
    v.points[0] = Vec3(1.2, 0, -0.03);
    CHECK(intersectFeatures(a, v, Vec3::UnitZ(), 1e-12).empty());
}

TEST_CASE("a face with a repeated corner clips as the same face without it") {
    // A zero-length edge of the clipping face gives no half-plane; skipping it once emptied the
    // buffer being read, so the whole intersection vanished.
    const std::vector<Vec2> square = {Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)};
    std::vector<Vec2> repeated = square;
    repeated.insert(repeated.begin() + 2, square[2]);  // corner (1, 1) twice
    const std::vector<Vec2> small = {Vec2(-0.5, -0.5), Vec2(0.5, -0.5), Vec2(0.5, 0.5), Vec2(-0.5, 0.5)};
    for (bool repeatedOnA : {true, false}) {
        const FeatureGeometry a = face(repeatedOnA ? repeated : small, 0.0, 0.0, true);
        const FeatureGeometry b = face(repeatedOnA ? small : repeated, -0.01, 0.0, false);
        const LiftedPoints points = intersectFeatures(a, b, Vec3::UnitZ(), 1e-9);
        REQUIRE(points.size() == 4);
        for (const LiftedPoint& p : points) {
            CHECK(std::abs(std::abs(p.position.x()) - 0.5) < 1e-12);
            CHECK(std::abs(std::abs(p.position.y()) - 0.5) < 1e-12);
            CHECK(p.depth == Approx(0.01));
        }
    }
}

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

namespace {

// The clip as it was before its closed polygons reused the first point's distance for the closing
// edge (commit "Clip: ..."), verbatim but for the buffers: the reference of the test below.
std::vector<Vec2> formerClip(const std::vector<Vec2>& subject, const std::vector<Vec2>& clip, double tolerance) {
    std::vector<Vec2> input = subject, output;
    for (std::size_t e = 0; e < clip.size() && !input.empty(); ++e) {
        const std::size_t n = input.size();
        const Vec2& a = clip[e];
        const Vec2 edge = clip[e + 1 == clip.size() ? 0 : e + 1] - a;
        const double length = edge.norm();
        if (!(length > 0)) continue;
        output.clear();
        const double slack = tolerance * length;
        auto distance = [&](const Vec2& p) { return edge.x() * (p - a).y() - edge.y() * (p - a).x(); };
        const bool closed = n >= 3;
        double dp = distance(input[0]);
        for (std::size_t i = 0; i < n; ++i) {
            const Vec2& p = input[i];
            if (dp >= -slack) output.push_back(p);
            if ((!closed && i + 1 == n) || n == 1) break;
            const Vec2& q = input[i + 1 == n ? 0 : i + 1];
            const double dq = distance(q);
            if ((dp < -slack && dq > slack) || (dp > slack && dq < -slack)) output.push_back(p + (q - p) * (dp / (dp - dq)));
            dp = dq;
        }
        input = output;
    }
    return input;
}

}  // namespace

// The clip's closed polygons reuse the first point's distance for the closing edge; it must give
// the former clip's points, in the same order, bit for bit — on 200000 pairs: random convex
// polygons, squares and rectangles turned by multiples of 45° or a little (box faces of resting
// pairs), identical polygons (every vertex on an edge), polygons sharing an edge, with repeated
// corners, segments and points as subjects, tolerance 0 or 1e-9.
TEST_CASE("The clip gives the former clip's points in the same order, bit for bit") {
    std::mt19937 random(2029);
    std::uniform_real_distribution<double> unit(0, 1);
    auto rectangle = [&](double w, double h, double turn, const Vec2& centre) {
        std::vector<Vec2> corners;
        for (const Vec2& c : {Vec2(-w, -h), Vec2(w, -h), Vec2(w, h), Vec2(-w, h)})
            corners.push_back(centre + Vec2(std::cos(turn) * c.x() - std::sin(turn) * c.y(), std::sin(turn) * c.x() + std::cos(turn) * c.y()));
        return corners;
    };
    long compared = 0, differing = 0, points = 0;
    double largest = 0;
    for (int trial = 0; trial < 200000; ++trial) {
        const int kind = trial % 6;
        std::vector<Vec2> subject, clip;
        const Vec2 offset = 0.01 * Vec2(unit(random) - 0.5, unit(random) - 0.5);
        if (kind == 0) {
            subject = randomConvexPolygon(random, offset, 0.5 + unit(random));
            clip = randomConvexPolygon(random, Vec2::Zero(), 0.5 + unit(random));
        } else if (kind == 1) {  // a quarter- or eighth-turned square on a square (the octagon)
            subject = rectangle(0.5, 0.5, (trial % 4) * 0.7853981633974483 + 1e-3 * (unit(random) - 0.5), offset);
            clip = rectangle(0.5, 0.5, 0, Vec2::Zero());
        } else if (kind == 2) {  // identical rectangles, or one shifted along an edge
            clip = rectangle(0.5, 0.2 + unit(random), 0.3 * unit(random), Vec2::Zero());
            subject = clip;
            if (trial % 4 == 2)
                for (Vec2& p : subject) p += (clip[1] - clip[0]) * 0.5;
        } else if (kind == 3) {  // repeated corners
            subject = rectangle(0.4 + unit(random), 0.4, unit(random), offset);
            clip = randomConvexPolygon(random, Vec2::Zero(), 0.7);
            subject.insert(subject.begin() + 1, subject[1]);
            clip.push_back(clip[0]);
        } else if (kind == 4) {  // a segment
            subject = {Vec2(unit(random) - 0.5, unit(random) - 0.5) * 2, Vec2(unit(random) - 0.5, unit(random) - 0.5) * 2};
            clip = rectangle(0.5, 0.5, unit(random), Vec2::Zero());
        } else {  // a point, on a corner or anywhere
            clip = rectangle(0.5, 0.3, unit(random), Vec2::Zero());
            subject = {trial % 2 ? clip[2] : Vec2(unit(random) - 0.5, unit(random) - 0.5)};
        }
        const double tolerance = trial % 2 ? 1e-9 : 0.0;
        const SmallVector<Vec2, 16> ours = clipConvexPolygon(subject.data(), static_cast<int>(subject.size()), clip.data(),
                                                             static_cast<int>(clip.size()), tolerance);
        const std::vector<Vec2> former = formerClip(subject, clip, tolerance);
        ++compared;
        bool same = ours.size() == former.size();
        for (std::size_t i = 0; same && i < former.size(); ++i) {
            largest = std::max(largest, (ours[i] - former[i]).cwiseAbs().maxCoeff());
            same = ours[i].x() == former[i].x() && ours[i].y() == former[i].y();
        }
        points += static_cast<long>(former.size());
        if (!same) {
            ++differing;
            INFO("trial " << trial << " kind " << kind);
            CHECK(same);
        }
    }
    WARN(compared << " clips compared (" << points << " points), " << differing << " differ, largest difference " << largest);
    CHECK(differing == 0);
    CHECK(largest == 0);
    CHECK(points > 500000);
}

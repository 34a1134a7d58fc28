// The persistent manifold of one pair, driven by the real libccd MPR on real polytopes: the normal
// convention, point refresh, the breaking threshold, accumulation over small rotations, the area
// rule in use, and bad input.
#include <gdcontact/tracking.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using gdc::Manifold;
using gdc::Mat3;
using gdc::Polytope;
using gdc::Pose;
using gdc::Vec2;
using gdc::Vec3;
using gdc::tracking::PersistentManifold;
using gdc::tracking::TrackedPoint;
using gdc::tracking::TrackingSettings;

namespace {

Mat3 tilt(double aboutX, double aboutY) {
    return (Eigen::AngleAxisd(aboutX, Vec3::UnitX()) * Eigen::AngleAxisd(aboutY, Vec3::UnitY()))
        .toRotationMatrix();
}

Pose at(const Vec3& position, const Mat3& rotation = Mat3::Identity()) {
    return {rotation, position};
}

// Area of the convex hull of ≤ 4 points in the xy-plane by brute force, independent of the
// library's hull: the largest |shoelace| over every triangle and every ordering of four points
// (the hull is one of these polygons; all others are subsets or self-intersecting, hence smaller).
double bruteForceArea(const std::vector<Vec2>& points) {
    auto shoelace = [](const std::vector<Vec2>& polygon) {
        double twice = 0.0;
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            const Vec2& p = polygon[i];
            const Vec2& q = polygon[(i + 1) % polygon.size()];
            twice += p.x() * q.y() - p.y() * q.x();
        }
        return 0.5 * std::abs(twice);
    };
    double best = 0.0;
    const int n = static_cast<int>(points.size());
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            for (int k = j + 1; k < n; ++k)
                best = std::max(best, shoelace({points[i], points[j], points[k]}));
    if (n == 4) {
        best = std::max(best, shoelace({points[0], points[1], points[2], points[3]}));
        best = std::max(best, shoelace({points[0], points[2], points[1], points[3]}));
        best = std::max(best, shoelace({points[0], points[1], points[3], points[2]}));
    }
    return best;
}

// A 2×2×1 slab A at the origin (top face z = 0.5) under a unit cube B whose bottom face overlaps
// the slab's top by `overlap` when level.
struct BoxOnSlab {
    Polytope slab = Polytope::box({1.0, 1.0, 0.5});
    Polytope cube = Polytope::box({0.5, 0.5, 0.5});
    double overlap = 0.005;
    Pose slabPose = at(Vec3::Zero());
    Pose cubePose(const Mat3& rotation = Mat3::Identity(), const Vec3& shift = Vec3::Zero()) const {
        return at(Vec3(0.0, 0.0, 1.0 - overlap) + shift, rotation);
    }
};

// The cube rocks towards each corner of its bottom face in turn, returning level in between, as a
// resting box does under a solver's jitter. Returns the manifold of the final level step.
Manifold rockOverEveryCorner(PersistentManifold& manifold, const BoxOnSlab& scene, double angle) {
    const double tilts[][2] = {{0, 0},           {angle, angle}, {0, 0},          {angle, -angle}, {0, 0},
                               {-angle, -angle}, {0, 0},         {-angle, angle}, {0, 0}};
    Manifold last;
    for (const auto& t : tilts)
        last = manifold.update(scene.slab, scene.slabPose, scene.cube, scene.cubePose(tilt(t[0], t[1])));
    return last;
}

}  // namespace

TEST_CASE("MPR's direction maps onto the core's normal from A towards B", "[tracking]") {
    const Polytope cube = Polytope::box({0.5, 0.5, 0.5});
    PersistentManifold manifold;
    // B 0.9 above A: the cubes overlap by 0.1 along z, and B must move up (+z) to separate.
    const Manifold result = manifold.update(cube, at(Vec3::Zero()), cube, at(Vec3(0.0, 0.0, 0.9)));
    REQUIRE(result.pointCount == 1);
    CHECK(result.normal.isApprox(Vec3::UnitZ(), 1e-9));
    CHECK(result.points[0].depth == Approx(0.1).margin(1e-9));
    // Midway between A's top face (z = 0.5) and B's bottom face (z = 0.4).
    CHECK(result.points[0].position.z() == Approx(0.45).margin(1e-9));

    PersistentManifold swapped;
    const Manifold mirrored = swapped.update(cube, at(Vec3(0.0, 0.0, 0.9)), cube, at(Vec3::Zero()));
    REQUIRE(mirrored.pointCount == 1);
    CHECK(mirrored.normal.isApprox(-Vec3::UnitZ(), 1e-9));
    CHECK(mirrored.points[0].depth == Approx(0.1).margin(1e-9));
}

TEST_CASE("a new point's anchors lie on both surfaces inside the overlap", "[tracking]") {
    BoxOnSlab scene;
    scene.overlap = 0.05;
    PersistentManifold manifold;
    // The cube shifted 0.3 sideways: the overlap region is x ∈ [−0.2, 0.8], y ∈ [−0.5, 0.5].
    manifold.update(scene.slab, scene.slabPose, scene.cube, scene.cubePose(Mat3::Identity(), {0.3, 0, 0}));
    REQUIRE(manifold.pointCount() == 1);
    const TrackedPoint& point = manifold.point(0);
    CHECK(point.anchorOnA.z() == Approx(0.5).margin(1e-9));   // the slab's top face
    CHECK(point.anchorOnB.z() == Approx(-0.5).margin(1e-9));  // the cube's bottom face
    CHECK(point.depth == Approx(0.05).margin(1e-9));
    CHECK(point.worldOnA.x() >= -0.2 - 1e-9);
    CHECK(point.worldOnA.x() <= 0.8 + 1e-9);
    CHECK(std::abs(point.worldOnA.y()) <= 0.5 + 1e-9);
    CHECK((point.worldOnA - point.worldOnB).cross(Vec3::UnitZ()).norm() < 1e-9);
}

TEST_CASE("separated and exactly touching pairs give no points and no NaN", "[tracking]") {
    const Polytope cube = Polytope::box({0.5, 0.5, 0.5});
    for (double height : {1.0, 1.0 + 1e-12, 1.1, 5.0}) {
        PersistentManifold manifold;
        const Manifold result = manifold.update(cube, at(Vec3::Zero()), cube, at(Vec3(0.0, 0.0, height)));
        CHECK(result.pointCount == 0);
        CHECK(manifold.pointCount() == 0);
        CHECK(result.normal.allFinite());
    }
}

TEST_CASE("a box rocking on a slab accumulates four points spanning the face", "[tracking]") {
    BoxOnSlab scene;
    PersistentManifold manifold;
    const Manifold result = rockOverEveryCorner(manifold, scene, 0.005);

    REQUIRE(result.pointCount == 4);
    CHECK(result.normal.isApprox(Vec3::UnitZ(), 1e-9));
    std::vector<Vec2> footprint;
    for (int i = 0; i < result.pointCount; ++i) {
        // Level again: every point's depth is the overlap, and it sits midway in the overlap slab.
        CHECK(result.points[i].depth == Approx(scene.overlap).margin(1e-9));
        CHECK(result.points[i].position.z() == Approx(0.5 - scene.overlap / 2).margin(1e-9));
        footprint.emplace_back(result.points[i].position.x(), result.points[i].position.y());
    }
    // One point near each corner of the 1×1 contact face: distinct quadrants, and a support
    // polygon covering most of the face. (For this aligned pair MPR's point lands next to the
    // lowest corner of each tilt; with other tie-breaking it may land elsewhere on the face, see
    // the half-space test.)
    int quadrants = 0;
    for (const Vec2& p : footprint) quadrants |= 1 << ((p.x() > 0 ? 1 : 0) + (p.y() > 0 ? 2 : 0));
    CHECK(quadrants == 0b1111);
    CHECK(bruteForceArea(footprint) > 0.9);
}

TEST_CASE("stored points are refreshed from the bodies' new poses", "[tracking]") {
    BoxOnSlab scene;
    PersistentManifold manifold;
    rockOverEveryCorner(manifold, scene, 0.005);
    REQUIRE(manifold.pointCount() == 4);

    // Slide the cube 0.01 along x (below the 0.02 breaking threshold): no point breaks; every
    // point MPR did not refresh keeps its anchors, so its world anchor on B moves with the cube
    // by exactly the slide while its anchor on A stays put, and its depth is unchanged.
    std::vector<TrackedPoint> before;
    for (int i = 0; i < manifold.pointCount(); ++i) before.push_back(manifold.point(i));
    const Vec3 slide(0.01, 0.0, 0.0);
    const Pose slid = scene.cubePose(Mat3::Identity(), slide);
    manifold.update(scene.slab, scene.slabPose, scene.cube, slid);
    CHECK(manifold.lastUpdate().dropped == 0);
    REQUIRE(manifold.pointCount() == 4);
    int refreshedOnly = 0;
    for (int i = 0; i < manifold.pointCount(); ++i) {
        const TrackedPoint& point = manifold.point(i);
        if (point.age == 0) continue;  // this one was just replaced by MPR's new point
        ++refreshedOnly;
        const auto same = std::find_if(before.begin(), before.end(), [&](const TrackedPoint& old) {
            return old.anchorOnA.isApprox(point.anchorOnA, 1e-12);
        });
        REQUIRE(same != before.end());
        CHECK(point.age == same->age + 1);
        CHECK(point.worldOnA.isApprox(same->worldOnA, 1e-12));
        CHECK((point.worldOnB - same->worldOnB - slide).norm() < 1e-12);
        CHECK(point.worldOnB.isApprox(slid.apply(point.anchorOnB), 1e-12));
        CHECK(point.depth == Approx(scene.overlap).margin(1e-12));
    }
    CHECK(refreshedOnly >= 3);
}

TEST_CASE("a point slid beyond the breaking threshold is dropped", "[tracking]") {
    BoxOnSlab scene;
    TrackingSettings settings;
    settings.breakingThreshold = 0.02;
    for (double slide : {0.015, 0.025}) {
        PersistentManifold manifold(settings);
        rockOverEveryCorner(manifold, scene, 0.005);
        REQUIRE(manifold.pointCount() == 4);
        manifold.update(scene.slab, scene.slabPose, scene.cube,
                        scene.cubePose(Mat3::Identity(), Vec3(0.0, slide, 0.0)));
        if (slide < settings.breakingThreshold) {
            CHECK(manifold.lastUpdate().dropped == 0);
            CHECK(manifold.pointCount() == 4);
        } else {
            // Every stored point drifted by 0.025 > 0.02: all four break; only MPR's new one is left.
            CHECK(manifold.lastUpdate().dropped == 4);
            REQUIRE(manifold.pointCount() == 1);
            CHECK(manifold.point(0).age == 0);
        }
    }
}

TEST_CASE("separation along the normal keeps points up to the threshold, then drops them all", "[tracking]") {
    BoxOnSlab scene;
    TrackingSettings settings;
    settings.speculativeMargin = 0.012;
    PersistentManifold manifold(settings);
    rockOverEveryCorner(manifold, scene, 0.005);
    REQUIRE(manifold.pointCount() == 4);

    // Lifted to a gap of 0.01: MPR sees no overlap, the normal is carried over, the points stay
    // stored with depth −0.01 and are reported as speculative points (margin 0.012).
    const double gap = 0.01;
    Manifold lifted = manifold.update(scene.slab, scene.slabPose, scene.cube,
                                      scene.cubePose(Mat3::Identity(), Vec3(0, 0, scene.overlap + gap)));
    CHECK_FALSE(manifold.lastUpdate().mprFoundContact);
    CHECK(manifold.pointCount() == 4);
    REQUIRE(lifted.pointCount == 4);
    CHECK(lifted.normal.isApprox(Vec3::UnitZ(), 1e-12));
    for (int i = 0; i < lifted.pointCount; ++i) CHECK(lifted.points[i].depth == Approx(-gap).margin(1e-12));

    // With the default margin 0 the same state is stored but not reported.
    PersistentManifold strict;
    rockOverEveryCorner(strict, scene, 0.005);
    lifted = strict.update(scene.slab, scene.slabPose, scene.cube,
                           scene.cubePose(Mat3::Identity(), Vec3(0, 0, scene.overlap + gap)));
    CHECK(strict.pointCount() == 4);
    CHECK(lifted.pointCount == 0);

    // Lifted further, to a gap of 0.03 > the 0.02 threshold: every point is dropped.
    lifted = manifold.update(scene.slab, scene.slabPose, scene.cube,
                             scene.cubePose(Mat3::Identity(), Vec3(0, 0, scene.overlap + 0.03)));
    CHECK(manifold.lastUpdate().dropped == 4);
    CHECK(manifold.pointCount() == 0);
    CHECK(lifted.pointCount == 0);
    CHECK_FALSE(manifold.hasNormal());
}

TEST_CASE("when full, the deepest point survives and the kept set has the largest area", "[tracking]") {
    // A 12-sided prism rocking and sliding on the slab at random: MPR's point wanders around the
    // rim (a box would only ever offer its 4 corners, which merge). Whenever the new point replaces
    // a stored one: the stored point that was deepest after the refresh is still there, and the
    // kept four span at least the area of every other admissible choice (brute-force oracle).
    BoxOnSlab scene;
    scene.overlap = 0.01;
    std::vector<Vec3> rim;
    for (int i = 0; i < 12; ++i) {
        const double around = 2.0 * M_PI * i / 12;
        for (double z : {-0.5, 0.5}) rim.emplace_back(0.5 * std::cos(around), 0.5 * std::sin(around), z);
    }
    scene.cube = Polytope::fromPoints(rim);
    PersistentManifold manifold;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> angle(-0.006, 0.006), shift(-0.002, 0.002);
    Vec3 position = Vec3::Zero();
    int replacements = 0;
    for (int step = 0; step < 400; ++step) {
        position += Vec3(shift(random), shift(random), 0.0);
        const Pose cubePose = scene.cubePose(tilt(angle(random), angle(random)), position);
        std::vector<TrackedPoint> before;
        for (int i = 0; i < manifold.pointCount(); ++i) before.push_back(manifold.point(i));

        const Manifold result = manifold.update(scene.slab, scene.slabPose, scene.cube, cubePose);
        REQUIRE(result.pointCount <= 4);
        const auto& report = manifold.lastUpdate();
        if (!report.replacedExisting) continue;
        ++replacements;
        REQUIRE(report.dropped == 0);  // so `before` is exactly the refreshed set, in order
        REQUIRE(before.size() == 4);

        // Refreshed depths of the four previous points, along this step's normal.
        const Vec3 normal = manifold.normal();
        std::vector<double> depths;
        std::vector<Vec2> inPlane;  // the normal is +z within MPR's tolerance here
        REQUIRE(normal.z() > 0.999);
        for (const TrackedPoint& old : before) {
            const Vec3 onA = scene.slabPose.apply(old.anchorOnA);
            const Vec3 onB = cubePose.apply(old.anchorOnB);
            depths.push_back((onA - onB).dot(normal));
            const Vec3 middle = 0.5 * (onA + onB);
            inPlane.emplace_back(middle.x(), middle.y());
        }
        const TrackedPoint& fresh = manifold.point(report.added);
        CHECK(fresh.age == 0);
        const Vec3 freshMiddle = 0.5 * (fresh.worldOnA + fresh.worldOnB);
        const Vec2 candidate(freshMiddle.x(), freshMiddle.y());

        const auto deepest = std::max_element(depths.begin(), depths.end()) - depths.begin();
        if (depths[deepest] > fresh.depth) CHECK(report.added != deepest);

        double bestAlternative = 0.0;
        for (int removed = 0; removed < 4; ++removed) {
            if (removed == deepest && depths[deepest] > fresh.depth) continue;
            std::vector<Vec2> kept{candidate};
            for (int i = 0; i < 4; ++i)
                if (i != removed) kept.push_back(inPlane[i]);
            bestAlternative = std::max(bestAlternative, bruteForceArea(kept));
        }
        std::vector<Vec2> chosen{candidate};
        for (int i = 0; i < 4; ++i)
            if (i != report.added) chosen.push_back(inPlane[i]);
        CHECK(bruteForceArea(chosen) >= bestAlternative - 1e-6);
    }
    CHECK(replacements > 10);  // the property was exercised, not vacuously true
}

TEST_CASE("the manifold is the same far from the origin", "[tracking]") {
    BoxOnSlab scene;
    PersistentManifold nearOrigin, farAway;
    // 100 000 km out, where one unit in the last place of a coordinate is 1.5e-8: computed in
    // absolute coordinates, the depths would be off by that much.
    const Vec3 offset(1e8, -2e8, 3e7);
    const Pose farSlab = at(offset);
    Manifold near, far;
    const double tilts[][2] = {{0, 0}, {0.004, 0.004}, {0, 0}, {-0.004, -0.004}, {0, 0}};
    for (const auto& t : tilts) {
        const Pose cube = scene.cubePose(tilt(t[0], t[1]));
        near = nearOrigin.update(scene.slab, scene.slabPose, scene.cube, cube);
        far = farAway.update(scene.slab, farSlab, scene.cube, at(cube.position + offset, cube.rotation));
    }
    REQUIRE(near.pointCount == far.pointCount);
    REQUIRE(near.pointCount >= 2);
    CHECK(far.normal.isApprox(near.normal, 1e-9));
    for (int i = 0; i < near.pointCount; ++i) {
        CHECK((far.points[i].position - offset - near.points[i].position).norm() < 1e-7);  // a few ulps
        CHECK(far.points[i].depth == Approx(near.points[i].depth).margin(1e-12));
    }
}

TEST_CASE("swapBodies mirrors the state", "[tracking]") {
    BoxOnSlab scene;
    PersistentManifold manifold;
    rockOverEveryCorner(manifold, scene, 0.005);
    const int count = manifold.pointCount();
    manifold.swapBodies();
    // Now A is the cube and B the slab: the same contact, seen from the other side.
    const Manifold result = manifold.update(scene.cube, scene.cubePose(), scene.slab, scene.slabPose);
    CHECK(result.normal.isApprox(-Vec3::UnitZ(), 1e-9));
    CHECK(manifold.lastUpdate().dropped == 0);
    REQUIRE(result.pointCount == count);
    for (int i = 0; i < result.pointCount; ++i)
        CHECK(result.points[i].depth == Approx(scene.overlap).margin(1e-9));
}

TEST_CASE("a half-space: normal, depth and position of a cube sunk into it", "[tracking]") {
    const Polytope cube = Polytope::box({0.5, 0.5, 0.5});
    PersistentManifold manifold;
    // Ground z ≤ 0; the cube's bottom face at z = −0.01.
    const Manifold result =
        manifold.update(cube, at(Vec3(0.0, 0.0, 0.49)), gdc::HalfSpace{Vec3::UnitZ(), 0.0});
    REQUIRE(result.pointCount == 1);
    CHECK(result.normal.isApprox(-Vec3::UnitZ(), 1e-9));  // from A into the solid, as the core
    CHECK(result.points[0].depth == Approx(0.01).margin(1e-9));
    CHECK(result.points[0].position.z() == Approx(-0.005).margin(1e-9));
    CHECK(std::abs(result.points[0].position.x()) <= 0.5 + 1e-9);

    PersistentManifold above;
    CHECK(above.update(cube, at(Vec3(0.0, 0.0, 0.51)), gdc::HalfSpace{Vec3::UnitZ(), 0.0}).pointCount == 0);
}

TEST_CASE("a half-space in any orientation: normal, depths and points on the contact face", "[tracking]") {
    // The rocking sequence against the plane z = 0.5, and the whole scene rotated and moved. MPR's
    // points depend on how the support functions break ties (the stand-in box is oriented by the
    // plane, not by the cube), so the two runs may pick different points of the face; what must
    // hold in both is exact: four points, each with depth = overlap, midway in the overlap layer
    // and inside the cube's bottom face.
    const Polytope cube = Polytope::box({0.5, 0.5, 0.5});
    const double overlap = 0.005, angle = 0.005;
    const double tilts[][2] = {{0, 0},           {angle, angle}, {0, 0},          {angle, -angle}, {0, 0},
                               {-angle, -angle}, {0, 0},         {-angle, angle}, {0, 0}};
    const Mat3 turn = (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).toRotationMatrix();
    for (const Mat3& rotation : {Mat3(Mat3::Identity()), turn}) {
        const Vec3 move = rotation.isIdentity() ? Vec3::Zero() : Vec3(3.0, -1.0, 2.0);
        const Vec3 up = rotation * Vec3::UnitZ();
        const gdc::HalfSpace ground{up, 0.5 + up.dot(move)};
        PersistentManifold manifold;
        Manifold result;
        Pose cubePose;
        for (const auto& t : tilts) {
            cubePose = at(rotation * Vec3(0.0, 0.0, 1.0 - overlap) + move, rotation * tilt(t[0], t[1]));
            result = manifold.update(cube, cubePose, ground);
        }
        REQUIRE(result.pointCount == 4);
        CHECK(result.normal.isApprox(-up, 1e-9));
        for (int i = 0; i < 4; ++i) {
            CHECK(result.points[i].depth == Approx(overlap).margin(1e-9));
            const Vec3 local = cubePose.applyInverse(result.points[i].position);
            CHECK(local.z() == Approx(-0.5 + overlap / 2).margin(1e-9));
            CHECK(std::abs(local.x()) <= 0.5 + 1e-9);
            CHECK(std::abs(local.y()) <= 0.5 + 1e-9);
        }
    }
}

TEST_CASE("a half-space's anchors are fixed to the plane, not to its stand-in", "[tracking]") {
    // Sliding the cube 0.025 across the ground must break every stored point: the ground's anchors
    // stay where they were, although the box standing in for the ground follows the cube.
    const Polytope cube = Polytope::box({0.5, 0.5, 0.5});
    const gdc::HalfSpace ground{Vec3::UnitZ(), 0.5};
    const double angle = 0.005;
    const double tilts[][2] = {{0, 0}, {angle, angle}, {0, 0}, {-angle, -angle}, {0, 0}};
    PersistentManifold manifold;
    for (const auto& t : tilts) manifold.update(cube, at(Vec3(0.0, 0.0, 0.995), tilt(t[0], t[1])), ground);
    REQUIRE(manifold.pointCount() >= 2);
    const int stored = manifold.pointCount();
    manifold.update(cube, at(Vec3(0.025, 0.0, 0.995)), ground);
    CHECK(manifold.lastUpdate().dropped == stored);
    CHECK(manifold.pointCount() == 1);
}

TEST_CASE("a still contact does not pile up duplicate points", "[tracking]") {
    // MPR returns the same point every step for a pair at rest; it must refresh the stored point,
    // not add copies of it (so a still box has one point: the baseline's known weakness).
    BoxOnSlab scene;
    PersistentManifold manifold;
    for (int step = 0; step < 10; ++step)
        manifold.update(scene.slab, scene.slabPose, scene.cube, scene.cubePose());
    CHECK(manifold.pointCount() == 1);
    CHECK(manifold.lastUpdate().mergedInto == 0);
}

TEST_CASE("random hulls moving through each other: anchors on the surfaces, depths bounded", "[tracking]") {
    // Oracles by brute force over the vertices and faces: every stored anchor lies on its body's
    // surface, so no point can be deeper than the overlap of the two shapes' projections onto the
    // normal, max over A of n·a − min over B of n·b. Never a NaN, a non-unit normal or a negative
    // reported depth.
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto randomHull = [&] {
        std::vector<Vec3> points;
        for (int i = 0; i < 14; ++i)
            points.emplace_back(0.5 * unit(random), 0.4 * unit(random), 0.3 * unit(random));
        return Polytope::fromPoints(points);
    };
    auto randomRotation = [&] {
        return Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random))
            .normalized()
            .toRotationMatrix();
    };
    auto surfaceGap = [](const Polytope& shape, const Vec3& local) {  // 0 on the surface
        double worst = -1e300;
        for (const auto& face : shape.faces()) worst = std::max(worst, face.normal.dot(local) - face.offset);
        return worst;
    };
    auto extreme = [](const Polytope& shape, const Pose& pose, const Vec3& direction) {
        double best = -1e300;
        for (const Vec3& v : shape.vertices()) best = std::max(best, direction.dot(pose.apply(v)));
        return best;
    };
    int pointsChecked = 0;
    for (int pair = 0; pair < 40; ++pair) {
        const Polytope a = randomHull(), b = randomHull();
        PersistentManifold manifold;
        Pose poseA = at(Vec3(unit(random), unit(random), unit(random)), randomRotation());
        Vec3 heading = Vec3(unit(random), unit(random), unit(random)).normalized();
        for (int step = 0; step < 30; ++step) {
            // B passes through A along a line, turning a little each step.
            const double along = -0.8 + 1.6 * step / 29.0;
            const Pose poseB = at(poseA.position + along * heading,
                                  Eigen::AngleAxisd(0.05 * step, heading).toRotationMatrix());
            const Manifold result = manifold.update(a, poseA, b, poseB);
            REQUIRE(result.pointCount <= 4);
            if (manifold.hasNormal()) {
                REQUIRE(result.normal.allFinite());
                CHECK(result.normal.norm() == Approx(1.0).margin(1e-12));
            }
            const double projectionOverlap =
                extreme(a, poseA, result.normal) + extreme(b, poseB, -result.normal);
            for (int i = 0; i < result.pointCount; ++i) {
                REQUIRE(result.points[i].position.allFinite());
                CHECK(result.points[i].depth >= 0.0);
                CHECK(result.points[i].depth <= projectionOverlap + 1e-9);
            }
            for (int i = 0; i < manifold.pointCount(); ++i) {
                CHECK(std::abs(surfaceGap(a, manifold.point(i).anchorOnA)) < 1e-9);
                CHECK(std::abs(surfaceGap(b, manifold.point(i).anchorOnB)) < 1e-9);
                ++pointsChecked;
            }
        }
    }
    CHECK(pointsChecked > 500);
}

TEST_CASE("bad input is rejected where it enters", "[tracking]") {
    const Polytope cube = Polytope::box({0.5, 0.5, 0.5});
    PersistentManifold manifold;
    Pose broken = at(Vec3(0, 0, 0.9));
    broken.position.x() = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(manifold.update(cube, at(Vec3::Zero()), cube, broken), gdc::InvalidInput);
    CHECK_THROWS_AS(manifold.update(cube, broken, cube, at(Vec3::Zero())), gdc::InvalidInput);
    CHECK_THROWS_AS(manifold.point(0), gdc::InvalidInput);
    CHECK_THROWS_AS(manifold.update(cube, broken, gdc::HalfSpace{}), gdc::InvalidInput);
    CHECK_THROWS_AS(manifold.update(cube, at(Vec3::Zero()), gdc::HalfSpace{Vec3::Zero(), 0.0}),
                    gdc::InvalidInput);
    CHECK_THROWS_AS(manifold.update(cube, at(Vec3::Zero()), gdc::HalfSpace{Vec3::UnitZ(), NAN}),
                    gdc::InvalidInput);

    auto rejects = [](auto change) {
        TrackingSettings settings;
        change(settings);
        CHECK_THROWS_AS(PersistentManifold(settings), gdc::InvalidInput);
    };
    rejects([](TrackingSettings& s) { s.breakingThreshold = 0.0; });
    rejects([](TrackingSettings& s) { s.breakingThreshold = std::numeric_limits<double>::infinity(); });
    rejects([](TrackingSettings& s) { s.maxPoints = 0; });
    rejects([](TrackingSettings& s) { s.maxPoints = gdc::kMaxManifoldPoints + 1; });
    rejects([](TrackingSettings& s) { s.mergeDistance = -1.0; });
    rejects([](TrackingSettings& s) { s.speculativeMargin = std::numeric_limits<double>::quiet_NaN(); });
    rejects([](TrackingSettings& s) { s.mprRelativeTolerance = 0.0; });
    rejects([](TrackingSettings& s) { s.maxMprIterations = 0; });
}

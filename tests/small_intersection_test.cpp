// The box pair's closed forms against the general computations, on 10^5 random poses of each kind
// of box pair (box_poses.hpp): stage 3's intersection in fixed arrays (intersectSmallFeatures)
// against the growable intersectFeatures every other pair uses — the same points, in the same
// order, to rounding — and the early out's closed-form overlap of two boxes along the line of
// centres against the support searches it spares.
#include "box_poses.hpp"
#include "contact/collide_general.hpp"
#include "shapes/box_shape.hpp"
#include "geometry/minkowski.hpp"
#include "sanitizer_scale.hpp"
#include "touching_poses.hpp"

#include <cmath>
#include <cstdio>
#include <random>

using namespace gdc;
using namespace gdc::testing;

namespace {

constexpr int kPosesPerKind = scaledForSanitizers(100000);

}  // namespace

// Stage 3 in both storages (the fixed arrays of intersectSmallFeatures, the growable vectors of
// intersectFeatures): every lifted point the same within 1e-12 of the size, with the same pieces,
// in the same order. The features and normals
// are the box pair's own — the growth-distance normal and each face normal of a selected face
// (refineNormal's candidates) — on poses of every kind of box pair, the tolerances' minimum depth
// and the region spanned or not.
TEST_CASE("stage 3: the fixed arrays and the growable storage lift the same points (10^5 poses per kind)") {
    const char* names[] = {"resting face", "face near the tolerance", "edge-edge", "vertex-face", "deep", "nearly touching",
                           "scattered"};
    for (int k = 0; k < int(BoxPoseKind::Count); ++k) {
        std::mt19937 random(20261201 + k);
        std::uniform_real_distribution<double> unit(0, 1);
        int mismatches = 0, calls = 0, points = 0, spanned = 0;
        double largest = 0;
        for (int trial = 0; trial < kPosesPerKind; ++trial) {
            const Vec3 halfA = randomHalfExtents(random), halfB = randomHalfExtents(random);
            const Polytope a = Polytope::box(halfA), b = Polytope::box(halfB);
            const double size = a.radius() + b.radius();
            const Settings settings = randomBoxPairSettings(random, size);
            const Pose bInA = boxPoseOfKind(BoxPoseKind(k), halfA, halfB, settings.angularTolerance, 0.8, random);
            const detail::BoxGrowth growth =
                detail::boxGrowth(halfA, halfB, bInA.rotation, bInA.position, bInA.position.norm(), size);
            if (!growth.valid) continue;
            const detail::AngularTolerance angular(settings.angularTolerance);
            const Feature featureA = detail::selectBoxFeature(growth.normal, angular);
            const Feature featureB = detail::selectBoxFeature(bInA.rotation.transpose() * -growth.normal, angular);
            const detail::BoxFeature geometryA = detail::boxFeature(a, featureA, nullptr);
            const detail::BoxFeature geometryB = detail::boxFeature(b, featureB, &bInA);
            const detail::FeatureView viewA = detail::view(geometryA), viewB = detail::view(geometryB);
            Vec3 normals[3] = {growth.normal};
            int normalCount = 1;
            if (viewA.type == FeatureType::Face) normals[normalCount++] = viewA.planeNormal;
            if (viewB.type == FeatureType::Face) normals[normalCount++] = -viewB.planeNormal;
            const double tolerance = 1e-9 * size;
            for (int n = 0; n < normalCount; ++n) {
                const bool span = n == 0 ? settings.spanContactRegion : unit(random) < 0.5;
                detail::LiftedPoints fast, growable;
                detail::intersectSmallFeatures(viewA, viewB, normals[n], tolerance, -settings.margin, span, fast);
                detail::intersectFeatures(viewA, viewB, normals[n], tolerance, -settings.margin, span, growable);
                ++calls;
                spanned += span;
                points += static_cast<int>(growable.size());
                bool same = fast.size() == growable.size();
                for (std::size_t i = 0; same && i < growable.size(); ++i) {
                    const detail::LiftedPoint &x = fast[i], &y = growable[i];
                    const double difference = std::max({(x.position - y.position).norm() / size,
                                                        std::abs(x.depth - y.depth) / size,
                                                        (x.planar - y.planar).norm() / size});
                    largest = std::max(largest, difference);
                    same = same && difference <= 1e-12 && x.pieceA == y.pieceA && x.pieceB == y.pieceB;
                }
                mismatches += !same;
            }
        }
        std::printf("stage 3, fixed arrays vs growable storage, %s: %d intersections (%d with the region spanned), %d "
                    "points; largest difference %.3g of the size; %d differ\n",
                    names[k], calls, spanned, points, largest, mismatches);
        INFO(names[k]);
        CHECK(mismatches == 0);
        CHECK(calls >= kPosesPerKind / 2);
        if (k != int(BoxPoseKind::Scattered)) CHECK(points > calls / 4);  // most intersections meet
    }
}

TEST_CASE("box-box early out: the closed-form overlap along the line of centres decides as the support searches (10^5 poses)") {
    std::mt19937 random(20261128);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int separated = 0, nearLimit = 0;
    for (int i = 0; i < kPosesPerKind; ++i) {
        const Polytope a = Polytope::box(randomHalfExtents(random)), b = Polytope::box(randomHalfExtents(random));
        auto [poseA, poseB] = randomTouchingPoses(random, a, b, i % 2 == 0, 0.03);
        const double size = a.radius() + b.radius();
        const Vec3 apart = poseB.position - poseA.position;
        if (i % 3 == 0 && apart.norm() > 0) poseB.position += apart.normalized() * (0.2 * unit(random) * size);
        const double margin = i % 5 == 0 ? 0.01 * size : 0.0;
        const double tolerance = 1e-9 * size;
        Pose bInA = poseA.relative(poseB);
        if (i % 4 == 3) {
            // Right at the limit: B moved along the line of centres (which keeps its direction) until
            // its overlap along it is the limit give or take 1e-16 to 1e-8 of the size, both sides,
            // so the closed form's band of 1e-12 is entered and left.
            const detail::MinkowskiDifference before(a, b, bInA, Settings{}.bruteForceSupportLimit);
            const Vec3 d = (before.centreB - before.centreA).normalized();
            const double offBy = (unit(random) < 0.5 ? -1 : 1) * std::pow(10.0, -16 + 8 * unit(random)) * size;
            bInA.position += d * (before.overlapAlong(d) + margin + tolerance - offBy);
        }
        const detail::MinkowskiDifference pair(a, b, bInA, Settings{}.bruteForceSupportLimit);
        const Vec3 offset = pair.centreB - pair.centreA;
        const double distance = offset.norm();
        const bool closedForm = detail::separatedByEarlyOut(pair, offset, distance, size, margin, tolerance);
        // The searches it spares, written out: bounding spheres, then the overlap along the centre line.
        const bool searched =
            distance > size + margin || (distance > 0 && pair.overlapAlong(offset / distance) < -margin - tolerance);
        INFO("pose " << i);
        REQUIRE(closedForm == searched);
        separated += searched;
        if (distance > 0 && std::abs(pair.overlapAlong(offset / distance) + margin + tolerance) < 1e-11 * size) ++nearLimit;
    }
    std::printf("box-box early out, closed form vs support searches: %d poses, %d separated, %d within 1e-11 of the "
                "size of the limit; the same decision on all\n",
                kPosesPerKind, separated, nearLimit);
    CHECK(separated > kPosesPerKind / 100);
    CHECK(nearLimit > kPosesPerKind / 40);  // the band where the support searches decide is exercised
}

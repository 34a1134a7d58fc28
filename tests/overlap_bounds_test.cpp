// The general pipeline's overlap bounds (collide.cpp: the bodies' inradii about their centroids bound
// every overlap from below) skip checks — the overhang check over the faces around the features —
// only where those checks could not change the answer. Proven here the way every faster path is:
// the pipeline with the bounds and the pipeline that runs every check (collideGeneral's
// boundFaceOverlaps = false), on 10^5 random poses of each hull pair type, give the same manifold.
#include "contact/collide_general.hpp"
#include "contact_checks.hpp"
#include "sanitizer_scale.hpp"
#include "touching_poses.hpp"

#include <cstdio>

using namespace gdc;
using namespace gdc::testing;

namespace {

constexpr int kPoses = scaledForSanitizers(100000);

void compareOn(const char* name, const Polytope& a, const Polytope& b, int count, std::uint32_t seed) {
    std::mt19937 random(seed);
    int touching = 0;
    double largestDifference = 0;  // positions, depths and normal, relative to the pair's size
    for (int i = 0; i < count; ++i) {
        // Resting poses (the bound's case), and any orientation; overlaps from a near miss to deep.
        const bool resting = i % 2 == 0;
        const auto [poseA, poseB] = randomTouchingPoses(random, a, b, resting, i % 3 == 0 ? 0.2 : 0.03);
        Settings settings;
        settings.maxContacts = 1 + i % kMaxManifoldPoints;
        settings.margin = i % 5 == 0 ? 0.01 * a.radius() : 0.0;
        settings.spanContactRegion = i % 7 == 0;
        const Manifold bounded = detail::collideGeneral(a, poseA, b, poseB, settings);
        const Manifold reference = detail::collideGeneral(a, poseA, b, poseB, settings, false, true,
                                                          /*boundFaceOverlaps=*/false);
        INFO(name << " pose " << i);
        REQUIRE(bounded.pointCount == reference.pointCount);
        if (bounded.empty()) continue;
        ++touching;
        REQUIRE(bounded.featureA.type == reference.featureA.type);
        REQUIRE(bounded.featureA.index == reference.featureA.index);
        REQUIRE(bounded.featureB.type == reference.featureB.type);
        REQUIRE(bounded.featureB.index == reference.featureB.index);
        const double size = a.radius() + b.radius();
        double difference = (bounded.normal - reference.normal).norm();
        for (int k = 0; k < bounded.pointCount; ++k) {
            difference = std::max(difference, (bounded.points[k].position - reference.points[k].position).norm() / size);
            difference = std::max(difference, std::abs(bounded.points[k].depth - reference.points[k].depth) / size);
        }
        largestDifference = std::max(largestDifference, difference);
        REQUIRE(difference == 0);  // the skipped checks change nothing, not even a rounding
    }
    std::printf("overlap bounds, %s: %d poses (%d touching), largest difference %.3g x size\n", name, count, touching,
                largestDifference);
    CHECK(touching > count * 3 / 4);  // the poses exercise contact, not just separation
}

}  // namespace

TEST_CASE("overlap bounds: skipping what they settle never changes a manifold (10^5 poses per hull pair type)") {
    std::mt19937 random(23);
    const Polytope cubeHull = Polytope::fromPoints(boxCorners(Vec3(0.5, 0.5, 0.5)));
    const Polytope plankHull = Polytope::fromPoints(boxCorners(Vec3(1.5, 0.3, 0.1)));
    const Polytope box = Polytope::box(Vec3(0.4, 0.25, 0.6));
    const Polytope rock = Polytope::fromPoints(randomCloud(random, 24, Vec3(0.5, 0.4, 0.3)));
    const Polytope pebble = Polytope::fromPoints(randomCloud(random, 10, Vec3(0.2, 0.2, 0.2)));
    const Polytope boulder = Polytope::fromPoints(randomCloud(random, 300, Vec3(0.6, 0.6, 0.6)));
    compareOn("8-vertex hull pair", cubeHull, cubeHull, kPoses, 1);
    compareOn("cube hull on plank hull (overhangs)", cubeHull, plankHull, kPoses, 2);
    compareOn("box and cube hull", box, cubeHull, kPoses, 3);
    compareOn("cube hull and box", cubeHull, box, kPoses, 4);
    compareOn("box pair (general path)", box, box, kPoses, 5);
    compareOn("random hulls (24 and 10 points)", rock, pebble, kPoses, 6);
    compareOn("large hull (300 points) and box", boulder, box, kPoses, 7);
}

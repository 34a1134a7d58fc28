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

// The pipeline with the bounds against the one that runs every check: equal to the bit.
void compareOn(const char* name, const Polytope& a, const Polytope& b, std::uint32_t seed) {
    requireSameManifolds(
        "overlap bounds", name, a, b, kPoses, seed, 0.03, /*deepEveryThird=*/true, /*tolerance=*/0.0,
        [](auto&&... args) { return detail::collideGeneral(args...); },
        [](const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB, const Settings& settings) {
            return detail::collideGeneral(a, poseA, b, poseB, settings, false, true, /*boundFaceOverlaps=*/false);
        });
}

}  // namespace

TEST_CASE("overlap bounds: skipping what they settle never changes a manifold (10^5 poses per hull pair type)") {
    std::mt19937 random(23);
    const ProvingHulls hulls(random);
    compareOn("8-vertex hull pair", hulls.cubeHull, hulls.cubeHull, 1);
    compareOn("cube hull on plank hull (overhangs)", hulls.cubeHull, hulls.plankHull, 2);
    compareOn("box and cube hull", hulls.box, hulls.cubeHull, 3);
    compareOn("cube hull and box", hulls.cubeHull, hulls.box, 4);
    compareOn("box pair (general path)", hulls.box, hulls.box, 5);
    compareOn("random hulls (24 and 10 points)", hulls.rock, hulls.pebble, 6);
    compareOn("large hull (300 points) and box", hulls.boulder, hulls.box, 7);
}

// What the hull enumeration finds on its way (hull_gauge.hpp's HullGaugeCarry: the overlaps along
// the faces it evaluated, its exit facet and that facet's features) is carried to the later stages
// of the general pipeline — refineNormal's overlaps, stage 1's overlap and support searches, the
// depth certificate — instead of searching again. The carried overlaps round differently from the
// support searches', so the proof is the one issue 23 asks of a faster path that rounds differently:
// the pipeline with the carry and the one without (collideGeneral's carryHullGauge = false), on 10^5
// random poses of each pair type that reaches the enumeration, give the same manifold shape (count,
// features, points in the same order), with normal, depths and points within 1e-12 of the pair's
// size; the largest difference is printed.
#include "contact/collide_general.hpp"
#include "geometry/hull_gauge.hpp"
#include "sanitizer_scale.hpp"
#include "touching_poses.hpp"

#include <cstdio>

using namespace gdc;
using namespace gdc::testing;

namespace {

constexpr int kPoses = scaledForSanitizers(100000);

void compareOn(const char* name, const Polytope& a, const Polytope& b, std::uint32_t seed) {
    requireSameManifolds(
        "hull enumeration carried", name, a, b, kPoses, seed, 0.03, /*deepEveryThird=*/true, /*tolerance=*/1e-12,
        [](auto&&... args) { return detail::collideGeneral(args...); },
        [](const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB, const Settings& settings) {
            return detail::collideGeneral(a, poseA, b, poseB, settings, false, true, true, /*carryHullGauge=*/false);
        });
}

}  // namespace

TEST_CASE("hull carry: the proving pairs reach the enumeration") {
    std::mt19937 random(23);
    const ProvingHulls hulls(random);
    CHECK(detail::hullGaugeApplies(hulls.cubeHull, hulls.cubeHull));
    CHECK(detail::hullGaugeApplies(hulls.cubeHull, hulls.plankHull));
    CHECK(detail::hullGaugeApplies(hulls.box, hulls.cubeHull));
    CHECK(detail::hullGaugeApplies(hulls.cubeHull, hulls.box));
    CHECK(detail::hullGaugeApplies(hulls.pebble, hulls.cubeHull));
}

TEST_CASE("hull carry: carrying the enumeration's findings never changes a manifold's shape (10^5 poses per pair type)") {
    std::mt19937 random(23);
    const ProvingHulls hulls(random);
    compareOn("8-vertex hull pair", hulls.cubeHull, hulls.cubeHull, 11);
    compareOn("cube hull on plank hull (overhangs)", hulls.cubeHull, hulls.plankHull, 12);
    compareOn("box and cube hull", hulls.box, hulls.cubeHull, 13);
    compareOn("cube hull and box", hulls.cubeHull, hulls.box, 14);
    compareOn("small random hull and cube hull", hulls.pebble, hulls.cubeHull, 15);
    compareOn("random hulls (24 and 10 points)", hulls.rock, hulls.pebble, 16);
}

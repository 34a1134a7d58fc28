// The general pipeline's answers against ODE's contact contract (touching_poses.hpp,
// requireContactContract), on 10^5 random touching poses of each pair type: points on each body,
// and the deepest depth within [0.96, 1.04] of the exit of the ray along the normal through A − B.
// What it guards: the shortcuts that decide without a search — the depth confirmation's
// certificates (collide.cpp, penetrationCertified and the enumeration's exit facet), the overlap
// bounds that skip the overhang check, the hull enumeration's carry — must never leave the deepest
// contact short of the penetration, nor a point off its body. The pairs: hull pairs whose faces
// overhang (cube on plank), boxes through the general path, random and large hulls, and
// near-spheres whose faces have caps.
#include "general_pipeline.hpp"
#include "geometry/growth_distance.hpp"
#include "contact_checks.hpp"
#include "sanitizer_scale.hpp"
#include "touching_poses.hpp"

#include <cstdio>

using namespace gdc;
using namespace gdc::testing;

namespace {

constexpr int kPoses = scaledForSanitizers(100000);

void checkOn(const char* name, const Polytope& a, const Polytope& b, std::uint32_t seed, bool deepEveryThird) {
    requireContactContract("contact contract, general pipeline", name, a, b, kPoses, seed, 0.03, deepEveryThird,
                           [](auto&&... args) { return generalManifold(args...); });
}

}  // namespace

TEST_CASE("contact contract: the general pipeline's points lie on their bodies and carry the penetration (10^5 poses per pair type)") {
    std::mt19937 random(11);
    const ProvingHulls hulls(random);
    // Near-spheres fine enough that a face's neighbours lie within the angular tolerance: caps.
    std::vector<Vec3> sphere;
    for (int i = 0; i < 4096; ++i) {
        const double z = 1 - 2 * (i + 0.5) / 4096, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
        sphere.emplace_back(0.5 * r * std::cos(phi), 0.5 * r * std::sin(phi), 0.5 * z);
    }
    const Polytope nearSphere = Polytope::fromPoints(sphere);
    checkOn("8-vertex hull pair", hulls.cubeHull, hulls.cubeHull, 1, true);
    checkOn("cube hull on plank hull (overhangs)", hulls.cubeHull, hulls.plankHull, 2, true);
    checkOn("box and cube hull", hulls.box, hulls.cubeHull, 3, true);
    checkOn("cube hull and box", hulls.cubeHull, hulls.box, 4, true);
    checkOn("box pair (general path)", hulls.box, hulls.box, 5, true);
    checkOn("random hulls (24 and 10 points)", hulls.rock, hulls.pebble, 6, true);
    checkOn("large hull (300 points) and box", hulls.boulder, hulls.box, 7, true);
    checkOn("near-spheres (4096 vertices, caps)", nearSphere, nearSphere, 8, false);
}

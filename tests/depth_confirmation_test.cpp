// The depth confirmation's certificate (collide.cpp, penetrationCertified) skips the ray cast along
// the normal only where that cast could not have added a point. Proven here the way every faster
// path is: the pipeline with the certificate and the pipeline that always casts, on 10^5 random
// poses of each pair type, give the same manifold.
#include "contact/collide_general.hpp"
#include "geometry/growth_distance.hpp"
#include "contact_checks.hpp"
#include "sanitizer_scale.hpp"
#include "touching_poses.hpp"

#include <cstdio>

using namespace gdc;
using namespace gdc::testing;

namespace {

constexpr int kPoses = scaledForSanitizers(100000);

// The pipeline with the certificate against the one that always casts: equal within 1e-12.
void compareOn(const char* name, const Polytope& a, const Polytope& b, std::uint32_t seed) {
    requireSameManifolds(
        "depth confirmation certificate", name, a, b, kPoses, seed, 0.03, /*deepEveryThird=*/false,
        /*tolerance=*/1e-12, [](auto&&... args) { return detail::collideGeneral(args...); },
        [](const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB, const Settings& settings) {
            return detail::collideGeneral(a, poseA, b, poseB, settings, /*alwaysConfirmDepth=*/true);
        });
}

}  // namespace

TEST_CASE("depth confirmation: the certificate never changes a manifold (10^5 poses per pair type)") {
    std::mt19937 random(11);
    const ProvingHulls hulls(random);
    // Near-spheres fine enough that a face's neighbours lie within the angular tolerance: caps.
    std::vector<Vec3> sphere;
    for (int i = 0; i < 4096; ++i) {
        const double z = 1 - 2 * (i + 0.5) / 4096, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
        sphere.emplace_back(0.5 * r * std::cos(phi), 0.5 * r * std::sin(phi), 0.5 * z);
    }
    const Polytope nearSphere = Polytope::fromPoints(sphere);
    compareOn("8-vertex hull pair", hulls.cubeHull, hulls.cubeHull, 1);
    compareOn("hull on plank hull", hulls.cubeHull, hulls.plankHull, 2);
    compareOn("box pair (general path)", hulls.box, hulls.box, 3);
    compareOn("random hulls (24 and 10 points)", hulls.rock, hulls.pebble, 4);
    compareOn("large hull (300 points) and box", hulls.boulder, hulls.box, 5);
    compareOn("near-spheres (4096 vertices, caps)", nearSphere, nearSphere, 6);
}

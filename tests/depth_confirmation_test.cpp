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

struct Comparison {
    int poses = 0;
    int touching = 0;
    double largestDifference = 0;  // positions, depths and normal, relative to the pair's size
};

void compareOn(const char* name, const Polytope& a, const Polytope& b, int count, std::uint32_t seed) {
    std::mt19937 random(seed);
    Comparison result;
    for (int i = 0; i < count; ++i) {
        const bool resting = i % 2 == 0;
        const auto [poseA, poseB] = randomTouchingPoses(random, a, b, resting, 0.03);
        Settings settings;
        settings.maxContacts = 1 + i % kMaxManifoldPoints;
        settings.margin = i % 5 == 0 ? 0.01 * a.radius() : 0.0;
        settings.spanContactRegion = i % 7 == 0;
        const Manifold fast = detail::collideGeneral(a, poseA, b, poseB, settings);
        const Manifold reference = detail::collideGeneral(a, poseA, b, poseB, settings, /*alwaysConfirmDepth=*/true);
        INFO(name << " pose " << i);
        REQUIRE(fast.pointCount == reference.pointCount);
        ++result.poses;
        if (fast.empty()) continue;
        ++result.touching;
        REQUIRE(fast.featureA.type == reference.featureA.type);
        REQUIRE(fast.featureB.type == reference.featureB.type);
        const double size = a.radius() + b.radius();
        double difference = (fast.normal - reference.normal).norm();
        for (int k = 0; k < fast.pointCount; ++k) {
            difference = std::max(difference, (fast.points[k].position - reference.points[k].position).norm() / size);
            difference = std::max(difference, std::abs(fast.points[k].depth - reference.points[k].depth) / size);
        }
        result.largestDifference = std::max(result.largestDifference, difference);
        REQUIRE(difference <= 1e-12);
    }
    std::printf("depth confirmation certificate, %s: %d poses (%d touching), largest difference %.3g x size\n", name,
                result.poses, result.touching, result.largestDifference);
    CHECK(result.touching > count * 3 / 4);  // the poses exercise contact, not just separation
}

}  // namespace

TEST_CASE("depth confirmation: the certificate never changes a manifold (10^5 poses per pair type)") {
    std::mt19937 random(11);
    const Polytope cubeHull = Polytope::fromPoints(boxCorners(Vec3(0.5, 0.5, 0.5)));
    const Polytope plankHull = Polytope::fromPoints(boxCorners(Vec3(1.5, 0.3, 0.1)));
    const Polytope box = Polytope::box(Vec3(0.4, 0.25, 0.6));
    const Polytope rock = Polytope::fromPoints(randomCloud(random, 24, Vec3(0.5, 0.4, 0.3)));
    const Polytope pebble = Polytope::fromPoints(randomCloud(random, 10, Vec3(0.2, 0.2, 0.2)));
    const Polytope boulder = Polytope::fromPoints(randomCloud(random, 300, Vec3(0.6, 0.6, 0.6)));
    // Near-spheres fine enough that a face's neighbours lie within the angular tolerance: caps.
    std::vector<Vec3> sphere;
    for (int i = 0; i < 4096; ++i) {
        const double z = 1 - 2 * (i + 0.5) / 4096, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
        sphere.emplace_back(0.5 * r * std::cos(phi), 0.5 * r * std::sin(phi), 0.5 * z);
    }
    const Polytope nearSphere = Polytope::fromPoints(sphere);
    compareOn("8-vertex hull pair", cubeHull, cubeHull, kPoses, 1);
    compareOn("hull on plank hull", cubeHull, plankHull, kPoses, 2);
    compareOn("box pair (general path)", box, box, kPoses, 3);
    compareOn("random hulls (24 and 10 points)", rock, pebble, kPoses, 4);
    compareOn("large hull (300 points) and box", boulder, box, kPoses, 5);
    compareOn("near-spheres (4096 vertices, caps)", nearSphere, nearSphere, kPoses, 6);
}

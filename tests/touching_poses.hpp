// Random hulls and random poses of two polytopes that nearly touch, shared by the pipeline's
// property tests (contact_contract_test, hull_carry_test, hull_gauge_test), and the check of ODE's
// contact contract they run on each answer.
#pragma once

#include "geometry/growth_distance.hpp"
#include "geometry_oracles.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdint>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace gdc::testing {

/// `count` points of a Gaussian cloud, scaled per axis by `scale`.
inline std::vector<Vec3> randomCloud(std::mt19937& random, int count, const Vec3& scale) {
    std::normal_distribution<double> gaussian;
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i)
        points.push_back(Vec3(gaussian(random), gaussian(random), gaussian(random)).cwiseProduct(scale));
    return points;
}

/// The eight corners of the box of half extents `half` about the origin (as points for a hull).
inline std::vector<Vec3> boxCorners(const Vec3& half) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.emplace_back((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(), (i & 4) ? half.z() : -half.z());
    return corners;
}

/// B placed against A along a direction d (A's frame): from a start where they overlap, B is moved
/// along d to where they just touch (the exact separation along d, by the ray cast), then back by
/// an overlap drawn from [−0.002, `maxOverlap`] of the pair's size, so the pair overlaps slightly,
/// touches, or misses by a little. Resting poses: d near A's up axis, small tilts, B shifted
/// sideways; the others: any orientation and direction. Returns the world poses of A and B.
inline std::pair<Pose, Pose> randomTouchingPoses(std::mt19937& random, const Polytope& a, const Polytope& b,
                                                 bool resting, double maxOverlap) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0), overlap(-0.002, maxOverlap);
    const Pose poseA{resting ? rotationAbout(Vec3(unit(random), unit(random), unit(random)), 0.01 * unit(random))
                             : randomRotation(random),
                     Vec3(unit(random), unit(random), unit(random))};
    const Mat3 rotationB = resting ? rotationAbout(Vec3(unit(random), unit(random), unit(random)), 0.01 * unit(random)) *
                                         rotationAbout(Vec3::UnitZ(), M_PI * unit(random))
                                   : randomRotation(random);
    const Vec3 direction = resting ? Vec3(0.001 * unit(random), 0.001 * unit(random), 1.0).normalized()
                                   : Vec3(unit(random), unit(random), unit(random)).normalized();
    const Vec3 start = resting ? Vec3(Vec3(0.3 * unit(random), 0.3 * unit(random), 0.0) * a.radius()) : Vec3(Vec3::Zero());
    Pose bInA{rotationB, a.centroid() + start - rotationB * b.centroid()};
    const detail::SeparationAlong apart = detail::separationAlong(a, b, bInA, direction, Settings{});
    if (apart.valid) bInA.position += (apart.distance - overlap(random) * (a.radius() + b.radius())) * direction;
    return {poseA, Pose{poseA.rotation * bInA.rotation, poseA.apply(bInA.position)}};
}

/// The hulls the pipeline's property tests run on: a cube and a plank as hulls (their faces
/// overhang each other), a box, two random clouds (24 and 10 points) and a 300-point hull.
struct ProvingHulls {
    explicit ProvingHulls(std::mt19937& random)
        : cubeHull(Polytope::fromPoints(boxCorners(Vec3(0.5, 0.5, 0.5)))),
          plankHull(Polytope::fromPoints(boxCorners(Vec3(1.5, 0.3, 0.1)))),
          box(Polytope::box(Vec3(0.4, 0.25, 0.6))),
          rock(Polytope::fromPoints(randomCloud(random, 24, Vec3(0.5, 0.4, 0.3)))),
          pebble(Polytope::fromPoints(randomCloud(random, 10, Vec3(0.2, 0.2, 0.2)))),
          boulder(Polytope::fromPoints(randomCloud(random, 300, Vec3(0.6, 0.6, 0.6)))) {}
    Polytope cubeHull, plankHull, box, rock, pebble, boulder;
};

/// Runs `collide` — (a, poseA, b, poseB, settings) → Manifold — on `count` random touching poses of
/// a and b (every other one resting; overlaps up to `maxOverlap` of the pair's size, and up to 0.2
/// on every third pose where `deepEveryThird`), with the budget, margin and spanning varied per
/// pose, and checks each answer against measures of its own (ODE's contact contract):
/// - the normal is a finite unit vector, every depth and position finite;
/// - each contact's point on A (position + depth/2·normal) lies in A and its point on B
///   (position − depth/2·normal) in B, within 1e-9 of the pair's size;
/// - the deepest depth carries the penetration along the normal: within [0.96, 1.04] of the exit
///   distance of the ray along n through A − B (separationAlong, the GJK ray cast, to its own
///   tolerance) — moving B by 0.96·depth still touches, by 1.04·depth separates.
/// Prints the largest relative depth error under `what` and `name`; checks that most poses touch.
template <class Collide>
void requireContactContract(const char* what, const char* name, const Polytope& a, const Polytope& b, int count,
                            std::uint32_t seed, double maxOverlap, bool deepEveryThird, Collide collide) {
    std::mt19937 random(seed);
    int touching = 0;
    double largestDepthError = 0, largestOutside = 0;
    const double size = a.radius() + b.radius();
    auto outside = [](const Polytope& shape, const Pose& pose, const Vec3& world) {
        const Vec3 local = pose.applyInverse(world);
        double worst = -INFINITY;
        for (const Polytope::Face& face : shape.faces()) worst = std::max(worst, face.normal.dot(local) - face.offset);
        return worst;
    };
    for (int i = 0; i < count; ++i) {
        const bool resting = i % 2 == 0;
        const auto [poseA, poseB] =
            randomTouchingPoses(random, a, b, resting, deepEveryThird && i % 3 == 0 ? 0.2 : maxOverlap);
        Settings settings;
        settings.maxContacts = 1 + i % kMaxManifoldPoints;
        settings.margin = i % 5 == 0 ? 0.01 * a.radius() : 0.0;
        settings.spanContactRegion = i % 7 == 0;
        const Manifold m = collide(a, poseA, b, poseB, settings);
        INFO(name << " pose " << i);
        if (m.empty()) continue;
        ++touching;
        REQUIRE(m.normal.allFinite());
        REQUIRE(std::abs(m.normal.norm() - 1) <= 1e-12);
        for (int k = 0; k < m.pointCount; ++k) {
            const ContactPoint& p = m.points[k];
            REQUIRE(p.position.allFinite());
            REQUIRE(std::isfinite(p.depth));
            const double out = std::max(outside(a, poseA, p.position + 0.5 * p.depth * m.normal),
                                        outside(b, poseB, p.position - 0.5 * p.depth * m.normal));
            largestOutside = std::max(largestOutside, out / size);
            REQUIRE(out <= 1e-9 * size);
        }
        const Vec3 normalInA = poseA.rotation.transpose() * m.normal;
        const detail::SeparationAlong exit = detail::separationAlong(a, b, poseA.relative(poseB), normalInA, settings);
        if (!exit.valid || exit.distance < 0) continue;  // apart along n: a speculative contact
        const double deepest = m.maxDepth(), slack = 1e-9 * size + 2 * settings.rayCastTolerance * size;
        largestDepthError = std::max(largestDepthError, std::abs(deepest - exit.distance) / std::max(exit.distance, 1e-300));
        REQUIRE(deepest >= 0.96 * exit.distance - slack);
        REQUIRE(deepest <= 1.04 * exit.distance + slack);
    }
    std::printf("%s, %s: %d poses (%d touching), deepest depth within %.3g of the exit along n, points at most "
                "%.3g x size outside their body\n",
                what, name, count, touching, largestDepthError, largestOutside);
    CHECK(touching > count * 3 / 4);  // the poses exercise contact, not just separation
}

}  // namespace gdc::testing

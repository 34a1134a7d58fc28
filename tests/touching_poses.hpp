// Random hulls and random poses of two polytopes that nearly touch, shared by the tests that prove
// a faster path equal to the one it replaces (depth_confirmation_test, hull_gauge_test).
#pragma once

#include "geometry/growth_distance.hpp"
#include "geometry_oracles.hpp"

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

}  // namespace gdc::testing

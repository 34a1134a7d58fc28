// Independent oracles and shape/pose generators for the robustness tests. Written differently from
// the library on purpose: the overlap oracle is a brute-force separating-axis test over every face
// normal and every pair of edge directions (exact for convex polytopes), never a GJK.
#pragma once

#include "geometry_oracles.hpp"  // tests/: rotationAbout, randomRotation

#include <gdcontact/gdcontact.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace gdc::robustness {

using gdc::testing::randomRotation;
using gdc::testing::rotationAbout;

inline Vec3 randomDirection(std::mt19937_64& random) {
    std::normal_distribution<double> gauss;
    return Vec3(gauss(random), gauss(random), gauss(random)).normalized();
}

/// Corners of an axis-aligned box of half extents h (vertex i has the signs of bits x:1, y:2, z:4).
inline std::vector<Vec3> boxCorners(const Vec3& h) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    return corners;
}

/// Evenly spread points on the unit sphere (Fibonacci lattice).
inline std::vector<Vec3> fibonacciSphere(int count) {
    std::vector<Vec3> points;
    const double golden = M_PI * (3 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        const double z = 1 - 2 * (i + 0.5) / count, r = std::sqrt(1 - z * z);
        points.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
    }
    return points;
}

/// A posed polytope's vertices in the world frame.
inline std::vector<Vec3> worldVertices(const Polytope& polytope, const Pose& pose) {
    std::vector<Vec3> out;
    for (const Vec3& v : polytope.vertices()) out.push_back(pose.apply(v));
    return out;
}

/// Every candidate separating axis of two posed convex polytopes, world frame: the face normals
/// of both and the cross product of every edge of A with every edge of B. A (near-)parallel edge
/// pair is skipped: it is no separating direction of its own (the face axes cover it), and its
/// rounding would decide wrongly.
inline std::vector<Vec3> separatingAxes(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB) {
    std::vector<Vec3> axes;
    for (const auto& face : a.faces()) axes.push_back(poseA.rotation * face.normal);
    for (const auto& face : b.faces()) axes.push_back(poseB.rotation * face.normal);
    std::vector<Vec3> edgesB;
    for (const auto& eb : b.edges())
        edgesB.push_back(poseB.rotation * (b.vertices()[eb.head] - b.vertices()[eb.tail]).normalized());
    for (const auto& ea : a.edges()) {
        const Vec3 da = poseA.rotation * (a.vertices()[ea.head] - a.vertices()[ea.tail]).normalized();
        for (const Vec3& db : edgesB) {
            const Vec3 axis = da.cross(db);
            if (axis.norm() >= 1e-9) axes.push_back(axis.normalized());
        }
    }
    return axes;
}

/// Extent [min, max] of a point set along an axis.
inline std::pair<double, double> extentAlong(const std::vector<Vec3>& points, const Vec3& axis) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec3& p : points) {
        const double x = axis.dot(p);
        lo = std::min(lo, x), hi = std::max(hi, x);
    }
    return {lo, hi};
}

/// Exact separating-axis oracle for two posed convex polytopes: the smallest overlap over every
/// candidate axis in both senses — the penetration depth (minimum translation distance) when
/// positive, minus the gap along the best axis when negative. `bestAxis` receives that axis,
/// pointing from A towards B (moving B along it by the overlap separates them).
inline double satOverlap(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                         Vec3* bestAxis = nullptr) {
    const std::vector<Vec3> va = worldVertices(a, poseA), vb = worldVertices(b, poseB);
    double best = INFINITY;
    Vec3 bestDirection = Vec3::UnitZ();
    for (const Vec3& axis : separatingAxes(a, poseA, b, poseB)) {
        const auto [loA, hiA] = extentAlong(va, axis);
        const auto [loB, hiB] = extentAlong(vb, axis);
        if (hiA - loB < best) best = hiA - loB, bestDirection = axis;    // B beyond A along +axis
        if (hiB - loA < best) best = hiB - loA, bestDirection = -axis;   // B beyond A along −axis
    }
    if (bestAxis) *bestAxis = bestDirection;
    return best;
}

/// Overlap of the posed polytopes along one unit axis (from A towards B): > 0 when their
/// projections overlap. Not a separation test on its own (see satOverlap).
inline double overlapAlong(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB, const Vec3& axis) {
    return extentAlong(worldVertices(a, poseA), axis).second - extentAlong(worldVertices(b, poseB), axis).first;
}

/// Signed distance from a world point to a posed polytope's surface (> 0 outside), by its planes.
inline double signedDistance(const Polytope& polytope, const Pose& pose, const Vec3& world) {
    const Vec3 local = pose.applyInverse(world);
    double distance = -INFINITY;
    for (const auto& face : polytope.faces()) distance = std::max(distance, face.normal.dot(local) - face.offset);
    return distance;
}

/// A random convex polytope of one of several characters: a cloud, a box-like hull (general path),
/// a flat plate, a needle, a rounded hull, or a Polytope::box (closed-form path). About unit size.
inline Polytope randomHull(std::mt19937_64& random) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> kind(0, 5);
    std::vector<Vec3> points;
    switch (kind(random)) {
        case 5:
            return Polytope::box(Vec3(0.1 + 0.9 * std::abs(unit(random)), 0.1 + 0.9 * std::abs(unit(random)),
                                      0.1 + 0.9 * std::abs(unit(random))));
        case 0:  // a cloud of 6–16 points
            for (int i = 0, n = 6 + static_cast<int>(random() % 11); i < n; ++i)
                points.emplace_back(unit(random), unit(random), unit(random));
            break;
        case 1: {  // a box-like hull of random proportions
            Vec3 h(0.2 + 0.8 * std::abs(unit(random)), 0.2 + 0.8 * std::abs(unit(random)), 0.2 + 0.8 * std::abs(unit(random)));
            points = boxCorners(h);
            break;
        }
        case 2: {  // a plate 20:1 (hexagonal)
            for (int i = 0; i < 6; ++i)
                for (double z : {-0.05, 0.05}) points.emplace_back(std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), z);
            break;
        }
        case 3: {  // a needle 1:1:20 with a square section
            for (double x : {-0.05, 0.05})
                for (double y : {-0.05, 0.05})
                    for (double z : {-1.0, 1.0}) points.emplace_back(x, y, z);
            break;
        }
        default:  // a rounded hull of 24 points on an ellipsoid
            for (const Vec3& p : fibonacciSphere(24)) points.push_back(p.cwiseProduct(Vec3(1.0, 0.7, 0.5)));
            break;
    }
    const Mat3 rotation = randomRotation(random);
    for (Vec3& p : points) p = rotation * p;
    return Polytope::fromPoints(points);
}

/// A random overlapping pose pair, as physics produces them: random orientations; B approaches A
/// along a random direction, stopped where the oracle says they first touch, then pushed further
/// in by `pushFraction` of the pair's size (sum of radii). The touching distance is exact: with B's
/// centroid at A's, every axis's overlap falls linearly as B moves out, and the pair separates
/// when the first of them reaches zero.
inline void randomContactPose(std::mt19937_64& random, const Polytope& a, const Polytope& b, double pushFraction,
                              Pose& poseA, Pose& poseB) {
    std::normal_distribution<double> gauss;
    poseA = Pose{randomRotation(random), Vec3(gauss(random), gauss(random), gauss(random))};
    poseB.rotation = randomRotation(random);
    const Vec3 direction = randomDirection(random);
    const Vec3 centreA = poseA.apply(a.centroid());
    poseB.position = centreA - poseB.rotation * b.centroid();
    const std::vector<Vec3> va = worldVertices(a, poseA), vb = worldVertices(b, poseB);
    double touching = INFINITY;
    for (const Vec3& axis : separatingAxes(a, poseA, b, poseB)) {
        const auto [loA, hiA] = extentAlong(va, axis);
        const auto [loB, hiB] = extentAlong(vb, axis);
        const double speed = axis.dot(direction);  // d(overlap along −axis)/dt for +axis, and so on
        if (speed > 0) touching = std::min(touching, (hiA - loB) / speed);
        if (speed < 0) touching = std::min(touching, (hiB - loA) / -speed);
    }
    const double size = a.radius() + b.radius();
    poseB.position += std::max(0.0, touching - pushFraction * size) * direction;
}

/// An integer from the environment (for the long modes), or `fallback`.
inline long environmentCount(const char* name, long fallback) {
    const char* text = std::getenv(name);
    if (!text || !*text) return fallback;
    return std::max(1L, std::strtol(text, nullptr, 10));
}

/// GDCONTACT_ROBUSTNESS_REPORT=1 prints the figures the tests measure (docs/robustness.md quotes
/// them); otherwise silent.
inline void report(const std::string& scene, const std::string& what) {
    if (environmentCount("GDCONTACT_ROBUSTNESS_REPORT", 0) > 0) std::printf("%-34s %s\n", scene.c_str(), what.c_str());
}

}  // namespace gdc::robustness

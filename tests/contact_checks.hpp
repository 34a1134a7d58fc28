// The invariants every contact of every test must satisfy.
#pragma once

#include "geometry_oracles.hpp"

#include <catch2/catch.hpp>

namespace gdc::testing {

/// Unit finite normal, finite points and depths; no point deeper than the pair's overlap along
/// the normal (the translation that separates them); every point within half its depth of both
/// shapes (it lies midway between a point of A and a point of B that are `depth` apart).
inline void requireValidContacts(const Manifold& m, const Polytope& a, const Pose& poseA, const Polytope& b,
                                 const Pose& poseB, double tolerance) {
    if (m.empty()) return;
    REQUIRE(m.normal.allFinite());
    REQUIRE(m.normal.norm() == Approx(1.0).margin(1e-12));
    double overlap = -INFINITY;  // max over A of n·x − min over B of n·x, by brute force
    double maxA = -INFINITY, minB = INFINITY;
    for (const Vec3& v : a.vertices()) maxA = std::max(maxA, m.normal.dot(poseA.apply(v)));
    for (const Vec3& v : b.vertices()) minB = std::min(minB, m.normal.dot(poseB.apply(v)));
    overlap = maxA - minB;
    for (int i = 0; i < m.pointCount; ++i) {
        const ContactPoint& p = m.points[i];
        REQUIRE(p.position.allFinite());
        REQUIRE(std::isfinite(p.depth));
        CHECK(p.depth <= overlap + tolerance);
        CHECK(signedDistance(a, poseA, p.position) <= 0.5 * std::abs(p.depth) + tolerance);
        CHECK(signedDistance(b, poseB, p.position) <= 0.5 * std::abs(p.depth) + tolerance);
    }
}

/// For contacts from a feature intersection: each point's two surface points lie on A and B.
inline void requireOnSurfaces(const Manifold& m, const Polytope& a, const Pose& poseA, const Polytope& b,
                              const Pose& poseB, double tolerance) {
    for (int i = 0; i < m.pointCount; ++i) {
        const ContactPoint& p = m.points[i];
        CHECK(std::abs(signedDistance(a, poseA, p.position + 0.5 * p.depth * m.normal)) <= tolerance);
        CHECK(std::abs(signedDistance(b, poseB, p.position - 0.5 * p.depth * m.normal)) <= tolerance);
    }
}

}  // namespace gdc::testing

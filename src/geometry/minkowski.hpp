// Support mappings of a pair of polytopes, with B placed in A's frame. Working in A's frame keeps
// precision when both bodies are far from the world origin.
#pragma once

#include "geometry/growth_distance.hpp"

namespace gdc::detail {

/// Overlaps of the pair that an earlier stage of the query already has, each along a direction as
/// the later stage will spell it (compared bit for bit): collide.cpp's refineNormal and overhang
/// check read them instead of searching the supports again (the general hooks fill them from the
/// hull enumeration, hull_gauge.hpp's HullGaugeCarry, and hand them on as a value: the hooks'
/// knownOverlaps()).
struct KnownOverlaps {
    static constexpr int kCapacity = 2;
    int count = 0;
    Vec3 directions[kCapacity];
    double overlaps[kCapacity];
    void add(const Vec3& direction, double overlap) {
        if (count < kCapacity) directions[count] = direction, overlaps[count++] = overlap;
    }
};

struct MinkowskiDifference {
    const Polytope& a;
    const Polytope& b;
    Pose bInA;
    int bruteForceLimit;
    Vec3 centreA;  // contraction points (centroids), in A's frame
    Vec3 centreB;

    MinkowskiDifference(const Polytope& a_, const Polytope& b_, const Pose& bInA_, int limit)
        : a(a_), b(b_), bInA(bInA_), bruteForceLimit(limit), centreA(a_.centroid()),
          centreB(bInA_.apply(b_.centroid())) {}

    // The queries of one contact query ask for nearby directions (GJK's converging v, faces
    // around the normal), so each support search of a large hull starts its climb at the
    // previous answer. A local object per query: no state is shared between queries.
    mutable int lastSupportA = -1;
    mutable int lastSupportB = -1;

    int supportA(const Vec3& direction) const {
        return lastSupportA = a.supportVertex(direction, bruteForceLimit, lastSupportA);
    }
    int supportB(const Vec3& direction) const { return supportBInB(bInA.rotation.transpose() * direction); }
    /// B's support for a direction already in B's own frame.
    int supportBInB(const Vec3& localDirection) const {
        return lastSupportB = b.supportVertex(localDirection, bruteForceLimit, lastSupportB);
    }
    Vec3 vertexB(int index) const { return bInA.apply(b.vertices()[index]); }

    /// Support point of (A − p_A) − (B − p_B) in `direction`.
    SupportPoint centred(const Vec3& direction) const {
        int ia = supportA(direction), ib = supportB(-direction);
        return {(a.vertices()[ia] - centreA) - (vertexB(ib) - centreB), ia, ib};
    }
    /// Overlap of A and B along the unit `normal` (from A towards B): > 0 overlapping.
    double overlapAlong(const Vec3& normal) const {
        return normal.dot(a.vertices()[supportA(normal)]) - normal.dot(vertexB(supportB(-normal)));
    }
};

}  // namespace gdc::detail

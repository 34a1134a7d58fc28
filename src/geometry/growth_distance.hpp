// Stage 1 of the paper: the contact normal from the growth distance (GJK-GD).
//
// Growth distance (paper eq. 1–2): scale A and B about interior contraction points p_A, p_B by α
// until they just touch. Writing C = (A − p_A) − (B − p_B), which contains the origin in its
// interior, the touching condition is −(1/α)·(p_A − p_B) ∈ ∂C: the exit point of the ray from
// the origin along w = (p_B − p_A)/|p_B − p_A| through C. α = |p_A − p_B| / h, where h is the
// exit distance; α < 1 overlaps, α > 1 is separated. The outward normal of C at the exit point is
// the contact normal, pointing from A towards B.
//
// The exit point is found by a GJK ray cast (van den Bergen, "Ray Casting against General Convex
// Objects with Application to Continuous Collision Detection", 2004) fired back at C from a point
// outside it on the same line, so that the ray never starts inside.
#pragma once

#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>

#include <array>
#include <cmath>

namespace gdc::detail {

/// A point of the Minkowski difference, with the vertices of A and B it came from.
struct SupportPoint {
    Vec3 point;
    int vertexA;
    int vertexB;
};

/// Closest point to the origin of the convex hull of up to four points, and the minimal subset
/// of them (with barycentric weights) whose hull contains it.
struct SimplexClosest {
    Vec3 closest = Vec3::Zero();
    int count = 0;
    std::array<int, 4> used{};        // indices into the input points
    std::array<double, 4> weights{};  // barycentric weights of the used points
};
SimplexClosest closestPointToOrigin(const std::array<Vec3, 4>& points, int count);

struct RayCastResult {
    bool hit = false;
    double lambda = 0;      // hit point = origin + lambda · direction
    Vec3 normal = Vec3::Zero();  // outward surface normal at the hit (not normalised; zero if unknown)
    int simplexCount = 0;   // support points whose hull contains the hit point
    std::array<SupportPoint, 4> simplex{};
    std::array<double, 4> weights{};
    int iterations = 0;
};

/// Whether the plane of the triangle `simplex[0..2]` (oriented along `side`) supports the convex
/// set of `support` within `tolerance`: one support query along its normal.
template <class Support>
bool supportsAsFacet(const Support& support, const std::array<SupportPoint, 4>& simplex, const Vec3& side,
                     double tolerance) {
    Vec3 facet = (simplex[1].point - simplex[0].point).cross(simplex[2].point - simplex[0].point);
    if (facet.dot(side) < 0) facet = -facet;
    if (!(facet.squaredNorm() > 0) || !facet.allFinite()) return false;
    facet.normalize();
    return facet.dot(support(facet).point) <= facet.dot(simplex[0].point) + tolerance;
}

/// GJK ray cast against a convex set given by its support function `support(direction)` →
/// SupportPoint. Stores the support points themselves (not x − p), so that moving the ray's
/// current point x never leaves a stale simplex. `tolerance` is a length.
/// With a `margin` m > 0 the set cast against is the support's set grown by a ball of radius m (a
/// sphere is a point so grown, a capsule a segment): the ray stops where it comes within m of the
/// support's set, and `normal` is the direction from that set's closest point (van den Bergen's
/// cast with margins). A point or a segment has finitely many supports where its grown set has a
/// continuum, so the cast ends in a few steps where it would only converge in the limit. With
/// m = 0 every step is the plain cast's, operation for operation.
template <class Support>
RayCastResult gjkRayCast(const Support& support, const Vec3& origin, const Vec3& direction, double tolerance,
                         int maxIterations, double margin = 0) {
    RayCastResult result;
    Vec3 x = origin;
    SupportPoint first = support(origin);
    Vec3 v = x - first.point;
    std::array<SupportPoint, 4> simplex{};
    int count = 0;
    const double toleranceSquared = (margin + tolerance) * (margin + tolerance);  // the stop: |v| ≤ m + tolerance
    bool restarted = false;
    while (v.squaredNorm() > toleranceSquared && result.iterations < maxIterations) {
        ++result.iterations;
        SupportPoint p = support(v);
        Vec3 w = x - p.point;
        double vw = v.dot(w);
        const double grown = margin > 0 ? margin * v.norm() : 0.0;  // the support plane moved out by m
        if (vw > grown) {
            double vr = v.dot(direction);
            if (vr >= 0) return result;  // the ray points away from the set: miss
            result.lambda -= (vw - grown) / vr;
            x = origin + result.lambda * direction;
            result.normal = v;
        }
        bool duplicate = false;
        for (int i = 0; i < count; ++i)
            duplicate |= simplex[i].vertexA == p.vertexA && simplex[i].vertexB == p.vertexB;
        if (duplicate && vw <= grown) {
            // No new support point and no progress: converged — or stalled with v still longer
            // than the tolerance. A stall on a triangle that is a supporting facet of C is settled
            // after the loop (the facet's plane). On a triangle that cuts through C the closest
            // point of the simplex is off by rounding (a thin triangle: the facets that a corner cut
            // by 1e-7 of the size makes of C), x lies inside C's support plane along v while the
            // simplex puts it 14 tolerances outside, and v is no normal of C at the hit: in one
            // frame the cast stalled there, in the other it converged, and the two orders of a
            // pair had normals 0.17 rad apart (issue 21, oracle seed 50005065). Then, once, the
            // cast starts again from the support point alone: a simplex built afresh from x
            // converges where the old one could not. The rounding came from the triangle's
            // barycentric closest point, which is now its plane's (triangleResult): since then
            // 50005065 passes without the restart, which fired 2849 times in the oracle's main
            // case before that change and none with its first form (the closest point from the
            // two shorter edges' normal; the kept form, ab × ac, was not recounted). It stays as a
            // guard for a stall of another origin.
            if (!restarted && count == 3 && v.squaredNorm() > toleranceSquared &&
                !supportsAsFacet(support, simplex, v, tolerance)) {
                restarted = true;
                simplex[0] = p;
                count = 1;
                result.weights = {1, 0, 0, 0};
                v = x - p.point;
                continue;
            }
            break;
        }
        std::array<Vec3, 4> relative;
        if (!duplicate) simplex[count++] = p;
        for (int i = 0; i < count; ++i) relative[i] = x - simplex[i].point;
        SimplexClosest closest = closestPointToOrigin(relative, count);
        std::array<SupportPoint, 4> reduced{};
        for (int i = 0; i < closest.count; ++i) reduced[i] = simplex[closest.used[i]];
        simplex = reduced;
        count = closest.count;
        for (int i = 0; i < count; ++i) result.weights[i] = closest.weights[i];
        v = closest.closest;
        if (count == 4) break;  // x is inside the hull of the simplex: on the boundary within rounding
    }
    result.hit = true;
    result.simplexCount = count;
    result.simplex = simplex;
    // result.normal is the v of the last advance: the normal of a true supporting plane of C
    // through the hit point, so always valid, but only as accurate as the convergence. When the
    // hit lies inside a facet of the polytope C, the final three support points span that facet and
    // give its normal exactly — provided the plane they span really supports C (a triangle that
    // cuts through C near an edge does not), which one more support query confirms.
    if (count >= 3) {
        Vec3 facetNormal = (simplex[1].point - simplex[0].point).cross(simplex[2].point - simplex[0].point);
        if (facetNormal.dot(result.normal) < 0) facetNormal = -facetNormal;
        if (facetNormal.squaredNorm() > 0 && facetNormal.allFinite()) {
            facetNormal.normalize();
            const double height = facetNormal.dot(simplex[0].point);
            const double supportHeight = facetNormal.dot(support(facetNormal).point);
            if (supportHeight <= height + tolerance) result.normal = facetNormal;
            // A cast that stalls (no new support point, no advance) stops short of the surface, and
            // its exit along the ray is too far: by 2.8e-6 of the size on the thin facet that two
            // edges whose faces lie nearly flat to the contact plane make of A − B, the edge–edge
            // depth then 0.2 % above the exact penetration, and a grazing pair 1e-6 "deep" while
            // apart (issue 21). The support plane along the final triangle's normal bounds the
            // exit too (every support plane does), and lies within its gap of the triangle, which
            // is inside the set: the ray's meeting point with it is the better answer. Only ever
            // forward (λ grows to the hit, the exit stays an upper bound); the witnesses' weights
            // are those of the triangle's point closest to it (convex). A converged cast (|v|
            // within the tolerance) is on its facet already.
            const double along = facetNormal.dot(direction);
            if (v.squaredNorm() > toleranceSquared && along < -1e-6) {
                const double lambda = (supportHeight + margin - facetNormal.dot(origin)) / along;
                if (lambda > result.lambda) {
                    const Vec3 hit = origin + lambda * direction;
                    const std::array<Vec3, 4> relative = {hit - simplex[0].point, hit - simplex[1].point,
                                                          hit - simplex[2].point, Vec3::Zero()};
                    const SimplexClosest closest = closestPointToOrigin(relative, 3);
                    std::array<SupportPoint, 4> reduced{};
                    for (int i = 0; i < closest.count; ++i) reduced[i] = simplex[closest.used[i]];
                    result.lambda = lambda;
                    result.simplex = reduced;
                    result.simplexCount = closest.count;
                    for (int i = 0; i < 4; ++i) result.weights[i] = i < closest.count ? closest.weights[i] : 0;
                }
            }
        }
    }
    return result;
}

/// Growth distance between A and B (B given in A's frame). All vectors in A's frame.
struct GrowthDistance {
    bool valid = false;   // false when the contraction points coincide or the cast failed
    Vec3 normal = Vec3::UnitZ();  // unit, from A towards B
    double growth = 1;    // α: < 1 overlapping, > 1 separated
    bool hasWitnesses = false;     // only when asked for (needWitnesses): collide() needs the normal only
    Vec3 witnessA = Vec3::Zero();  // points of A and B whose difference is the exit point (on the
    Vec3 witnessB = Vec3::Zero();  // centre line, inside A ∩ B when overlapping)
    int iterations = 0;
    /// A lower bound of the pair's overlap along every face normal of A and of B, either sign
    /// (−∞ when unknown). The box fast path has it for free: it lets collide() skip the overhang
    /// check when no face can need much less translation than the growth-distance normal.
    double faceOverlapLowerBound = -INFINITY;
};

struct MinkowskiDifference;

/// By the GJK ray cast (any polytopes), or in closed form when both are boxes unless
/// `needWitnesses`.
GrowthDistance growthDistance(const Polytope& a, const Polytope& b, const Pose& bInA, const Settings& settings,
                              bool needWitnesses = true);
/// The same for a pair the caller already holds: its support searches continue from the pair's
/// earlier ones (warm start), as do the pair's later searches from these.
GrowthDistance growthDistance(const MinkowskiDifference& pair, const Settings& settings, bool needWitnesses);

/// growthDistance's closed form for two boxes (what it returns for them, unless asked for
/// witnesses): valid, the normal, the face-overlap bound and the exit distance h (the growth is
/// separation / h), for B at `rotationB`, `centreOffset` = p_B − p_A of length `separation`, `size` =
/// the sum of the radii. The box–box path calls it directly.
struct BoxGrowth {
    bool valid = false;
    Vec3 normal = Vec3::UnitZ();
    double faceOverlapLowerBound = -INFINITY;
    double exitDistance = INFINITY;
};
BoxGrowth boxGrowth(const Vec3& halfA, const Vec3& halfB, const Mat3& rotationB, const Vec3& centreOffset,
                    double separation, double size);

/// How far B must move along the unit `normal` (A's frame, from A towards B) to stop overlapping
/// A: the exit distance t of the ray from the origin along `normal` through A − B, with points of
/// A and B (A's frame) whose difference is t·normal — the touching pair at that translation.
struct SeparationAlong {
    bool valid = false;  // false when the line along `normal` misses A − B (the pair is separated)
    double distance = 0;
    Vec3 witnessA = Vec3::Zero();
    Vec3 witnessB = Vec3::Zero();
};
SeparationAlong separationAlong(const Polytope& a, const Polytope& b, const Pose& bInA, const Vec3& normal,
                                const Settings& settings);
SeparationAlong separationAlong(const MinkowskiDifference& pair, const Vec3& normal, const Settings& settings);

}  // namespace gdc::detail

// The contact set a pair hands the solver: at most the caller's budget of points, ranked by
// importance so that every prefix is itself a good set — the deepest point first (it carries the
// penetration), then the point farthest from it, then each point that adds the most area to the
// points kept so far (they carry the torque that keeps a resting body flat). Candidates within a
// relative band of the best count as equal and go to a fixed identity (hysteresis without state),
// and where the bodies' centroids project inside the whole polygon but outside the kept points,
// a point is swapped in that restores them. docs/algorithm.md, "The contact set the solver gets".
#pragma once

#include "contact/feature_intersection.hpp"

namespace gdc::detail {

/// What the ranking needs besides the points.
struct RankingRule {
    int maxCount;        ///< the budget (≥ 1)
    double hysteresis;   ///< Settings::reductionHysteresis: the relative band of equal candidates
    double tolerance;    ///< a length: the pair's rounding scale (1e-9 × its size)
    Vec3 identity;       ///< the fixed generic world direction in the points' frame (kIdentityDirection)
    const Vec2* centroids = nullptr;  ///< the bodies' centroids projected onto the contact plane
    int centroidCount = 0;            ///< (planar coordinates, as the points' `planar`)
    /// A given prefix: chosen[0, fixedCount) already hold distinct indices (the caller's choice,
    /// e.g. the body-pair reduction's triangle around a centre of mass), and the ranking fills the
    /// rest of the budget by area from them — the kept hull rebuilt from the kept points each slot,
    /// gains below `areaTolerance` (an area) counted as collinear — without the centroid rule.
    /// 0: the ranking chooses every slot.
    int fixedCount = 0;
    double areaTolerance = 0;  ///< with fixedCount > 0 only (else tolerance × the farthest distance)
};

/// The fixed generic world direction that gives each contact point its identity for ties: the
/// powers 1/ρ, 1/ρ², 1/ρ³ of the plastic number are independent over the rationals, so corners of
/// boxes with commensurate sizes (2:1 bricks, cubes) never share a position along it.
/// Inline and by value: out of line it would cost every ranked query a call and a guard check of
/// a function-local static.
inline Vec3 identityDirection() { return Vec3(0.7548776662466927, 0.5698402909980532, 0.4301597090019468); }

/// What the ranking reads of one point.
struct RankPoint {
    Vec2 planar;      ///< coordinates in the contact plane (read when there are 3 or more points)
    double depth;
    double identity;  ///< its position along rule.identity (the tie-break)
};

/// Chooses at most rule.maxCount of `points` in the order of importance (indices into `points`,
/// written to `chosen`, which holds kMaxManifoldPoints). Returns how many were chosen
/// (min(count, maxCount); with a given prefix at least rule.fixedCount).
int rankContacts(const RankPoint* points, int count, const RankingRule& rule, int* chosen);

/// Whether `points` (their `planar`), in the given order, are the vertices of a strictly convex
/// counter-clockwise polygon, certified despite rounding: every turn left by more than the
/// rounding of any cross product of the points' differences, the boundary winding once. Then every
/// cross product of three of the points has its true sign, and rankContacts takes each free
/// point's area gain from its two neighbours on the kept hull alone (the clip of two faces).
bool isStrictlyConvexCycle(const RankPoint* points, int count);

/// The same for lifted points (their `planar` set when there are 3 or more): each one's identity
/// is its position along rule.identity, and where the ranking of a convex cycle may pay, the
/// certificate is taken in the pass that gathers them. The same choices as rankContacts above.
int rankContacts(const LiftedPoints& points, const RankingRule& rule, int* chosen);

}  // namespace gdc::detail

// Stage 1 around the growth-distance normal (normal_choice.cpp): the early outs before it, the
// fallback where it has no answer, the overhang check once the features are known, and the
// refinement of the normal among the features' own faces. Shared by the general and the box
// pair's hooks (pipeline.hpp).
#pragma once

#include "contact/feature_intersection.hpp"
#include "geometry/minkowski.hpp"
#include "geometry/small_vector.hpp"

#include <gdcontact/manifold.hpp>

namespace gdc::detail {

/// Contact normal when the growth distance has no answer (coincident contraction points, or a
/// failed cast): the face normal of either body along which the overlap is smallest — the
/// direction a separating-axis test would push them apart. Deterministic and swap-symmetric.
Vec3 minimumOverlapFaceNormal(const MinkowskiDifference& pair);

/// The pair's overlap along `direction`, read where it is already known: `normalOverlap` when the
/// direction is `normal` itself, an earlier stage's `known` overlap along exactly this direction
/// (nullptr: none); else the support searches. overlapAlong is a deterministic function of the
/// direction's value, so a reused number is the one it would compute (within rounding for `known`).
double overlapAlong(const MinkowskiDifference& pair, const KnownOverlaps* known, const Vec3& direction,
                    const Vec3& normal, double normalOverlap);

/// The overhang check: the growth-distance `normal` (with the pair's overlap along it,
/// `normalOverlap`) against the face normals around the two selected features (with their pieces:
/// a face's cap, an edge's chain). Where one of them needs clearly less translation to separate the
/// pair (kClearlySmallerOverlap), it becomes the normal and both are updated; returns whether.
bool preferNearbyFaceNormal(const MinkowskiDifference& pair, const Feature& featureA, const SmallVector<int, 8>& piecesA,
                            const Feature& featureB, const SmallVector<int, 8>& piecesB, double tolerance,
                            const KnownOverlaps* known, Vec3& normal, double& normalOverlap);

/// How much smaller a face's overlap must be than the growth-distance normal's before the overhang
/// check (preferNearbyFaceNormal) replaces that normal by it: "clearly" smaller, so
/// that the paper's normal is kept wherever the two roughly agree and the choice cannot flicker
/// between near-equal candidates. The box–box path uses it to know when that check cannot run.
constexpr double kClearlySmallerOverlap = 0.5;

/// The general pipeline's early outs for a separated pair: bounding spheres about the centroids,
/// then the line of centres as a separating axis (more than `margin` apart, beyond `tolerance`).
/// `centreOffset` is pair.centreB − pair.centreA and `centreDistance` its length. Two boxes have
/// their overlap along the line of centres in closed form.
bool separatedByEarlyOut(const MinkowskiDifference& pair, const Vec3& centreOffset, double centreDistance, double size,
                         double margin, double tolerance);

/// An edge–edge contact's normal: the edges' common perpendicular, turned to agree with `normal`,
/// replaces it (and `normalOverlap` with the pair's overlap along it), unless the edges are parallel
/// (then it returns false and changes nothing).
bool edgeEdgeNormal(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const MinkowskiDifference& pair,
                    Vec3& normal, double& normalOverlap);

/// Stage 1's last step, once the features are known: the contact normal among the features' faces
/// (and their caps' faces) is the one along which the pair overlaps least; edge–edge (chains: each
/// pair of their edges), the edges' common perpendicular; `normal` and `normalOverlap` updated
/// together. Called by the general pipeline and the box–box path alike. `known`:
/// overlaps an earlier stage already has (the hooks' knownOverlaps(); nullptr: none), read instead
/// of a support search along exactly their directions.
void refineNormal(Vec3& normal, double& normalOverlap, const FeatureView& a, const FeatureView& b,
                  const MinkowskiDifference& pair, const KnownOverlaps* known = nullptr);

}  // namespace gdc::detail

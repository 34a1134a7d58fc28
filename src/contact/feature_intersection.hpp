// Stage 3 of the paper: intersect the two features in the contact plane.
//
// Both features are projected onto the plane ⟂ n and intersected in 2-D (convex polygon clipping,
// segment clipping, segment crossing, point containment). Every vertex of the intersection is
// lifted back onto both features along n; the gap between the two lifted points is that point's
// own depth, so a tilted face–face contact reports the true wedge of depths rather than one value.
#pragma once

#include "geometry/small_vector.hpp"
#include "shapes/feature.hpp"

#include <gdcontact/manifold.hpp>

#include <cmath>
#include <vector>

namespace gdc::detail {

struct LiftedPoint {
    Vec3 position;   // midway between the two features, in the common frame
    double depth;    // (point on A − point on B)·n: > 0 overlapping
    Vec2 planar;     // coordinates in the contact plane (for reduction)
    // The faces of the two caps the point was lifted onto (index into capFaces); 0 for a feature
    // without a cap, −1 for a point that did not come from the intersection.
    int pieceA = -1;
    int pieceB = -1;
};

using LiftedPoints = SmallVector<LiftedPoint, 16>;

/// Where the edge from a point of depth `from` to one of depth `to` crosses `contactDepth`, as the
/// fraction of the way from the first (the depth is affine along the edge), when the edge runs
/// between contact (depth ≥ contactDepth) and a clear gap (depth < contactDepth − tolerance) in
/// either direction; NaN otherwise (both in contact, or the gap within rounding of the contact).
double contactBoundaryCrossing(double from, double to, double contactDepth, double tolerance);

/// Orthonormal basis (u, v) of the plane ⟂ n (unit) with u × v = n. Inline: a call of its own was
/// a twentieth of a box–plane query (the half-space path ranks a box face's four points with it).
inline void planeBasis(const Vec3& n, Vec3& u, Vec3& v) {
    Vec3 helper = std::abs(n.x()) < 0.57 ? Vec3::UnitX() : (std::abs(n.y()) < 0.57 ? Vec3::UnitY() : Vec3::UnitZ());
    u = helper.cross(n).normalized();
    v = n.cross(u);
}

/// Intersects feature A and feature B in the plane ⟂ `normal` (unit, from A towards B).
/// `tolerance` is a length: the slack of containment tests. Points shallower than `minimumDepth`
/// by more than `tolerance` (the shapes do not touch there) are dropped; with `spanRegion`, where
/// an edge of the region runs from depth ≥ `minimumDepth` into such a gap, the point where it
/// crosses `minimumDepth` is added, so that the points span the region of contact. Returns nothing
/// when the projections do not meet (the caller then falls back to the growth-distance witness).
LiftedPoints intersectFeatures(const FeatureGeometry& a, const FeatureGeometry& b, const Vec3& normal,
                               double tolerance, double minimumDepth = -INFINITY, bool spanRegion = false);

/// The same intersection for two feature views, appended to `out`: the one implementation, which
/// the general pipeline (through the overload above) and the box–box path both call.
void intersectFeatures(const FeatureView& a, const FeatureView& b, const Vec3& normal, double tolerance,
                       double minimumDepth, bool spanRegion, LiftedPoints& out);

/// intersectFeatures for two features of at most four points each and no pieces (a box's vertex,
/// edge or face): the same steps on the same numbers, so the same points bit for bit, in fixed
/// arrays (the box–box path's; the general pipeline keeps the overload above, and
/// tests/small_intersection_test.cpp compares the two).
void intersectSmallFeatures(const FeatureView& a, const FeatureView& b, const Vec3& normal, double tolerance,
                            double minimumDepth, bool spanRegion, LiftedPoints& out);

/// Sutherland–Hodgman clip of `subject` (a convex counter-clockwise polygon of n ≥ 3 points, a
/// segment or a point) by the half-planes left of each edge of the convex counter-clockwise
/// polygon `clip`, exactly as intersectFeatures clips; exposed for its test (the result's points,
/// in order).
SmallVector<Vec2, 16> clipConvexPolygon(const Vec2* subject, int n, const Vec2* clip, int sides, double tolerance);

}  // namespace gdc::detail

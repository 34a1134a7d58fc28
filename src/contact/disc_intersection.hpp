// Stage 3 where a feature is a disc (a cylinder's cap): the exact intersection, in the contact
// plane, of the disc with a polygon, a segment, a point or another disc, each point lifted onto both
// features along n for its own depth. Seen along n a disc is an ellipse; its rim is parametrised by
// the angle t about its centre, t = 0 where the rim reaches furthest along n (the deepest rim
// point), so every point placed on an arc is a point of the real rim. The region's vertices are the
// polygon's corners inside the disc, the crossings of the two boundaries, and points on the arcs of
// the rim inside the other feature, spread evenly between the arc's ends at most 2π/arcPointsPerTurn apart:
// where the arcs go is decided by the region (its crossings), so a rotated scene rotates the points
// and a small motion moves them a little. A whole rim inside the other feature has no crossing to
// start from; its points (as many as the contact budget, a regular polygon) start at the deepest rim point, and where the disc lies exactly flat to the
// contact plane (no deepest point), at the disc's reference direction, fixed in the cylinder.
#pragma once

#include "contact/feature_intersection.hpp"
#include "shapes/round_shape.hpp"

#include <gdcontact/settings.hpp>

#include <algorithm>

namespace gdc::detail {

/// Intersects two features in the plane ⟂ `normal` (unit, from A towards B) and appends the lifted
/// points to `out`, as intersectFeatures does (`tolerance` a length, points shallower than
/// `minimumDepth` by more than it dropped); a disc on either side takes the exact disc
/// intersections above, with at most 2π/`arcPointsPerTurn` between points on an arc and
/// `wholeRimPoints` evenly on a whole rim (the caller's budget: a regular polygon of as many points
/// as the solver gets is the support polygon nearest the disc). Neither a disc: intersectFeatures
/// itself.
void intersectAnyFeatures(const AnyFeature& a, const AnyFeature& b, const Vec3& normal, double tolerance,
                          double minimumDepth, bool spanRegion, int arcPointsPerTurn, int wholeRimPoints,
                          LiftedPoints& out);

/// How many points a whole rim gets: the budget, at most the points of a turn (a regular polygon of
/// as many points as the solver gets is the support polygon nearest the disc).
inline int wholeRimPoints(const Settings& settings) {
    return std::min(settings.rimPointsPerTurn, settings.maxContacts);
}

/// Stage 3 against a half-space: its feature is its whole plane, so the contact region is A's
/// feature itself where it is deep enough, and each of its points is lifted straight onto the plane
/// (no clip against a stand-in polygon). `planeOffset` places the plane: a point p of A is
/// `planeOffset + normal·p` deep. The points are what intersectAnyFeatures gives against any polygon
/// that holds A's shadow: a disc's whole rim as `wholeRimPoints` evenly from its deepest point,
/// dropped where not in contact; a segment's or a point's own points; with `spanRegion` the rim's or
/// the segment's crossings of `minimumDepth` and the arc between them.
void liftOntoPlane(const AnyFeature& a, const Vec3& normal, double planeOffset, double tolerance,
                   double minimumDepth, bool spanRegion, int arcPointsPerTurn, int wholeRimPoints, LiftedPoints& out);

}  // namespace gdc::detail

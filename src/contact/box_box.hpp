// The box–box path: the general pipeline's answer for two boxes, from the boxes' closed forms.
#pragma once

#include <gdcontact/collide.hpp>

#include "contact/half_space.hpp"
#include "shapes/box_shape.hpp"
#include "geometry/growth_distance.hpp"

#include <cmath>

namespace gdc::detail {

/// Largest angular tolerance the box pair's hooks serve (rad): below π/4 a box face's neighbours on
/// the Gauss map (90° away) are more than twice the tolerance away, so no face has a cap (faceCap)
/// and no direction is within the tolerance of two faces' normals on opposite sides of the box.
constexpr double kMaxBoxPairAngularTolerance = 0.7;

/// Whether collideBoxBoxInto serves this pair with these settings: two boxes (Polytope::isBox()),
/// the growth-distance normal, and an angular tolerance in [0, kMaxBoxPairAngularTolerance] (larger
/// tolerances go to the general pipeline). Inline: the pair table's cell asks on every call.
inline bool boxBoxApplies(const Polytope& a, const Polytope& b, const Settings& settings) {
    return a.isBox() && b.isBox() && settings.normalMethod == NormalMethod::GrowthDistance &&
           settings.angularTolerance >= 0 && settings.angularTolerance <= kMaxBoxPairAngularTolerance;
}

/// The pair table's cell for two boxes where boxBoxApplies(): the general pipeline's three stages
/// with the boxes' closed forms — features from the box's Gauss map, faces and edges intersected
/// in fixed arrays, and the depth confirmation's ray cast replaced by the exact exit of the ray
/// through the zonotope A − B (the general pipeline runs, whole, only in the rare cases: no
/// growth-distance normal, a possible overhang, an empty intersection, a confirmation that may add
/// a point). Written into `out` (normal, pointCount, points [0, pointCount), features), the points
/// in `order` (half_space.hpp's ImportanceOrder). On a throw `out` is unspecified.
template <ImportanceOrder order>
void collideBoxBoxInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       const Settings& settings, Manifold& out);

}  // namespace gdc::detail

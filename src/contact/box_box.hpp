// The box–box path: the general pipeline's answer for two boxes, from the boxes' closed forms.
#pragma once

#include <gdcontact/collide.hpp>

#include "contact/half_space.hpp"
#include "shapes/box_shape.hpp"
#include "geometry/growth_distance.hpp"

#include <cmath>

namespace gdc::detail {

/// Whether collideBoxBox serves this pair with these settings: two boxes (Polytope::isBox()), the
/// growth-distance normal, and an angular tolerance in [0, 0.7] rad (below π/4, where a box's
/// Gauss map gives each direction at most one face and no face a cap; larger tolerances go to
/// the general pipeline).
bool boxBoxApplies(const Polytope& a, const Polytope& b, const Settings& settings);

/// The same manifold as collideGeneral (collide_general.hpp) — normal, points, depths, count and
/// features, to rounding — for a pair boxBoxApplies() accepts: features from the box's Gauss map
/// in closed form, faces and edges intersected in fixed arrays, and the depth confirmation's ray
/// cast replaced by the exact exit of the ray through the zonotope A − B (run, with the rest of
/// the general pipeline, only where that exit says the cast could add a point).
Manifold collideBoxBox(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       const Settings& settings);

/// collideBoxBox written into `out` (normal, pointCount, points [0, pointCount), features), for a
/// caller that keeps its answer in a Manifold of its own (the ODE adapter): no 0.5 KB Manifold
/// made and copied per call. On a throw `out` is unspecified.
void collideBoxBoxInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       const Settings& settings, Manifold& out);

/// The same with the points in `order` (half_space.hpp's ImportanceOrder; instantiated for
/// AmongEqualDepths, the ODE adapter's pair path: lift order where every point is kept and no two
/// depths are equal, collide_general.hpp's emitInLiftOrder).
template <ImportanceOrder order>
void collideBoxBoxInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       const Settings& settings, Manifold& out);

}  // namespace gdc::detail

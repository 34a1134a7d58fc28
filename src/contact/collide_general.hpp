// The general pipeline of the paper, without the kinds' closed forms (box–box, polytope–half-space
// vertex loops): the cells of the pair table (pair_table.hpp) for hulls, and where those closed
// forms do not apply.
#pragma once

#include <gdcontact/collide.hpp>

#include "contact/feature_intersection.hpp"
#include "contact/normal_choice.hpp"
#include "contact/half_space.hpp"
#include "geometry/minkowski.hpp"

namespace gdc::detail {

/// Writes the lifted points (A's frame) to the manifold in world coordinates, ranked by importance
/// and reduced to settings.maxContacts (reduction.hpp: rankContacts, with the bodies' `centroids`
/// in A's frame for the centroid rule; `tolerance` the pair's rounding length); throws InvalidInput
/// when finite input overflowed into a non-finite contact.
void emitManifold(const LiftedPoints& points, const Vec3& normal, const Pose& commonToWorld, const Settings& settings,
                  double tolerance, const Vec3* centroids, int centroidCount, Manifold& manifold);

/// emitManifold's manifold with the points in lift order, for a caller that orders them by depth
/// itself, keeping the order of equal depths (the ODE adapter's writeContacts): only where the
/// ranking keeps every point (at most settings.maxContacts of them) and no two depths compare
/// equal, so that the importance order decides nothing that caller reads — the same points, to the
/// bit, and the same throw. Returns false (nothing written) otherwise: emitManifold ranks them.
bool emitInLiftOrder(const LiftedPoints& points, const Vec3& normal, const Pose& commonToWorld, const Settings& settings,
                     Manifold& manifold);

/// The paper's three stages for any two polytopes (collide.cpp), written into `out`: the
/// growth-distance normal (the hull enumeration for small pairs, the GJK ray cast otherwise), the
/// Gauss-map features, their intersection in the contact plane with the depth confirmation; the
/// points in `order` (half_space.hpp's ImportanceOrder). The cell of any pair with a hull, and
/// where the boxes' closed forms do not apply or leave a rare case. Poses must be finite
/// (pair_table.cpp checks them). On a throw `out` is unspecified.
template <ImportanceOrder order>
void collideGeneralInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                        const Settings& settings, Manifold& out);

/// Any polytope on a half-space (half_space.cpp, the general polytope-on-plane hooks: the support
/// search and the Gauss map), written into `out`. poseA must be finite.
void collideGeneralInto(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b, const Settings& settings,
                        Manifold& out);

}  // namespace gdc::detail

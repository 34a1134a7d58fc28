// ODE's curved geoms (sphere, capsule, cylinder) as the core's curved kinds, and the one list of the
// class pairs gdcontact collides: install() overrides exactly those, spaceCollide hands exactly
// those to its workers. Pairs whose ODE answer is already the exact region stay with ODE: a sphere
// against a sphere, a box, a plane, a capsule or a cylinder (one point, exact), and a capsule
// against a capsule or a plane (ODE's segment closest points give both ends) — docs/ode.md.
#pragma once

#include "contact/pair_table.hpp"

#include <ode/ode.h>

namespace gdc::ode::detail {

/// Whether gdcontact collides geoms of these classes (either order).
bool isGdcontactPair(int class1, int class2);

/// Whether the class is sphere, capsule or cylinder.
inline bool isRoundClass(int geomClass) {
    return geomClass == dSphereClass || geomClass == dCapsuleClass || geomClass == dCylinderClass;
}

/// The curved geom's kind and size. Sizes ODE accepts and the core does not (a zero radius, a
/// zero-length cylinder) become the thinnest the core takes; throws InvalidInput for a negative or
/// non-finite size.
void readRound(dGeomID geom, int geomClass, gdc::detail::ShapeKind& kind, gdc::detail::RoundShape& round);

/// A bound of the curved shape's points about its centre.
double roundRadius(gdc::detail::ShapeKind kind, const gdc::detail::RoundShape& round);

}  // namespace gdc::ode::detail

// dConvex geoms after install() (convex_geoms.cpp): the hull gdcontact knows for a geom, and ODE's
// own collider for a plain dCreateConvex geom gdcontact does not know. Without ODE's colliders
// (another ODE build) such a pair gets no contacts, with one message — never an abort.
#pragma once

#include "thread_cache.hpp"

#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>

#include <ode/ode.h>

namespace gdc::ode::detail {

/// The hull of a convex geom at `pose`, or nullptr when gdcontact does not know the geom's shape:
/// a plain dCreateConvex geom (`unregistered` set), or a createConvex geom given other data by
/// dGeomSetConvex (its AABB, which ODE computes from the points it holds, no longer matches the
/// hull; said once). Out of line: the box case of the caller is the hot one.
[[gnu::noinline]] const Polytope* knownHull(dGeomID geom, const Pose& pose, const Settings& settings,
                                            ThreadCache& cache, bool& unregistered);

/// The pair (o1, o2), one of them a dConvex gdcontact does not know, collided by ODE's own collider
/// for it, as dCollide would; only valid contacts kept.
int collideWithOde(dGeomID o1, int class1, dGeomID o2, int class2, int maxContacts, dContactGeom* contact,
                   int skip);

/// Says once per session that a plain dCreateConvex geom goes to ODE's own collider.
[[gnu::cold, gnu::noinline]] void reportPlainConvex();

/// A new session (install()) says its one-time messages again.
void resetConvexMessages();

}  // namespace gdc::ode::detail

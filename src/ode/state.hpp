// The adapter's process-wide state: the convex registry, the box-polytope cache and the installed
// settings. This is the one place in gdcontact with global mutable state, and it exists because
// ODE leaves no other choice: a dColliderFn carries no user pointer (so the installed settings
// must be found globally), ODE 0.16.2 has no getter for a dConvex's data (so the hull of a
// createConvex geom must be found by the geom's address) and no geom-destroy callback (so the
// registry learns of a destroyed geom through ODE's free handler). Everything here is guarded by
// locks; the core stays pure.
#pragma once

#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>

#include <ode/ode.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace gdc::ode::detail {

/// What gdcontact keeps for one createConvex geom.
struct ConvexRecord {
    std::shared_ptr<const Polytope> polytope;
    // The arrays handed to dCreateConvex. ODE keeps only pointers to them, so they must live
    // exactly as long as the geom: the record is dropped when ODE frees the geom's memory.
    std::vector<dReal> planes;
    std::vector<dReal> points;
    std::vector<unsigned> polygons;
};

/// Creates the dConvex for `record` (whose arrays must be filled) in `space` and registers it.
dGeomID createRegisteredConvex(dSpaceID space, std::shared_ptr<ConvexRecord> record);

/// The hull of a createConvex geom; nullptr for a geom gdcontact did not create.
std::shared_ptr<const Polytope> registeredConvex(dGeomID geom);

/// Number of live registered convex geoms.
std::size_t registeredConvexCount();

/// A box polytope of the given half extents, shared between all boxes of that size (bounded
/// cache: building a Polytope allocates, and box–box must be cheap).
std::shared_ptr<const Polytope> boxPolytope(double halfX, double halfY, double halfZ);

/// The settings of the last install() (defaults before).
Settings installedSettings();
void setInstalledSettings(const Settings& settings);

}  // namespace gdc::ode::detail

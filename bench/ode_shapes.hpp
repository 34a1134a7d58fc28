// ODE geoms for the shared fixtures: dBox, dPlane and a dConvex built from the very hull gdcontact
// uses, so that ODE's native colliders see the same shape.
#pragma once

#include "fixtures.hpp"

#include <gdcontact/polytope.hpp>
#include <ode/ode.h>

#include <memory>
#include <vector>

namespace gdcbench {

/// dInitODE2 / dCloseODE for the lifetime of a benchmark program.
class OdeSession {
public:
    OdeSession() { dInitODE2(0); }
    ~OdeSession() { dCloseODE(); }
    OdeSession(const OdeSession&) = delete;
    OdeSession& operator=(const OdeSession&) = delete;
};

void setGeomPose(dGeomID geom, const Pose& pose);
void setBodyPose(dBodyID body, const Pose& pose);
Pose geomPose(dGeomID geom);

/// A dBox of the given half extents (ODE takes full side lengths).
dGeomID createOdeBox(dSpaceID space, const Vec3& halfExtents);
/// A dPlane for the solid half-space (ODE's plane is solid on the side opposite its normal).
dGeomID createOdePlane(dSpaceID space, const gdc::HalfSpace& halfSpace);

/// ODE's dConvex keeps pointers to its planes, points and polygons: this owns them next to the geom.
/// A geom created in a space belongs to that space (destroyed with it); one without a space is
/// destroyed here. Either way this object must outlive the geom's use.
class OdeConvex {
public:
    OdeConvex(dSpaceID space, const gdc::Polytope& hull);
    ~OdeConvex();
    OdeConvex(const OdeConvex&) = delete;
    OdeConvex& operator=(const OdeConvex&) = delete;
    dGeomID geom() const { return geom_; }

private:
    std::vector<dReal> planes_, points_;
    std::vector<unsigned> polygons_;
    dGeomID geom_ = nullptr;
    bool ownsGeom_ = false;
};

/// A geom-only dCollide into a fixed buffer; returns the number of contacts.
int odeCollide(dGeomID a, dGeomID b, int maxContacts, dContactGeom* contacts);

}  // namespace gdcbench

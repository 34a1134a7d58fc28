// Reading ODE's geoms as the core takes them: a class's name, a pose, the fixed order of a pair.
#pragma once

#include <gdcontact/types.hpp>

#include <ode/ode.h>

#include <functional>

namespace gdc::ode::detail {

// ODE's geom classes by number (its enum, dSphereClass = 0 … dHeightfieldClass).
inline const char* className(int geomClass) {
    static const char* const names[] = {"sphere", "box",    "capsule",        "cylinder", "plane",
                                        "ray",    "convex", "geom transform", "trimesh",  "heightfield"};
    static_assert(dHeightfieldClass == 9, "ODE's geom class numbers");
    return geomClass >= 0 && geomClass <= dHeightfieldClass ? names[geomClass] : "unsupported class";
}

// poseOf without its checks, for geoms whose class is already known to be placeable: ODE's arrays
// read straight into the pose the core takes (in place, no copy).
inline void readPoseInto(dGeomID geom, Pose& pose) {
    const dReal* p = dGeomGetPosition(geom);
    const dReal* r = dGeomGetRotation(geom);  // a dMatrix3: 3x4 row-major, the fourth column padding
    pose.position = Vec3{p[0], p[1], p[2]};
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column) pose.rotation(row, column) = r[4 * row + column];
}

// One fixed order per pair, so collide(a,b) and collide(b,a) make the same core call and their
// answers are exact mirrors (ODE calls fn(b,a) for dCollide(a,b) on same-class pairs). The order
// comes from the geoms' positions, not their addresses: a world rebuilt in the same state must
// replay exactly, and allocation reuses addresses in another order (the address only breaks
// exact ties).
inline bool comesFirst(const Vec3& p, dGeomID geomP, const Vec3& q, dGeomID geomQ) {
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return std::less<const void*>{}(static_cast<const void*>(geomP), static_cast<const void*>(geomQ));
}

}  // namespace gdc::ode::detail

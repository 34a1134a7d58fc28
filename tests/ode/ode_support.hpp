// Helpers shared by the ODE adapter tests: an ODE session per test, contact queries through
// dCollide, rotations.
#pragma once

#include "geometry_oracles.hpp"  // tests/: rotationAbout, randomRotation

#include <gdcontact/ode.hpp>

#include <ode/ode.h>

#include <cmath>
#include <random>
#include <vector>

namespace gdc::ode::test {

/// dInitODE2 … dCloseODE around one test, so that every test starts from ODE's own collider
/// table (dCloseODE forgets install()).
struct OdeSession {
    explicit OdeSession(bool installGdcontact = true, const Settings& settings = gdc::ode::defaultSettings()) {
        dInitODE2(0);
        if (installGdcontact) install(settings);
    }
    ~OdeSession() { dCloseODE(); }
    OdeSession(const OdeSession&) = delete;
    OdeSession& operator=(const OdeSession&) = delete;
};

/// dCollide into an array of full dContact records (stride sizeof(dContact) > sizeof(dContactGeom)).
inline std::vector<dContactGeom> collideThroughOde(dGeomID o1, dGeomID o2, int maxContacts, int extraFlags = 0) {
    std::vector<dContact> records(static_cast<std::size_t>(maxContacts));
    const int count = dCollide(o1, o2, maxContacts | extraFlags, &records[0].geom, sizeof(dContact));
    std::vector<dContactGeom> result;
    for (int i = 0; i < count; ++i) result.push_back(records[static_cast<std::size_t>(i)].geom);
    return result;
}

inline Vec3 toVec(const dReal* v) { return Vec3(v[0], v[1], v[2]); }

/// A body's rotation as a Mat3 (ODE's dMatrix3 is 3×4 row-major, the fourth column padding).
inline Mat3 bodyRotation(dBodyID body) {
    const dReal* r = dBodyGetRotation(body);
    Mat3 m;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column) m(row, column) = r[4 * row + column];
    return m;
}

inline void setRotation(dGeomID geom, const Mat3& rotation) {
    dMatrix3 matrix;
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) matrix[4 * row + column] = rotation(row, column);
        matrix[4 * row + 3] = 0;
    }
    dGeomSetRotation(geom, matrix);
}

inline void setPose(dGeomID geom, const Pose& pose) {
    dGeomSetPosition(geom, pose.position.x(), pose.position.y(), pose.position.z());
    setRotation(geom, pose.rotation);
}

using gdc::testing::randomRotation;
using gdc::testing::rotationAbout;

/// Corners of an axis-aligned box of half extents h, as x,y,z triples for createConvex.
inline std::vector<dReal> boxCorners(const Vec3& h) {
    std::vector<dReal> points;
    for (int i = 0; i < 8; ++i) {
        points.push_back((i & 1) ? h.x() : -h.x());
        points.push_back((i & 2) ? h.y() : -h.y());
        points.push_back((i & 4) ? h.z() : -h.z());
    }
    return points;
}

}  // namespace gdc::ode::test

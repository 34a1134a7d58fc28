#include "ode_shapes.hpp"

namespace gdcbench {

namespace {

/// ODE's row-major 3×4 rotation layout (the fourth column unused).
void toOdeRotation(const Mat3& from, dMatrix3 to) {
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) to[4 * i + j] = from(i, j);
        to[4 * i + 3] = 0;
    }
}

}  // namespace

void setGeomPose(dGeomID geom, const Pose& pose) {
    dMatrix3 rotation;
    toOdeRotation(pose.rotation, rotation);
    dGeomSetRotation(geom, rotation);
    dGeomSetPosition(geom, pose.position.x(), pose.position.y(), pose.position.z());
}

void setBodyPose(dBodyID body, const Pose& pose) {
    dMatrix3 rotation;
    toOdeRotation(pose.rotation, rotation);
    dBodySetRotation(body, rotation);
    dBodySetPosition(body, pose.position.x(), pose.position.y(), pose.position.z());
}

Pose geomPose(dGeomID geom) {
    const dReal* rotation = dGeomGetRotation(geom);
    const dReal* position = dGeomGetPosition(geom);
    Pose pose;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) pose.rotation(i, j) = rotation[4 * i + j];
    pose.position = Vec3(position[0], position[1], position[2]);
    return pose;
}

dGeomID createOdeBox(dSpaceID space, const Vec3& halfExtents) {
    return dCreateBox(space, 2 * halfExtents.x(), 2 * halfExtents.y(), 2 * halfExtents.z());
}

dGeomID createOdePlane(dSpaceID space, const gdc::HalfSpace& halfSpace) {
    const double length = halfSpace.normal.norm();
    const Vec3 normal = halfSpace.normal / length;
    return dCreatePlane(space, normal.x(), normal.y(), normal.z(), halfSpace.offset / length);
}

OdeConvex::OdeConvex(dSpaceID space, const gdc::Polytope& hull) {
    for (const Vec3& v : hull.vertices()) points_.insert(points_.end(), {v.x(), v.y(), v.z()});
    for (const gdc::Polytope::Face& face : hull.faces()) {
        planes_.insert(planes_.end(), {face.normal.x(), face.normal.y(), face.normal.z(), face.offset});
        polygons_.push_back(static_cast<unsigned>(face.count));
        for (int k = 0; k < face.count; ++k)
            polygons_.push_back(static_cast<unsigned>(hull.faceVertices()[face.first + k]));
    }
    geom_ = dCreateConvex(space, planes_.data(), static_cast<unsigned>(hull.faces().size()), points_.data(),
                          static_cast<unsigned>(hull.vertices().size()), polygons_.data());
    ownsGeom_ = space == nullptr;
}

OdeConvex::~OdeConvex() {
    if (ownsGeom_) dGeomDestroy(geom_);
}

int odeCollide(dGeomID a, dGeomID b, int maxContacts, dContactGeom* contacts) {
    return dCollide(a, b, maxContacts, contacts, sizeof(dContactGeom));
}

}  // namespace gdcbench

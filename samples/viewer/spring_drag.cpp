#include "spring_drag.hpp"

#include <cmath>

namespace gdc::viewer {

void SpringDrag::begin(dBodyID body, const Vec3& grabPoint, double distance) {
    body_ = body;
    dVector3 local;
    dBodyGetPosRelPoint(body, grabPoint.x(), grabPoint.y(), grabPoint.z(), local);
    localAnchor_ = Vec3(local[0], local[1], local[2]);
    target_ = grabPoint;
    distance_ = distance;
}

void SpringDrag::moveTo(const Ray& cursorRay) {
    if (active()) target_ = cursorRay.at(distance_);
}

void SpringDrag::end() { body_ = nullptr; }

Vec3 SpringDrag::anchorWorld() const {
    if (!active()) return Vec3::Zero();
    dVector3 world;
    dBodyGetRelPointPos(body_, localAnchor_.x(), localAnchor_.y(), localAnchor_.z(), world);
    return Vec3(world[0], world[1], world[2]);
}

void SpringDrag::apply() const {
    if (!active()) return;
    dMass mass;
    dBodyGetMass(body_, &mass);
    const Vec3 anchor = anchorWorld();
    dVector3 velocity;
    dBodyGetRelPointVel(body_, localAnchor_.x(), localAnchor_.y(), localAnchor_.z(), velocity);
    const double omega = std::sqrt(stiffnessPerMass);
    Vec3 acceleration = stiffnessPerMass * (target_ - anchor) -
                        2.0 * dampingRatio * omega * Vec3(velocity[0], velocity[1], velocity[2]);
    const double magnitude = acceleration.norm();
    if (magnitude > maxAcceleration) acceleration *= maxAcceleration / magnitude;
    const Vec3 force = mass.mass * acceleration;
    dBodyEnable(body_);
    dBodyAddForceAtPos(body_, force.x(), force.y(), force.z(), anchor.x(), anchor.y(), anchor.z());
}

}  // namespace gdc::viewer

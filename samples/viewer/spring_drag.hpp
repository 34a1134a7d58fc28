// Pulling a body with the mouse: a damped spring from a point fixed on the body to a target point
// that follows the cursor. Applied as a force every simulation step, so the solver — not the
// viewer — decides how the body and everything touching it respond.
#pragma once

#include "camera.hpp"

#include <ode/ode.h>

namespace gdc::viewer {

class SpringDrag {
public:
    /// Spring stiffness per unit mass (1/s²): the natural angular frequency squared. 150 lets a
    /// brick follow the cursor within a fraction of a second without exciting the stack.
    double stiffnessPerMass = 150.0;
    /// 1 = critically damped: the body follows without overshooting.
    double dampingRatio = 1.0;
    /// Cap on the spring's acceleration (m/s²) so a far-away cursor cannot fling a body through
    /// its neighbours in one step.
    double maxAcceleration = 60.0;

    /// Grab `body` at the world point `grabPoint`, found at `distance` along the pick ray.
    void begin(dBodyID body, const Vec3& grabPoint, double distance);
    /// Move the target: the point at the grab distance along the new cursor ray (so the body
    /// moves in the plane facing the camera, as the hand does).
    void moveTo(const Ray& cursorRay);
    void end();

    bool active() const { return body_ != nullptr; }
    dBodyID body() const { return body_; }
    Vec3 anchorWorld() const;
    const Vec3& target() const { return target_; }
    /// The body disappeared (removed brick, scene reset): let go without touching it.
    void forget() { body_ = nullptr; }

    /// Add the spring force at the anchor for this step and keep the body awake.
    void apply() const;

private:
    dBodyID body_ = nullptr;
    Vec3 localAnchor_ = Vec3::Zero();
    Vec3 target_ = Vec3::Zero();
    double distance_ = 0.0;
};

}  // namespace gdc::viewer

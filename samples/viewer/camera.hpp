// An orbit camera: it circles a target point, zooms towards it, and turns a pixel into a pick ray.
// Pure maths (no OpenGL), so picking can be tested without a window.
#pragma once

#include <gdcontact/types.hpp>

#include <Eigen/Core>

namespace gdc::viewer {

using Mat4 = Eigen::Matrix4d;

/// A half-line: points origin + t·direction for t ≥ 0. `direction` is unit length.
struct Ray {
    Vec3 origin;
    Vec3 direction;
    Vec3 at(double t) const { return origin + t * direction; }
};

class OrbitCamera {
public:
    /// `up` is the world's vertical axis (the opposite of gravity); it must be non-zero.
    explicit OrbitCamera(const Vec3& up = Vec3::UnitZ());

    /// Place the camera so that the axis-aligned box [low, high] fills the view.
    void frame(const Vec3& low, const Vec3& high);

    /// Turn around the target: yaw about `up`, pitch towards/away from it (radians). Pitch is
    /// kept short of the poles so the view never flips.
    void orbit(double deltaYaw, double deltaPitch);
    /// Move towards (factor < 1) or away from (factor > 1) the target.
    void zoom(double factor);
    /// Slide target and eye parallel to the image plane by a fraction of the view height.
    void pan(double rightFraction, double upFraction);

    Vec3 eye() const;
    const Vec3& target() const { return target_; }
    const Vec3& up() const { return up_; }
    double distance() const { return distance_; }
    double fieldOfViewY() const { return fieldOfViewY_; }

    /// World → eye transform (column-major, ready for glLoadMatrixd).
    Mat4 view() const;
    /// Perspective projection for a viewport of the given aspect ratio (width / height).
    Mat4 projection(double aspect) const;

    /// The ray from the eye through pixel (x, y) of a width × height image whose origin is the
    /// top-left corner (window/mouse convention).
    Ray rayThroughPixel(double x, double y, int width, int height) const;
    /// The pixel (top-left origin) where a world point appears; the inverse of rayThroughPixel.
    Eigen::Vector2d project(const Vec3& world, int width, int height) const;

    double nearPlane() const { return 0.01 * distance_; }
    double farPlane() const { return 100.0 * distance_ + 100.0; }

private:
    /// Camera axes: right, camera-up, and forward (from the eye to the target).
    void basis(Vec3& right, Vec3& cameraUp, Vec3& forward) const;

    Vec3 up_;
    Vec3 reference_;  // a horizontal direction: yaw 0 looks along it
    Vec3 target_ = Vec3::Zero();
    double distance_ = 10.0;
    double yaw_ = -1.15;  // from the −y side, slightly to the right: the wall (along x) is seen from the front
    double pitch_ = 0.4;
    double fieldOfViewY_ = 0.8;  // radians, ≈ 46°
};

}  // namespace gdc::viewer

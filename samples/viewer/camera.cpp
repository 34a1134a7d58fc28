#include "camera.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::viewer {

OrbitCamera::OrbitCamera(const Vec3& up) {
    if (!up.allFinite() || up.norm() == 0.0) throw InvalidInput("camera up axis must be a finite non-zero vector");
    up_ = up.normalized();
    // Any direction perpendicular to up serves as yaw 0; pick the world axis least aligned with up.
    Vec3 axis = std::abs(up_.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    reference_ = (axis - axis.dot(up_) * up_).normalized();
}

void OrbitCamera::frame(const Vec3& low, const Vec3& high) {
    target_ = 0.5 * (low + high);
    const double radius = std::max(0.5 * (high - low).norm(), 1e-3);
    // Distance at which a sphere of that radius fits the vertical field of view, plus a margin.
    distance_ = 1.05 * radius / std::sin(0.5 * fieldOfViewY_);
}

void OrbitCamera::orbit(double deltaYaw, double deltaPitch) {
    yaw_ += deltaYaw;
    const double limit = 1.5;  // rad, short of ±π/2 where the basis would degenerate
    pitch_ = std::clamp(pitch_ + deltaPitch, -limit, limit);
}

void OrbitCamera::zoom(double factor) {
    if (!(factor > 0.0) || !std::isfinite(factor)) return;
    distance_ = std::clamp(distance_ * factor, 1e-3, 1e5);
}

void OrbitCamera::pan(double rightFraction, double upFraction) {
    Vec3 right, cameraUp, forward;
    basis(right, cameraUp, forward);
    const double viewHeight = 2.0 * distance_ * std::tan(0.5 * fieldOfViewY_);
    target_ += viewHeight * (rightFraction * right + upFraction * cameraUp);
}

Vec3 OrbitCamera::eye() const {
    const Vec3 side = up_.cross(reference_);
    const Vec3 horizontal = std::cos(yaw_) * reference_ + std::sin(yaw_) * side;
    const Vec3 offset = std::cos(pitch_) * horizontal + std::sin(pitch_) * up_;
    return target_ + distance_ * offset;
}

void OrbitCamera::basis(Vec3& right, Vec3& cameraUp, Vec3& forward) const {
    forward = (target_ - eye()).normalized();
    right = forward.cross(up_).normalized();
    cameraUp = right.cross(forward);
}

Mat4 OrbitCamera::view() const {
    Vec3 right, cameraUp, forward;
    basis(right, cameraUp, forward);
    const Vec3 from = eye();
    Mat4 m = Mat4::Identity();
    m.block<1, 3>(0, 0) = right.transpose();
    m.block<1, 3>(1, 0) = cameraUp.transpose();
    m.block<1, 3>(2, 0) = -forward.transpose();
    m(0, 3) = -right.dot(from);
    m(1, 3) = -cameraUp.dot(from);
    m(2, 3) = forward.dot(from);
    return m;
}

Mat4 OrbitCamera::projection(double aspect) const {
    const double f = 1.0 / std::tan(0.5 * fieldOfViewY_);
    const double n = nearPlane(), fa = farPlane();
    Mat4 m = Mat4::Zero();
    m(0, 0) = f / aspect;
    m(1, 1) = f;
    m(2, 2) = (fa + n) / (n - fa);
    m(2, 3) = 2.0 * fa * n / (n - fa);
    m(3, 2) = -1.0;
    return m;
}

Ray OrbitCamera::rayThroughPixel(double x, double y, int width, int height) const {
    Vec3 right, cameraUp, forward;
    basis(right, cameraUp, forward);
    const double aspect = double(width) / double(height);
    const double halfHeight = std::tan(0.5 * fieldOfViewY_);
    const double ndcX = 2.0 * x / width - 1.0;
    const double ndcY = 1.0 - 2.0 * y / height;
    const Vec3 direction = forward + ndcX * halfHeight * aspect * right + ndcY * halfHeight * cameraUp;
    return {eye(), direction.normalized()};
}

Eigen::Vector2d OrbitCamera::project(const Vec3& world, int width, int height) const {
    const Eigen::Vector4d clip = projection(double(width) / height) * view() * world.homogeneous();
    const double ndcX = clip.x() / clip.w(), ndcY = clip.y() / clip.w();
    return {0.5 * (ndcX + 1.0) * width, 0.5 * (1.0 - ndcY) * height};
}

}  // namespace gdc::viewer

// Basic value types shared by every part of gdcontact: vectors, rigid poses, the error type.
#pragma once

#include <gdcontact/export.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <stdexcept>
#include <string>

namespace gdc {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// A rigid transform: world = rotation * local + position. `rotation` must be orthonormal.
struct Pose {
    Mat3 rotation = Mat3::Identity();
    Vec3 position = Vec3::Zero();

    Vec3 apply(const Vec3& local) const { return rotation * local + position; }
    Vec3 applyInverse(const Vec3& world) const { return rotation.transpose() * (world - position); }
    /// The pose of `other` expressed in this pose's frame (this⁻¹ · other).
    Pose relative(const Pose& other) const {
        return {rotation.transpose() * other.rotation, applyInverse(other.position)};
    }
    /// x·0 is 0 for every finite x and NaN otherwise: one branch-free test for the twelve numbers
    /// (allFinite() tests each, which showed in the profile of a separated pair).
    bool isFinite() const {
        return (rotation.array() * 0.0).sum() + (position.array() * 0.0).sum() == 0.0;
    }
};

/// Thrown where bad input enters gdcontact (a degenerate point set, a non-convex face list,
/// a NaN pose, a zero-size box). The message names what is wrong.
class GDCONTACT_API InvalidInput : public std::invalid_argument {
public:
    explicit InvalidInput(const std::string& what) : std::invalid_argument("gdcontact: " + what) {}
};

}  // namespace gdc

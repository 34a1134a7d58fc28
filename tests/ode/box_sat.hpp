// An exact separating-axis test for two oriented boxes: the oracle for "touching" in the box–box
// tests. ODE's dBoxTouchesBox and dBoxBox call some overlapping rotated boxes with parallel faces
// separated (rounding in their edge axes), so the tests use this instead.
#pragma once

#include <gdcontact/types.hpp>

#include <cmath>

namespace gdc::ode::test {

struct OrientedBox {
    Pose pose;        // the box's axes are pose.rotation's columns
    Vec3 halfExtents;
};

/// Half the box's extent along `axis` (any length).
inline double projectedRadius(const OrientedBox& box, const Vec3& axis) {
    double radius = 0.0;
    for (int i = 0; i < 3; ++i) radius += box.halfExtents[i] * std::abs(box.pose.rotation.col(i).dot(axis));
    return radius;
}

/// True when the closed boxes share at least one point. All 15 candidate axes are tested; a
/// cross product of (nearly) parallel edges is skipped, because it is no separating direction of
/// its own — the face axes already cover that case — and its rounding would decide wrongly.
inline bool boxesTouch(const OrientedBox& a, const OrientedBox& b) {
    const Vec3 between = b.pose.position - a.pose.position;
    auto separatedAlong = [&](const Vec3& axis) {
        return std::abs(between.dot(axis)) > projectedRadius(a, axis) + projectedRadius(b, axis);
    };
    for (int i = 0; i < 3; ++i) {
        if (separatedAlong(a.pose.rotation.col(i))) return false;
        if (separatedAlong(b.pose.rotation.col(i))) return false;
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const Vec3 axis = a.pose.rotation.col(i).cross(b.pose.rotation.col(j));
            if (axis.norm() < 1e-9) continue;  // parallel edges
            if (separatedAlong(axis.normalized())) return false;
        }
    return true;
}

}  // namespace gdc::ode::test

// The curved shape kinds — sphere, capsule, cylinder — as the method needs them: a support point
// for a direction and a Gauss-map feature within the angular tolerance, in the shape's own frame
// (its axis along z, ODE's convention). A curved surface has no faces to select among: its feature
// for a direction d is read off the geometry. A cylinder's cap is a disc where d is within the
// tolerance of the axis, its side a segment where d is within the tolerance of the equator, and a
// rim point otherwise; a capsule's feature is its segment (with the radius) near the equator, else
// an end point (with the radius); a sphere's is a point (with the radius). The tolerance is the
// margin that keeps a resting cylinder's feature from flickering: at rest the tilt is far below it.
#pragma once

#include <gdcontact/manifold.hpp>
#include <gdcontact/shapes.hpp>

#include "shapes/feature.hpp"

#include <cmath>

namespace gdc::detail {

/// A curved shape's size: a sphere (halfLength 0), a capsule's or a cylinder's radius and half the
/// length of its axis.
struct RoundShape {
    double radius = 0;
    double halfLength = 0;
};

/// A planar disc (a cylinder's cap) in some frame: the points c + x with x·axis = 0, |x| ≤ radius.
/// `reference` is a unit vector in its plane fixed in the shape's frame: where nothing else fixes
/// where the points on a whole rim go (the contact normal exactly along the axis), they start there.
struct Disc {
    Vec3 centre = Vec3::Zero();
    Vec3 axis = Vec3::UnitZ();  // unit, pointing out of the body
    double radius = 0;
    Vec3 reference = Vec3::UnitX();
};

/// A body's Gauss-map feature in the common frame: a polytope's (or a curved kind's segment or
/// point) as FeatureGeometry, or a disc.
struct AnyFeature {
    FeatureGeometry geometry;  // type Face with no points for a disc
    bool isDisc = false;
    Disc disc;
    Feature id;  // what the manifold reports (featureA / featureB)
};

/// The unit radial part of a direction in a round shape's frame (x, y), or the x axis where it has
/// none (the direction along the axis: every radial direction is a support).
inline Vec3 radialUnit(const Vec3& direction) {
    const double length = std::hypot(direction.x(), direction.y());
    return length > 0 ? Vec3(direction.x() / length, direction.y() / length, 0) : Vec3::UnitX();
}

/// The axis end toward a direction: +halfLength where d·z ≥ 0.
inline double endToward(const Vec3& direction, double halfLength) {
    return direction.z() >= 0 ? halfLength : -halfLength;
}

/// Support points in the shape's frame of a direction d (any length, non-zero).
inline Vec3 sphereSupport(const RoundShape& s, const Vec3& d) { return s.radius * d.normalized(); }
inline Vec3 capsuleSupport(const RoundShape& s, const Vec3& d) {
    return Vec3(0, 0, endToward(d, s.halfLength)) + s.radius * d.normalized();
}
inline Vec3 cylinderSupport(const RoundShape& s, const Vec3& d) {
    return s.radius * radialUnit(d) + Vec3(0, 0, endToward(d, s.halfLength));
}

/// The curved kinds' features for the unit direction d (the shape's frame, pointing away from the
/// body: the contact normal for A, its negation for B), placed in the common frame by `toCommon`.
/// `sine` and `cosine` are the angular tolerance's.
AnyFeature sphereFeature(const RoundShape& s, const Vec3& d, const Pose& toCommon);
AnyFeature capsuleFeature(const RoundShape& s, const Vec3& d, const Pose& toCommon, const AngularTolerance& tolerance);
AnyFeature cylinderFeature(const RoundShape& s, const Vec3& d, const Pose& toCommon, const AngularTolerance& tolerance);

}  // namespace gdc::detail

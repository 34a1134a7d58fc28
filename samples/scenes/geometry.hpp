// Geometry the scenes need besides contact generation: an independent penetration oracle for the
// quality measures, mass properties of convex parts, and the shapes of the paper's scenes.
#pragma once

#include <gdcontact/collide.hpp>
#include <gdcontact/polytope.hpp>
#include <gdcontact/types.hpp>

#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace gdc::scenes {

inline constexpr double kPi = 3.14159265358979323846;

/// Exact penetration depth (minimum translation distance, metres) of two convex polytopes by the
/// separating axis theorem over every face normal and every edge-edge cross product; 0 when they
/// are separated or touching. Independent of every contact method, so it can judge all of them.
double penetrationDepth(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB);
/// How far the polytope's deepest vertex lies inside the half-space (metres); 0 when none does.
double penetrationDepth(const Polytope& a, const Pose& poseA, const HalfSpace& halfSpace);

/// Angle (rad) between `direction` and +z; accurate down to 1e-16 rad (acos of the z component
/// is not: it cannot resolve tilts below ~1e-8 rad, and tilts that small are what is measured).
inline double angleFromVertical(const Vec3& direction) {
    return std::atan2(direction.head<2>().norm(), direction.z());
}

/// Mass properties of a solid polytope of unit density, in its local frame.
struct MassProperties {
    double volume = 0.0;
    Vec3 centroid = Vec3::Zero();
    Mat3 inertiaAboutCentroid = Mat3::Zero();  ///< kg·m² per kg/m³ of density
};
MassProperties massProperties(const Polytope& shape);

/// Deterministic pseudo-random numbers (the same on every platform and standard library, unlike
/// std::uniform_real_distribution), so every scene is the same on every machine.
class Random {
public:
    explicit Random(std::uint64_t seed) : state_(seed) {}
    double uniform(double low, double high);  ///< in [low, high)
private:
    std::uint64_t state_;
};

// ---- shapes, each centred on its volume centroid's vertical axis, flat bottom at z = −halfHeight
/// A right prism over a regular n-gon of circumradius `radius`, axis along z.
std::shared_ptr<const Polytope> makePrism(int sides, double radius, double halfHeight);
/// A flat-topped, flat-bottomed hull with irregular sides: random polygons top and bottom plus a
/// random belt of points between them (radius up to `radius`).
std::shared_ptr<const Polytope> makeIrregularSlab(Random& random, double radius, double halfHeight);
std::shared_ptr<const Polytope> makeBox(const Vec3& halfExtents);
/// The same shape moved so that its volume centroid is the origin, and where that centroid was.
/// ODE assumes a dConvex's own origin lies inside it (its sanity checks warn otherwise, and its
/// native colliders measure from there), so a part given anywhere is made about its centroid and
/// placed by its offset.
std::pair<std::shared_ptr<const Polytope>, Vec3> centredOnCentroid(const Polytope& shape);

/// ODE's curved geoms a part may be. Their axis is the part's local z (ODE's convention).
enum class RoundKind { None, Cylinder, Capsule };

/// One convex part of a composite, placed in the composite's frame.
struct PlacedPart {
    std::shared_ptr<const Polytope> shape;
    Pose offset;
    bool isBox = false;     ///< a box (shape made by makeBox), may become an ODE dBox
    Vec3 halfExtents = Vec3::Zero();
    /// A cylinder or capsule becomes a real dCylinder / dCapsule with its exact mass; `shape` is
    /// then only its tessellation, which the geometric penetration measure and the tracking
    /// baseline (both polytope-only) see in its place.
    RoundKind round = RoundKind::None;
    double roundRadius = 0.0;  ///< m
    double roundLength = 0.0;  ///< m: a cylinder's height, a capsule's segment between its ball centres
};
/// A solid cylinder along z, centred: a dCylinder(radius, length). Its tessellation is the
/// inscribed prism of `sides` sides. Throws InvalidInput unless radius, length > 0 and sides ≥ 3.
PlacedPart makeCylinderPart(double radius, double length, int sides = 24);
/// A capsule along z, centred: a dCapsule(radius, length), `length` between the end balls'
/// centres. Its tessellation puts its vertices on the surface (rings of `sides` points).
PlacedPart makeCapsulePart(double radius, double length, int sides = 16);
/// The part's mass properties at unit density in the part's own frame: exact for a cylinder or
/// capsule (ODE's dMassSetCylinder / dMassSetCapsule), the polytope's otherwise.
MassProperties massProperties(const PlacedPart& part);
/// A gear lying flat: a `hubSides`-gon hub prism and `teeth` box teeth around it, all of the same
/// thickness (so its top and bottom are flat and it can be stacked).
std::vector<PlacedPart> makeGear(double hubRadius, int hubSides, int teeth, const Vec3& toothHalfExtents,
                                 double halfThickness);

}  // namespace gdc::scenes

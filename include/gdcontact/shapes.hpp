// The curved shape kinds, as ODE defines them (each in its own frame, the axis along z), and the
// one reference to any shape a query takes. Values: a query validates them where they enter.
#pragma once

#include <gdcontact/polytope.hpp>
#include <gdcontact/types.hpp>

namespace gdc {

/// The ball of `radius` about its frame's origin (ODE's dCreateSphere). radius > 0.
struct Sphere {
    double radius = 0.5;
};

/// The points within `radius` of the segment from (0, 0, −length/2) to (0, 0, length/2) (ODE's
/// dCreateCapsule: `length` is the straight part's, the caps add a radius at each end). radius > 0,
/// length ≥ 0 (0 is a sphere).
struct Capsule {
    double radius = 0.5;
    double length = 1.0;
};

/// The solid cylinder about the z axis, its caps the discs of `radius` at z = ±length/2 (ODE's
/// dCreateCylinder). radius > 0, length > 0.
struct Cylinder {
    double radius = 0.5;
    double length = 1.0;
};

/// The solid half-space {x : normal·x ≤ offset} (an ODE plane). `normal` must be non-zero; a
/// query normalises it.
struct HalfSpace {
    Vec3 normal = Vec3::UnitZ();
    double offset = 0.0;
};

/// One side of a query: a polytope (borrowed for the call), a curved shape or a half-space (copied).
/// Converts implicitly from each, so gdc::collide(Cylinder{0.3, 1}, pose, box, boxPose) reads as
/// written.
class GDCONTACT_API ShapeRef {
public:
    enum class Kind : unsigned char { Polytope, Sphere, Capsule, Cylinder, HalfSpace };

    ShapeRef(const Polytope& polytope) : kind_(Kind::Polytope), polytope_(&polytope) {}
    ShapeRef(const Sphere& sphere) : kind_(Kind::Sphere), radius_(sphere.radius) {}
    ShapeRef(const Capsule& capsule) : kind_(Kind::Capsule), radius_(capsule.radius), length_(capsule.length) {}
    ShapeRef(const Cylinder& cylinder) : kind_(Kind::Cylinder), radius_(cylinder.radius), length_(cylinder.length) {}
    ShapeRef(const HalfSpace& halfSpace) : kind_(Kind::HalfSpace), halfSpace_(halfSpace) {}

    Kind kind() const { return kind_; }
    const Polytope* polytope() const { return polytope_; }  ///< Polytope only
    double radius() const { return radius_; }               ///< Sphere, Capsule, Cylinder
    double length() const { return length_; }               ///< Capsule, Cylinder
    const HalfSpace& halfSpace() const { return halfSpace_; }  ///< HalfSpace only

private:
    Kind kind_;
    const Polytope* polytope_ = nullptr;
    double radius_ = 0;
    double length_ = 0;
    HalfSpace halfSpace_{};
};

}  // namespace gdc

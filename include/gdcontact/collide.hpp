// The contact query of gdcontact: shapes and poses in, a value manifold out. Pure and re-entrant.
#pragma once

#include <gdcontact/manifold.hpp>
#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>

namespace gdc {

/// The solid half-space {x : normal·x ≤ offset} (an ODE plane). `normal` must be non-zero; it is
/// normalised by collide().
struct HalfSpace {
    Vec3 normal = Vec3::UnitZ();
    double offset = 0.0;
};

/// Contact manifold between two convex polytopes by the paper's three stages: growth-distance
/// normal, one Gauss-map feature per body, feature intersection in the contact plane.
/// Returns an empty manifold when the pair is separated by more than settings.margin.
/// Throws InvalidInput for non-finite poses.
GDCONTACT_API Manifold collide(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                 const Settings& settings = {});

/// Contact manifold between a convex polytope (A) and a solid half-space (B). The normal is
/// −halfSpace.normal (from A into B's solid, as above).
GDCONTACT_API Manifold collide(const Polytope& a, const Pose& poseA, const HalfSpace& b,
                 const Settings& settings = {});

}  // namespace gdc

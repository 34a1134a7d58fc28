// The contact budget of one pair of bodies (composites: bodies made of several convex parts), as
// Jolt and bepuphysics apply it: the contacts of every pair of parts between the same two bodies
// are clustered by normal, near-duplicates are merged, and each cluster is reduced again to
// Settings::maxBodyPairContacts points. Pure geometry (no ODE): the ODE adapter's
// gdc::ode::reduceBodyPair and gdc::ode::spaceCollide read the bodies and call it.
#pragma once

#include <gdcontact/export.hpp>
#include <gdcontact/settings.hpp>
#include <gdcontact/types.hpp>

#include <vector>

namespace gdc {

/// One contact of a body pair (A, B), whichever pair of their parts made it.
struct BodyPairContact {
    Vec3 position = Vec3::Zero();  ///< world position
    Vec3 normal = Vec3::UnitZ();   ///< world unit normal pointing from B into A (ODE's convention with o1 on A)
    double depth = 0.0;            ///< overlap along the normal (≥ 0 for ODE)
};

/// What the reduction knows of the two bodies beyond their contacts.
struct BodyPairFrame {
    /// Centres of mass (world). A body without one (the static world) has hasCentre false.
    Vec3 centreA = Vec3::Zero(), centreB = Vec3::Zero();
    bool hasCentreA = false, hasCentreB = false;
    /// Gravity (world, any length; zero: none). A cluster whose normal pushes a body against gravity
    /// carries that body: its centre of mass, projected along the normal, is kept inside the kept
    /// points' polygon whenever it lay inside the polygon of all the cluster's points.
    Vec3 gravity = Vec3::Zero();
};

/// Chooses which of one body pair's `contacts` to keep (their indices, ascending, into `kept`;
/// returns how many). Deterministic, and the same for the swapped pair (every normal negated, the
/// frame's A and B exchanged). With settings.maxBodyPairContacts == 0 every contact is kept.
/// Otherwise:
/// 1. Clusters: each contact in turn joins the first cluster whose first normal is within
///    settings.bodyPairNormalTolerance of its own, else starts one (opposite normals — a body
///    clamped between two faces — and supports at an angle stay separate).
/// 2. Touching points (depth exactly 0) are left out of a cluster that has overlapping ones
///    (depth > 0): their rows would give ODE's Dantzig LCP an exactly zero residual between bodies
///    moving together, on which it stalls ("LCP internal error"; docs/algorithm.md).
/// 3. Merges near-duplicates in each cluster: points whose positions, seen along the cluster's
///    normal, lie within kBodyPairMergeFraction of the cluster's extent of each other are the same
///    row to the solver; the deeper of them is kept.
/// 4. Reduces each cluster to settings.maxBodyPairContacts by the per-geom-pair ranking: the
///    deepest, the farthest from it, then each time the point that adds the most area to the kept
///    polygon; then, if the carried body's centre of mass (see BodyPairFrame) lay inside the
///    cluster's polygon but not inside the kept one, the largest triangle of the deepest and two
///    points that contains the centre, filled up again by area.
/// Every choice has the per-geom-pair reduction's hysteresis: values within
/// settings.reductionHysteresis of the best (depths: within 1e-9 of the cluster's size) are equal
/// and go to the point of larger position along a fixed generic direction, so a perturbation
/// within rounding keeps the same points.
/// Throws InvalidInput for a negative count or a contact with a non-finite field or a normal that
/// is not unit length (to 1e-6).
GDCONTACT_API int reduceBodyPairContacts(const BodyPairContact* contacts, int count, const BodyPairFrame& frame,
                                         const Settings& settings, std::vector<int>& kept);

/// Points closer than this fraction of their cluster's extent (the diagonal of the bounding box of
/// the points seen along the normal) are merged: a thousandth of the support's size is far below
/// what changes a resting body's support, and far above the rounding (1e-17 m) at which two
/// overlapping parts of one body report the same point twice.
constexpr double kBodyPairMergeFraction = 1e-3;

}  // namespace gdc

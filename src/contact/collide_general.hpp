// The general pipeline of the paper, without the specialised paths (box–box, polytope–half-space
// vertex loops): the reference every specialised path is tested equal to. collide() dispatches.
#pragma once

#include <gdcontact/collide.hpp>

#include "contact/feature_intersection.hpp"
#include "contact/half_space.hpp"
#include "geometry/minkowski.hpp"

namespace gdc::detail {

/// The paper's three stages for any two polytopes (collide.cpp). `alwaysConfirmDepth` runs the
/// depth confirmation's ray cast wherever the lifted points fall short of the supports' overlap,
/// even where a certificate shows it cannot add a point: the path the certificate replaced, kept
/// so that a test can prove the two equal. `enumerateSmallHulls` false makes stage 1 run the GJK ray
/// cast even where the hull hook's enumeration applies (hull_gauge.hpp): what the test of the two
/// compares against. `boundFaceOverlaps` false runs every check that a lower bound on the pair's
/// overlaps (the bodies' inradii about their centroids, collide.cpp) shows cannot change the answer:
/// the path the bounds replaced, kept so that a test can prove the two equal. `carryHullGauge` false
/// makes the later stages search again for what the hull enumeration found on its way (the overlaps
/// along the selected faces' normals, the exit facet as the depth certificate, B's vertices placed
/// in A's frame; hull_gauge.hpp's HullGaugeCarry) and place A's feature by its identity pose: the
/// path the carry replaced, kept so that a test can prove the two equal.
Manifold collideGeneral(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                        const Settings& settings, bool alwaysConfirmDepth = false, bool enumerateSmallHulls = true,
                        bool boundFaceOverlaps = true, bool carryHullGauge = true);
/// Gauss-map feature of A lifted onto the half-space, for any polytope (half_space.cpp: the
/// half-space query with the general shape hooks).
Manifold collideGeneral(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings);

/// How much smaller a face's overlap must be than the growth-distance normal's before the overhang
/// check (collide.cpp, preferNearbyFaceNormal) replaces that normal by it: "clearly" smaller, so
/// that the paper's normal is kept wherever the two roughly agree and the choice cannot flicker
/// between near-equal candidates. The box–box path uses it to know when that check cannot run.
constexpr double kClearlySmallerOverlap = 0.5;

/// The general pipeline's early outs for a separated pair: bounding spheres about the centroids,
/// then the line of centres as a separating axis (more than `margin` apart, beyond `tolerance`).
/// `centreOffset` is pair.centreB − pair.centreA and `centreDistance` its length. Two boxes have
/// their overlap along the line of centres in closed form (the same decision; `closedFormBoxes`
/// false: the support searches it replaced, for the test comparing the two).
bool separatedByEarlyOut(const MinkowskiDifference& pair, const Vec3& centreOffset, double centreDistance, double size,
                         double margin, double tolerance, bool closedFormBoxes = true);

/// An edge–edge contact's normal: the edges' common perpendicular, turned to agree with `normal`,
/// replaces it (and `normalOverlap` with the pair's overlap along it), unless the edges are parallel
/// (then it returns false and changes nothing).
bool edgeEdgeNormal(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const MinkowskiDifference& pair,
                    Vec3& normal, double& normalOverlap);

/// Stage 1's last step, once the features are known: the contact normal among the features' faces
/// (and their caps' faces) is the one along which the pair overlaps least; edge–edge (chains: each
/// pair of their edges), the edges' common perpendicular; `normal` and `normalOverlap` updated
/// together (collide.cpp). Called by the general pipeline and the box–box path alike. `known`:
/// overlaps an earlier stage already has (the hooks' knownOverlaps(); nullptr: none), read instead
/// of a support search along exactly their directions.
void refineNormal(Vec3& normal, double& normalOverlap, const FeatureView& a, const FeatureView& b,
                  const MinkowskiDifference& pair, const KnownOverlaps* known = nullptr);

/// Writes the lifted points (A's frame) to the manifold in world coordinates, ranked by importance
/// and reduced to settings.maxContacts (reduction.hpp: rankContacts, with the bodies' `centroids`
/// in A's frame for the centroid rule; `tolerance` the pair's rounding length); throws InvalidInput
/// when finite input overflowed into a non-finite contact.
void emitManifold(const LiftedPoints& points, const Vec3& normal, const Pose& commonToWorld, const Settings& settings,
                  double tolerance, const Vec3* centroids, int centroidCount, Manifold& manifold);

/// emitManifold's manifold with the points in lift order, for a caller that orders them by depth
/// itself, keeping the order of equal depths (the ODE adapter's writeContacts): only where the
/// ranking keeps every point (at most settings.maxContacts of them) and no two depths compare
/// equal, so that the importance order decides nothing that caller reads — the same points, to the
/// bit, and the same throw. Returns false (nothing written) otherwise: emitManifold ranks them.
bool emitInLiftOrder(const LiftedPoints& points, const Vec3& normal, const Pose& commonToWorld, const Settings& settings,
                     Manifold& manifold);

/// collideGeneral(a, poseA, b, poseB, settings) written into `out`, the points in `order`
/// (half_space.hpp's ImportanceOrder; instantiated for AmongEqualDepths, the ODE adapter's pair
/// path). On a throw `out` is unspecified.
template <ImportanceOrder order>
void collideGeneralInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                        const Settings& settings, Manifold& out);

}  // namespace gdc::detail

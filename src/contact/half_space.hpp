// The polytope–half-space query where a vertex loop suffices: boxes (closed-form support and
// Gauss-map feature) and small hulls (one loop over the vertices gives every depth, the support
// and the early out). It returns the Manifold that detail::collideGeneral returns for the same
// input — the same normal, points, order, depths and features, computed by the same floating-
// point expressions — and throws the same InvalidInput for bad input. collide() dispatches.
#pragma once

#include <gdcontact/collide.hpp>

#include "contact/gauss_map.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {

/// Largest Settings::angularTolerance (radians) the specialised path takes: below π/4, so that
/// no two faces of a box both lie within the tolerance of a direction.
constexpr double kMaxHalfSpaceAngularTolerance = 0.75;

/// Box extents whose squares and products of squares neither overflow nor underflow (nor turn
/// subnormal): there Polytope::box's face normals (Newell's, normalised) are exactly ±e_k and its
/// edge directions normalise to exactly e_k (in binary floating point √(x²) is |x| for such x),
/// which the closed-form feature relies on. A box of extents 1e-80 (which Polytope::box accepts)
/// has face normals off the axes by an ulp.
constexpr double kSmallestBoxExtent = 1e-60, kLargestBoxExtent = 1e60;

/// Most vertices of a hull the specialised path takes (its depths live on the stack).
constexpr int kMaxSmallHullVertices = 64;

/// Whether collideHalfSpaceInto handles `polytope` under `settings`: a box of moderate extents, or a
/// hull small enough for the brute-force support search, with an angular tolerance of at most
/// kMaxHalfSpaceAngularTolerance (where a box's face cap is always the face alone). Inline: it
/// runs on every call.
inline bool halfSpaceFastPathApplies(const Polytope& polytope, const Settings& settings) {
    if (!(settings.angularTolerance >= 0 && settings.angularTolerance <= kMaxHalfSpaceAngularTolerance)) return false;
    if (polytope.isBox()) {
        const Vec3& extents = polytope.boxHalfExtents();
        return extents.minCoeff() >= kSmallestBoxExtent && extents.maxCoeff() <= kLargestBoxExtent;
    }
    const int vertexCount = static_cast<int>(polytope.vertices().size());
    return vertexCount <= settings.bruteForceSupportLimit && vertexCount <= kMaxSmallHullVertices;
}

/// A half-space normalised where it enters (the public collide(), the ODE adapter's plane cache):
/// the unit normal and the offset scaled with it (an axis-aligned unit normal kept as it is).
/// Throws InvalidInput for a non-finite or zero normal, or an offset that overflows once scaled.
struct UnitHalfSpace {
    Vec3 normal;
    double offset;
};
[[noreturn, gnu::cold, gnu::noinline]] void throwBadHalfSpace(bool overflow);
// Through the largest component first, so that a finite normal of huge or tiny components neither
// overflows nor underflows. Inline: a public query normalises on every call. A function of the
// half-space alone, so that a caller with a fixed plane (the ODE adapter's plane cache) pays its
// square root and six divisions once.
inline UnitHalfSpace normaliseHalfSpace(const HalfSpace& b) {
    const Vec3 magnitude = b.normal.cwiseAbs();
    const double largest = std::max(std::max(magnitude.x(), magnitude.y()), magnitude.z());
    if (!((b.normal * 0.0).sum() + b.offset * 0.0 == 0) || !(largest > 0)) throwBadHalfSpace(false);
    // An axis-aligned unit normal (a ground plane) is its own normalisation: divided by 1 twice.
    if (largest == 1 && b.normal.squaredNorm() == 1) return {b.normal, b.offset};
    const double normalLength = (b.normal / largest).norm();
    const Vec3 unitNormal = b.normal / largest / normalLength;
    const double scaledOffset = b.offset / largest / normalLength;
    if (!std::isfinite(scaledOffset)) throwBadHalfSpace(true);
    return {unitNormal, scaledOffset};
}

/// The order of a manifold's points a caller needs. Full: the importance order (the deepest
/// first, every prefix the best of its length), as every query returns it. AmongEqualDepths: for a
/// caller that writes the points ordered by depth itself, keeping the order of equal depths (the
/// ODE adapter's writeContacts): there the importance order decides only between points of equal
/// depth, so where every depth differs from every other the points may come in any order — the
/// ranking a face's points took (a plane basis, planar coordinates, rankAllOfFew: a large part of a
/// box–plane query) is then left out. Only where the query keeps every point (no
/// reduction): the set of points is the same either way, and the depths to the bit.
enum class ImportanceOrder { Full, AmongEqualDepths };

/// The contacts of a polytope A on the half-space b, for the inputs halfSpaceFastPathApplies
/// accepts (a box's closed forms, a small hull's vertex loop), written into `out` (every field a
/// caller reads: normal, pointCount, points [0, pointCount), features), the points in `order`.
/// `angularTolerance`: AngularTolerance(settings.angularTolerance) kept by the caller, or nullptr.
/// poseA must be finite (pair_table.cpp checks it). On a throw `out` is unspecified.
template <ImportanceOrder order>
void collideHalfSpaceInto(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b, const Settings& settings,
                          const AngularTolerance* angularTolerance, Manifold& out);

}  // namespace gdc::detail

// The polytope–half-space query where a vertex loop suffices: boxes (closed-form support and
// Gauss-map feature) and small hulls (one loop over the vertices gives every depth, the support
// and the early out). It returns the Manifold that detail::collideGeneral returns for the same
// input — the same normal, points, order, depths and features, computed by the same floating-
// point expressions — and throws the same InvalidInput for bad input. collide() dispatches.
#pragma once

#include <gdcontact/collide.hpp>

#include "contact/gauss_map.hpp"

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

/// Whether collideHalfSpace handles `polytope` under `settings`: a box of moderate extents, or a
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

/// collideGeneral(a, poseA, b, settings) for the inputs halfSpaceFastPathApplies accepts.
Manifold collideHalfSpace(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings);

/// A half-space as collideHalfSpace (and collideGeneral) normalise it: the unit normal and the
/// offset scaled with it (an axis-aligned unit normal kept as it is). Throws the InvalidInput they
/// throw for a non-finite or zero normal, or an offset that overflows once scaled.
struct UnitHalfSpace {
    Vec3 normal;
    double offset;
};
UnitHalfSpace normaliseHalfSpace(const HalfSpace& b);

/// The order of a manifold's points a caller needs. Full: the importance order (the deepest
/// first, every prefix the best of its length), as every query returns it. AmongEqualDepths: for a
/// caller that writes the points ordered by depth itself, keeping the order of equal depths (the
/// ODE adapter's writeContacts): there the importance order decides only between points of equal
/// depth, so where every depth differs from every other the points may come in any order — the
/// ranking a face's points took (a plane basis, planar coordinates, rankAllOfFew: a large part of a
/// box–plane query) is then left out. Only where the query keeps every point (no
/// reduction): the set of points is the same either way, and the depths to the bit.
enum class ImportanceOrder { Full, AmongEqualDepths };

/// collideHalfSpace written into `out` (every field a caller reads: normal, pointCount, points
/// [0, pointCount), features), for a caller that keeps its answer in a Manifold of its own (the
/// ODE adapter): no 0.5 KB Manifold made and copied per call. On a throw `out` is unspecified.
void collideHalfSpaceInto(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings,
                          Manifold& out);

/// The same, for the half-space normaliseHalfSpace(b) made (a caller with a fixed plane normalises
/// it once): the same answer, to the bit, as collideHalfSpaceInto(a, poseA, b, settings, out).
void collideHalfSpaceInto(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b, const Settings& settings,
                          Manifold& out);

/// The same, with `angularTolerance` = AngularTolerance(settings.angularTolerance) given by a
/// caller that keeps it across calls (the ODE adapter's thread cache), so that its cosine and sine
/// are not recomputed per query. The same answer.
void collideHalfSpaceInto(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b, const Settings& settings,
                          const AngularTolerance& angularTolerance, Manifold& out);

/// The two above with the points in `order` (instantiated for ImportanceOrder::AmongEqualDepths;
/// Full is the functions above). A template argument, not a parameter: a seventh argument would go
/// on the stack of every call.
template <ImportanceOrder order>
void collideHalfSpaceInto(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b, const Settings& settings,
                          Manifold& out);
template <ImportanceOrder order>
void collideHalfSpaceInto(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b, const Settings& settings,
                          const AngularTolerance& angularTolerance, Manifold& out);

}  // namespace gdc::detail

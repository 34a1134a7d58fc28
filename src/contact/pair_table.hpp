// The one dispatch of a pair to its composition: a table by (kind of A, kind of B), used by the
// public queries (collide.cpp), the pair cache (pair_cache.cpp) and the ODE adapter alike. A shape
// kind is a row and a column here plus its hooks in a file of its own (docs/algorithm.md, "Shape
// kinds"); a pair whose B comes before its A in the table's order is the mirror of the pair the
// other way round.
#pragma once

#include <gdcontact/collide.hpp>

#include "contact/half_space.hpp"
#include "shapes/feature.hpp"
#include "shapes/round_shape.hpp"

namespace gdc::detail {

/// The shape kinds the pipeline composes. A Box is a Polytope made by Polytope::box (isBox():
/// its closed forms apply); a Hull any other Polytope; Sphere, Capsule and Cylinder the curved
/// kinds (shapes/round_shape.hpp, sizes checked where they enter: enterRound); a HalfSpace a
/// plane's solid side, already normalised (UnitHalfSpace: bad planes are refused where they enter,
/// normaliseHalfSpace).
enum class ShapeKind : unsigned char { Box, Hull, Sphere, Capsule, Cylinder, HalfSpace };
inline constexpr int kShapeKindCount = 6;

/// One side of a pair as the table takes it: the kind and the shape, borrowed for the call. The
/// pose that goes with it is the caller's (a half-space's is ignored: it lives in the world).
struct Shape {
    ShapeKind kind;
    const Polytope* polytope = nullptr;        // Box, Hull
    const UnitHalfSpace* halfSpace = nullptr;  // HalfSpace
    RoundShape round{};                        // Sphere, Capsule, Cylinder
    static Shape of(const Polytope& p) { return {p.isBox() ? ShapeKind::Box : ShapeKind::Hull, &p, nullptr}; }
    static Shape of(const UnitHalfSpace& h) { return {ShapeKind::HalfSpace, nullptr, &h}; }
    static Shape of(ShapeKind roundKind, const RoundShape& r) { return {roundKind, nullptr, nullptr, r}; }
    /// Every kind but the half-space is a body with a pose.
    bool isPolytope() const { return kind <= ShapeKind::Hull; }
    bool hasPose() const { return kind != ShapeKind::HalfSpace; }
};

/// What a caller asks of one query beyond the settings.
struct PairQuery {
    const Settings& settings;
    /// Full: the points in the importance order (every query's contract). AmongEqualDepths: the
    /// caller orders them by depth itself (half_space.hpp), so a composition may leave points of
    /// different depths unranked; it is a permission, and a composition may rank in full anyway.
    ImportanceOrder order = ImportanceOrder::Full;
    /// AngularTolerance(settings.angularTolerance), kept by a caller across calls (its cosine and
    /// sine are not recomputed); nullptr: made where a composition needs it.
    const AngularTolerance* angularTolerance = nullptr;
    /// The caller's kept tolerance, or one made from the settings.
    AngularTolerance angular() const {
        return angularTolerance ? *angularTolerance : AngularTolerance(settings.angularTolerance);
    }
};

/// One cell of the table: the pair's contacts written into `out` (normal, pointCount, points
/// [0, pointCount), features). On a throw `out` is unspecified.
using PairFunction = void (*)(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB,
                              const PairQuery& query, Manifold& out);

/// The table: kPairCells[order].at[kind of A][kind of B] (pair_table.cpp), order 0 Full, 1
/// AmongEqualDepths.
struct PairCells {
    PairFunction at[kShapeKindCount][kShapeKindCount];
};
extern const PairCells kPairCells[2];

/// Throws InvalidInput("the pose of <which> is not finite").
[[noreturn, gnu::cold, gnu::noinline]] void throwPoseNotFinite(const char* which);

/// The table's answer for (a, b): the cell by their kinds. Throws InvalidInput for non-finite
/// poses of polytopes and for a pair the table has no cell for (two half-spaces). Inline: the
/// checks and the lookup are a few instructions, a call around them more.
inline void collidePair(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, const PairQuery& query,
                        Manifold& out) {
    if (a.hasPose() && !poseA.isFinite()) throwPoseNotFinite("A");
    if (b.hasPose() && !poseB.isFinite()) throwPoseNotFinite("B");
    const PairFunction cell =
        kPairCells[query.order == ImportanceOrder::Full ? 0 : 1].at[static_cast<int>(a.kind)][static_cast<int>(b.kind)];
    cell(a, poseA, b, poseB, query, out);
}

/// A curved shape as a public query names it (shapes.hpp), its size checked: throws InvalidInput
/// naming `which` (A or B) for a radius that is not positive and finite, a cylinder's length that is
/// not, or a capsule's that is negative or not finite.
Shape enterRound(ShapeRef::Kind kind, double radius, double length, const char* which);

/// A polytope A's pose and a half-space as a public query takes them: the pose checked first (a bad
/// pose is reported before a bad plane), then the half-space normalised (normaliseHalfSpace).
UnitHalfSpace enterHalfSpace(const Pose& poseA, const HalfSpace& b);

}  // namespace gdc::detail

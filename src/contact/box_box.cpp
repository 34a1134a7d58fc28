// Two boxes through the general pipeline's steps (collide.cpp, collideGeneral), each in the box's
// closed form where the general one searches or allocates: the growth distance over the 15 axes
// without vector temporaries, the Gauss-map feature from the signs and sizes of the direction's
// components, faces and edges straight from the box's numbering and intersected in fixed arrays,
// and, for the depth confirmation, the exit of the ray along n through A − B from the 15 slabs of
// that zonotope instead of a GJK ray cast. Every decision is made on the same numbers the general
// pipeline compares (the same expressions on the same inputs), so both return the same manifold,
// bit for bit on box_box_test's poses; where the general pipeline takes a rare branch (no
// growth-distance normal, the overhang check, an empty intersection, a depth confirmation that
// may add a point) the pair goes to it whole.
#include "contact/box_box.hpp"

#include "geometry/box_shape.hpp"
#include "contact/collide_general.hpp"
#include "contact/feature_intersection.hpp"
#include "contact/gauss_map.hpp"
#include "geometry/growth_distance.hpp"
#include "geometry/minkowski.hpp"
#include "contact/reduction.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {
namespace {

// Largest angular tolerance served (rad): below π/4 a box face's neighbours on the Gauss map (90°
// away) are more than twice the tolerance away, so no face has a cap (faceCap) and no direction
// is within the tolerance of two faces' normals on opposite sides of the box.
constexpr double kMaxAngularTolerance = 0.7;

// Whether the ray along n leaves A − B (B at `bInA`, all in A's frame) no later than `limit` plus
// what a ray cast stopping within `castTolerance` of A − B can add: then the general pipeline's
// depth confirmation cannot add a point. A − B is the zonotope spanned by the boxes' half-edges,
// the intersection of the slabs |m·x + m·p| ≤ r(m) over its facet normals m — the 3 + 3 face
// normals and the 9 edge cross products e_i × (column j of R), each of length ≤ 1 — with
// r(m) = halfA·|m| + halfB·|Rᵀm| and p B's centre (the separating-axis radii of Gottschalk's OBB
// test). Along the line t·n the slab bounds t by (r − s·m·p)/|m·n| (s the sign of m·n), so one
// slab with r − s·m·p + castTolerance ≤ limit·|m·n| settles it: the line leaves (or misses) the
// slab by then, and a point within castTolerance of A − B is within castTolerance/|m·n| (|m| ≤ 1)
// of the slab along the line. The edge slabs come first: an overhanging face's deepest point is
// where an edge of one box crosses an edge of the other.
bool exitsBy(const Vec3& halfA, const Vec3& halfB, const Pose& bInA, const Vec3& n, double limit,
             double castTolerance) {
    const Mat3& r = bInA.rotation;
    const Vec3& p = bInA.position;
    const Mat3 absR = r.cwiseAbs();
    auto settles = [&](double radius, double mp, double mn) {
        return radius - (mn < 0 ? -mp : mp) + castTolerance <= limit * std::abs(mn);
    };
    for (int i = 0; i < 3; ++i) {
        const int i1 = i == 2 ? 0 : i + 1, i2 = i == 0 ? 2 : i - 1;
        for (int j = 0; j < 3; ++j) {
            const int j1 = j == 2 ? 0 : j + 1, j2 = j == 0 ? 2 : j - 1;
            // m = e_i × c_j has m[i1] = −R(i2, j), m[i2] = R(i1, j); Rᵀm = (row i) × e_j.
            const double mn = r(i1, j) * n[i2] - r(i2, j) * n[i1];
            const double mp = r(i1, j) * p[i2] - r(i2, j) * p[i1];
            const double radius = halfA[i1] * absR(i2, j) + halfA[i2] * absR(i1, j) + halfB[j1] * absR(i, j2) +
                                  halfB[j2] * absR(i, j1);
            if (settles(radius, mp, mn)) return true;
        }
    }
    for (int i = 0; i < 3; ++i)
        if (settles(halfA[i] + halfB.dot(absR.row(i).transpose()), p[i], n[i])) return true;
    for (int j = 0; j < 3; ++j)
        if (settles(halfA.dot(absR.col(j)) + halfB[j], r.col(j).dot(p), r.col(j).dot(n))) return true;
    return false;
}

}  // namespace

bool boxBoxApplies(const Polytope& a, const Polytope& b, const Settings& settings) {
    return a.isBox() && b.isBox() && settings.normalMethod == NormalMethod::GrowthDistance &&
           settings.angularTolerance >= 0 && settings.angularTolerance <= kMaxAngularTolerance;
}

void collideBoxBoxInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       const Settings& settings, Manifold& manifold) {
    auto general = [&] { manifold.assignUsed(collideGeneral(a, poseA, b, poseB, settings)); };
    if (!poseA.isFinite() || !poseB.isFinite()) return general();  // it says what is wrong
    // The empty answer a new Manifold is (the points beyond pointCount are never read).
    manifold.normal = Vec3::UnitZ();
    manifold.pointCount = 0;
    manifold.featureA = Feature{};
    manifold.featureB = Feature{};
    const Pose bInA = poseA.relative(poseB);
    const MinkowskiDifference pair(a, b, bInA, settings.bruteForceSupportLimit);
    const double size = a.radius() + b.radius();
    const double tolerance = 1e-9 * size;
    const Vec3 centreOffset = pair.centreB - pair.centreA;
    const double centreDistance = centreOffset.norm();
    if (separatedByEarlyOut(pair, centreOffset, centreDistance, size, settings.margin, tolerance)) return;

    // Stage 1: the closed-form growth distance of two boxes.
    const BoxGrowth growth =
        boxGrowth(a.boxHalfExtents(), b.boxHalfExtents(), bInA.rotation, centreOffset, centreDistance, size);
    if (!growth.valid) return general();  // coincident centres: the general fallback normal
    Vec3 normal = growth.normal;
    double normalOverlap = pair.overlapAlong(normal);
    if (normalOverlap < -settings.margin - tolerance) return;
    // The overhang check can only act where the box pair's bound leaves room for a face of less
    // than half the normal's overlap (deep overlap): then the general pipeline runs it.
    if (!(growth.faceOverlapLowerBound >= kClearlySmallerOverlap * normalOverlap + tolerance)) return general();

    // Stage 2: one feature per box (B's with −n in its own frame).
    LazyAngularTolerance angularTolerance(settings.angularTolerance);
    const Vec3 directionB = bInA.rotation.transpose() * -normal;
    manifold.featureA = selectBoxFeature(normal, boxSupport(normal), angularTolerance);
    manifold.featureB = selectBoxFeature(directionB, boxSupport(directionB), angularTolerance);
    const BoxFeature featureA = boxFeature(a, manifold.featureA, nullptr);
    const BoxFeature featureB = boxFeature(b, manifold.featureB, &bInA);
    const FeatureView viewA = view(featureA), viewB = view(featureB);
    refineNormal(normal, normalOverlap, viewA, viewB, pair);

    // Stage 3: the intersection in the contact plane.
    LiftedPoints kept;
    intersectFeatures(viewA, viewB, normal, tolerance, -settings.margin, settings.spanContactRegion, kept);
    if (kept.empty()) return general();  // its fallbacks: the ray cast's witnesses or the supports' gap
    double deepest = -INFINITY;
    for (const LiftedPoint& point : kept) deepest = std::max(deepest, point.depth);
    // The depth confirmation: the general pipeline casts a ray along n through A − B where the
    // lifted points fall short of the supports' overlap, and adds a point where the cast's exit is
    // deeper than the deepest lifted point by more than 1 % of it. Where one box's face, edge or
    // corner overhangs the other's feature the exit is the deepest lifted point itself (the region
    // of overlap ends where the features' edges cross, and those crossings are lifted points), so
    // the exact exit, within rounding of the deepest point, settles it — leaving the whole slack to
    // the cast's own inaccuracy (it stops outside A − B, within its tolerance). Otherwise (the
    // overlap reaches beyond the features, 22 of the 105000 poses of box_box_test) the general
    // pipeline runs and decides.
    if (deepest < normalOverlap - tolerance &&
        !exitsBy(a.boxHalfExtents(), b.boxHalfExtents(), bInA, normal, deepest + 2 * tolerance,
                 2 * settings.rayCastTolerance * size))
        return general();
    const Vec3 centroids[2] = {pair.centreA, pair.centreB};
    emitManifold(kept, normal, poseA, settings, tolerance, centroids, 2, manifold);
}

Manifold collideBoxBox(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       const Settings& settings) {
    Manifold manifold;
    collideBoxBoxInto(a, poseA, b, poseB, settings, manifold);
    return manifold;
}

}  // namespace gdc::detail

// Two boxes through the one composition of the stages (pipeline.hpp, composeStages), with hooks in
// the box's closed form where the general hooks (collide.cpp) search or allocate: the growth
// distance over the 15 axes without vector temporaries, the Gauss-map feature from the signs and
// sizes of the direction's components, faces and edges straight from the box's numbering and
// intersected in fixed arrays, and, for the depth confirmation, the exit of the ray along n through
// A − B from the 15 slabs of that zonotope instead of a GJK ray cast. Every decision is made on the
// same numbers the general hooks compare (the same expressions on the same inputs), so both return
// the same manifold, bit for bit on box_box_test's poses; where the general pipeline takes a rare
// branch (no growth-distance normal, the overhang check, an empty intersection, a depth
// confirmation that may add a point) the hooks delegate and the pair goes to it whole.
#include "contact/box_box.hpp"

#include "shapes/box_shape.hpp"
#include "contact/collide_general.hpp"
#include "contact/feature_intersection.hpp"
#include "contact/gauss_map.hpp"
#include "contact/pipeline.hpp"
#include "geometry/growth_distance.hpp"
#include "geometry/minkowski.hpp"
#include "contact/reduction.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {
namespace {

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

namespace {

// The box pair's hooks for the one composition (pipeline.hpp): each stage in the boxes' closed
// form; the rare branches (no growth-distance normal, the overhang check, an empty intersection, a
// depth confirmation that may add a point) are delegated to the general hooks whole.
struct BoxPairHooks {
    static constexpr bool kDelegatesRareCases = true;
    // Box features (a vertex, an edge, a face's four corners) intersected in fixed arrays.
    static constexpr bool kSmallFeatures = true;
    explicit BoxPairHooks(const Settings& settings) : settings(settings) {}
    const Settings& settings;
    LazyAngularTolerance angularTolerance{settings.angularTolerance};

    // Non-finite poses: the general pipeline says what is wrong.

    // Stage 1: the closed-form growth distance of two boxes (coincident centres: the general
    // pipeline's fallback normal). Its bound of the face overlaps settles the overhang check.
    Stage1 growthNormal(const PairFrame& frame, const Vec3& centreOffset) const {
        const BoxGrowth growth = boxGrowth(frame.a.boxHalfExtents(), frame.b.boxHalfExtents(), frame.bInA.rotation,
                                           centreOffset, frame.centreDistance, frame.size);
        Stage1 stage1;
        if (!growth.valid) {
            stage1.delegate = true;
            return stage1;
        }
        stage1.normal = growth.normal;
        stage1.normalOverlap = frame.pair.overlapAlong(growth.normal);
        stage1.growthNormal = true;
        stage1.faceOverlapLowerBound = growth.faceOverlapLowerBound;
        return stage1;
    }

    // Stage 2: the Gauss-map feature from the signs and sizes of the direction's components.
    void selectFeatures(const PairFrame& frame, const Vec3& normal, bool /*first*/, Manifold& manifold) {
        const Vec3 directionB = frame.bInA.rotation.transpose() * -normal;
        manifold.featureA = selectBoxFeature(normal, boxSupport(normal), angularTolerance);
        manifold.featureB = selectBoxFeature(directionB, boxSupport(directionB), angularTolerance);
    }
    // No preferNearbyFace: with kDelegatesRareCases the composition never asks for the overhang check.
    static BoxFeature featureA(const PairFrame& frame, const Feature& feature) {
        return boxFeature(frame.a, feature, nullptr);
    }
    static BoxFeature featureB(const PairFrame& frame, const Feature& feature) {
        return boxFeature(frame.b, feature, &frame.bInA);
    }
    static bool refinesNormal() { return true; }
    static constexpr const KnownOverlaps* knownOverlaps() { return nullptr; }  // the closed forms carry none

    // The depth confirmation: the general pipeline casts a ray along n through A − B where the
    // lifted points fall short of the supports' overlap, and adds a point where the cast's exit is
    // deeper than the deepest lifted point by more than 1 % of it. Where one box's face, edge or
    // corner overhangs the other's feature the exit is the deepest lifted point itself (the region
    // of overlap ends where the features' edges cross, and those crossings are lifted points), so
    // the exact exit, within rounding of the deepest point, settles it — leaving the whole slack to
    // the cast's own inaccuracy (it stops outside A − B, within its tolerance). Otherwise (the
    // overlap reaches beyond the features, 22 of the 105000 poses of box_box_test) the general
    // pipeline runs and decides.
    DepthCheck confirmDepth(const PairFrame& frame, LiftedPoints&, double deepest, const LiftedPoint*,
                            const Vec3& normal, const BoxFeature&, const BoxFeature&) const {
        return exitsBy(frame.a.boxHalfExtents(), frame.b.boxHalfExtents(), frame.bInA, normal,
                       deepest + 2 * frame.tolerance, 2 * settings.rayCastTolerance * frame.size)
                   ? DepthCheck::Confirmed
                   : DepthCheck::Delegate;
    }
};

}  // namespace

namespace {

// The box pair's hooks for a caller that needs the points only in `order` (pipeline.hpp, OrderFlag).
template <ImportanceOrder order>
struct BoxPairHooksIn : BoxPairHooks {
    static constexpr ImportanceOrder kOrder = order;
    explicit BoxPairHooksIn(const Settings& settings) : BoxPairHooks(settings) {}
};

}  // namespace

// The delegated rare cases keep the full ranking: the same answer either way.
template <ImportanceOrder order>
void collideBoxBoxInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       const Settings& settings, Manifold& manifold) {
    BoxPairHooksIn<order> hooks(settings);
    if (composeStages(hooks, a, poseA, b, poseB, settings, manifold) == Composed::Delegate)
        collideGeneralInto<ImportanceOrder::Full>(a, poseA, b, poseB, settings, manifold);
}
template void collideBoxBoxInto<ImportanceOrder::Full>(const Polytope&, const Pose&, const Polytope&, const Pose&,
                                                       const Settings&, Manifold&);
template void collideBoxBoxInto<ImportanceOrder::AmongEqualDepths>(const Polytope&, const Pose&, const Polytope&,
                                                                   const Pose&, const Settings&, Manifold&);

}  // namespace gdc::detail

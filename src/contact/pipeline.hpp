// The paper's three stages composed once, for every pair a polytope A meets: another polytope or a
// half-space. composeStages constructs the pair (two polytopes: their Minkowski difference and the
// early out; a half-space: its plane in A's frame), then composeStagesIn runs stage 1 (the normal
// and the overhang check), stage 2 (one Gauss-map feature per body) and stage 3 (the contacts:
// two polytopes' features refined and intersected in the contact plane, with the depth
// confirmation; a feature against a plane lifted to its depths), and writes the manifold out. What
// differs between shapes is supplied by a hooks struct (Jolt's way: a shape gives its support and
// supporting face, the algorithm is one): collide.cpp's GeneralPairHooks (any polytopes: GJK ray
// cast or the hull enumeration, Gauss-map search, the ray cast's depth confirmation),
// box_box.cpp's BoxPairHooks (the boxes' closed forms), and half_space.cpp's hooks of a box, a
// small hull and any polytope on a plane. What depends on what B is (a polytope or a plane) is
// chosen by the frame's type: contactNormal and composeContacts, overloaded on PairFrame and
// HalfSpaceFrame. Templates, so that each shape's hooks inline into straight-line code.
//
// A pair's hooks struct supplies:
//   static constexpr bool kSmallFeatures (optional) — true: every feature has at most four points
//       and no pieces (a box's), intersected in fixed arrays (intersectSmallFeatures);
//   static constexpr bool kDelegatesRareCases — true: the overhang check and an empty intersection
//       are not handled but returned as Composed::Delegate (the caller runs the general hooks);
//   Stage1 growthNormal(frame, centreOffset)   — the normal, its overlap and a bound for the check;
//   void selectFeatures(frame, normal, first, manifold) — manifold.featureA/B for normal;
//   bool preferNearbyFace(frame, normal, normalOverlap, manifold) — the overhang check proper (only
//       where kDelegatesRareCases is false);
//   featureA(frame, feature), featureB(frame, feature) — the features in A's frame (view()-able);
//   bool refinesNormal()                       — false where the normal is exact already (SAT);
//   const KnownOverlaps* knownOverlaps()       — overlaps an earlier stage has (nullptr: none), for
//       refineNormal;
//   DepthCheck confirmDepth(frame, kept, deepest, deepestPoint, normal, featureA, featureB).
// A half-space's hooks struct supplies (the plane brings the normal, the shape the rest):
//   static constexpr bool kDelegatesRareCases = false, and preferNearbyFace (never asked: the
//       plane's normal is exact);
//   double supportDepth(frame, normal)         — the depth of A's support along normal (−m), kept
//       as `deepest` (a vertex index);
//   void selectFeatures(frame, normal, first, manifold) — A's Gauss-map feature for normal, the
//       plane's face for B;
//   const SmallVector<int, 8>* cap()            — the feature's cap of near-coplanar faces, if any;
//   double depthOf(frame, vertex)              — a vertex's depth below the plane.
#pragma once

#include "contact/collide_general.hpp"
#include "contact/feature_intersection.hpp"
#include "contact/plane_contacts.hpp"
#include "contact/reduction.hpp"
#include "geometry/minkowski.hpp"

#include <cmath>
#include <type_traits>

namespace gdc::detail {

/// What the composition did: the manifold is written, or the hooks left this pair to the general
/// pipeline (a rare branch the specialised hooks do not carry).
enum class Composed { Done, Delegate };

/// The verdict of a depth confirmation: the lifted points stand (maybe with a point added), the
/// pair turns out apart, or the hooks cannot decide and the general pipeline must.
enum class DepthCheck { Confirmed, Separated, Delegate };

/// Stage 1's answer from the hooks: the normal, the pair's overlap along it, whether the overhang
/// check applies to it (a growth-distance normal) and a lower bound of every face's overlap.
struct Stage1 {
    bool delegate = false;
    Vec3 normal = Vec3::UnitZ();
    double normalOverlap = 0;
    bool growthNormal = false;
    double faceOverlapLowerBound = -INFINITY;
};

/// Two polytopes in A's frame, as every stage sees them. The pair construction is the composition's
/// first hook point: two polytopes make this frame (their Minkowski difference, the centres'
/// offset); a half-space makes a HalfSpaceFrame (its plane in A's frame), where a Minkowski
/// difference means nothing.
struct PairFrame {
    const Polytope& a;
    const Polytope& b;
    const Pose& bInA;
    const MinkowskiDifference& pair;
    double size;
    double tolerance;
    double centreDistance;
    const Vec3& centreOffset;  // B's centre less A's
};

/// The empty answer a new Manifold is (the points beyond pointCount are never read).
inline void clearManifold(Manifold& manifold) {
    manifold.normal = Vec3::UnitZ();
    manifold.pointCount = 0;
    manifold.featureA = Feature{};
    manifold.featureB = Feature{};
}

/// Stage 1's hook for a pair of polytopes: the growth-distance normal (or the hooks' closed form).
template <class Hooks>
[[gnu::always_inline]] inline Stage1 contactNormal(Hooks& hooks, const PairFrame& frame) {
    return hooks.growthNormal(frame, frame.centreOffset);
}

/// A half-space B: its plane in A's frame, the solid {x : m·x ≤ offset}.
struct HalfSpaceFrame {
    const Polytope& a;
    PlaneInA plane;
    double tolerance;  // 1e-9 × A's radius (the plane adds no size)
};

/// Stage 1 where B is a half-space: the normal is the plane's own, −m; the overlap along it is the
/// depth of A's support along −m, which the shape's hook finds (a box's closed form, a hull's loop
/// or search) and keeps for stage 2. No overhang check: the normal is exact.
template <class Hooks>
[[gnu::always_inline]] inline Stage1 contactNormal(Hooks& hooks, const HalfSpaceFrame& frame) {
    Stage1 stage1;
    stage1.normal = -frame.plane.m;
    stage1.normalOverlap = hooks.supportDepth(frame, stage1.normal);
    return stage1;
}

/// Whether the hooks' features are all small (Hooks::kSmallFeatures: at most four points and no
/// pieces, a box's), so that stage 3 intersects them in fixed arrays (intersectSmallFeatures, the
/// same points as intersectFeatures to the bit); hooks without the flag get the general one.
template <class Hooks, class = void>
struct SmallFeaturesFlag : std::false_type {};
template <class Hooks>
struct SmallFeaturesFlag<Hooks, std::void_t<decltype(Hooks::kSmallFeatures)>> : std::bool_constant<Hooks::kSmallFeatures> {};
template <class Hooks>
constexpr bool intersectsSmallFeatures() { return SmallFeaturesFlag<Hooks>::value; }

/// The order of the points the hooks' caller needs (Hooks::kOrder, half_space.hpp's
/// ImportanceOrder; Full where the hooks name none).
template <class Hooks, class = void>
struct OrderFlag : std::integral_constant<ImportanceOrder, ImportanceOrder::Full> {};
template <class Hooks>
struct OrderFlag<Hooks, std::void_t<decltype(Hooks::kOrder)>> : std::integral_constant<ImportanceOrder, Hooks::kOrder> {};

/// Stage 3 and the manifold written out, for two polytopes: the features in A's frame (refining
/// the normal among their faces), their intersection in the contact plane, the depth
/// confirmation, the supports' gap where nothing intersects, emitManifold.
template <class Hooks>
[[gnu::always_inline]] inline Composed composeContacts(Hooks& hooks, const PairFrame& frame, Vec3& normal,
                                                       double& normalOverlap, const Pose& poseA,
                                                       const Settings& settings, Manifold& manifold) {
    const MinkowskiDifference& pair = frame.pair;
    const double tolerance = frame.tolerance;
    const auto featureA = hooks.featureA(frame, manifold.featureA);
    const auto featureB = hooks.featureB(frame, manifold.featureB);
    const FeatureView viewA = view(featureA), viewB = view(featureB);
    if (hooks.refinesNormal()) refineNormal(normal, normalOverlap, viewA, viewB, pair, hooks.knownOverlaps());

    // Stage 3: the intersection in the contact plane, each point with its own depth.
    LiftedPoints kept;
    if constexpr (intersectsSmallFeatures<Hooks>())
        intersectSmallFeatures(viewA, viewB, normal, tolerance, -settings.margin, settings.spanContactRegion, kept);
    else
        intersectFeatures(viewA, viewB, normal, tolerance, -settings.margin, settings.spanContactRegion, kept);
    if constexpr (Hooks::kDelegatesRareCases)
        if (kept.empty()) return Composed::Delegate;  // the fallbacks: a ray cast's witnesses or the supports' gap

    // The depth confirmation (collide.cpp, GeneralPairHooks::confirmDepth, says why): only where the
    // lifted points fall short of the supports' overlap along n.
    double deepest = -INFINITY;
    const LiftedPoint* deepestPoint = nullptr;
    for (const LiftedPoint& point : kept)
        if (point.depth > deepest) deepest = point.depth, deepestPoint = &point;
    if (deepest < normalOverlap - tolerance) {
        const DepthCheck check =
            hooks.confirmDepth(frame, kept, deepest, deepestPoint, normal, featureA, featureB);
        if (check == DepthCheck::Delegate) return Composed::Delegate;
        if (check == DepthCheck::Separated) {
            clearManifold(manifold);
            return Composed::Done;
        }
    }
    if (kept.empty()) {
        // The line along n misses A − B: the pair is apart, by at most the margin (the supports'
        // overlap along n passed the check above) — a speculative contact at the supports' gap.
        const Vec3 middle = 0.5 * (frame.a.vertices()[pair.supportA(normal)] + pair.vertexB(pair.supportB(-normal)));
        const double gap = normalOverlap;
        if (gap < -settings.margin - tolerance) {
            clearManifold(manifold);
            return Composed::Done;
        }
        kept.push_back({middle, gap, Vec2::Zero()});
    }
    // A caller that orders the points by depth itself (OrderFlag AmongEqualDepths) gets them in
    // lift order where every point is kept and no two depths are equal: the ranking could only
    // have ordered them (emitInLiftOrder).
    // (Its first condition here as well: a reduced face, the common case of many points, makes no call.)
    if constexpr (OrderFlag<Hooks>::value == ImportanceOrder::AmongEqualDepths)
        if (static_cast<int>(kept.size()) <= settings.maxContacts &&
            emitInLiftOrder(kept, normal, poseA, settings, manifold))
            return Composed::Done;
    const Vec3 centroids[2] = {pair.centreA, pair.centreB};
    emitManifold(kept, normal, poseA, settings, tolerance, centroids, 2, manifold);
    return Composed::Done;
}

/// Stage 3 and the manifold written out where B is a half-space: A's feature against the plane is
/// its points lifted to their depths (plane_contacts.hpp), ranked and emitted by emitManifold's
/// rule. The depth needs no confirmation — every depth is exact, the deepest vertex among them —
/// and where all points float the support itself stands in for the supports' gap.
template <class Hooks>
[[gnu::always_inline]] inline Composed composeContacts(Hooks& hooks, const HalfSpaceFrame& frame, Vec3& /*normal: −m*/,
                                                       double& /*normalOverlap*/, const Pose& poseA,
                                                       const Settings& settings, Manifold& manifold) {
    const PlaneLift lift{frame.a, frame.plane, settings, frame.tolerance, -settings.margin - frame.tolerance};
    lift.liftFeature<Hooks::kOrder>(
        manifold.featureA, hooks.deepest, hooks.cap(), [&](int v) { return hooks.depthOf(frame, v); }, poseA,
        manifold);
    return Composed::Done;
}

/// The one composition, once the pair is constructed: stage 1 (the normal), the separation along
/// it, the overhang check, stage 2 (the features), stage 3 with the manifold written out. `frame`
/// says what B is (PairFrame, HalfSpaceFrame); contactNormal and composeContacts are the hook
/// points that depend on it, the shape's own hooks are the rest.
template <class Hooks, class Frame>
[[gnu::always_inline]] inline Composed composeStagesIn(Hooks& hooks, const Frame& frame, const Pose& poseA,
                                                       const Settings& settings, Manifold& manifold) {
    const double tolerance = frame.tolerance;

    // Stage 1: the contact normal.
    const Stage1 stage1 = contactNormal(hooks, frame);
    if (stage1.delegate) return Composed::Delegate;
    Vec3 normal = stage1.normal;
    double normalOverlap = stage1.normalOverlap;
    if (normalOverlap < -settings.margin - tolerance) return Composed::Done;  // separated along n
    // The overhang check (preferNearbyFaceNormal) can only pick a face whose overlap is below half
    // the normal's, so a lower bound of every face's overlap above that settles it without a search.
    const bool overhangPossible =
        stage1.growthNormal && !(stage1.faceOverlapLowerBound >= kClearlySmallerOverlap * normalOverlap + tolerance);
    if constexpr (Hooks::kDelegatesRareCases)
        if (overhangPossible) return Composed::Delegate;

    // Stage 2: one Gauss-map feature per body (B's with −n in its own frame), the overhang check
    // on them.
    hooks.selectFeatures(frame, normal, /*first=*/true, manifold);
    if constexpr (!Hooks::kDelegatesRareCases) {
        if (overhangPossible && hooks.preferNearbyFace(frame, normal, normalOverlap, manifold)) {
            if (normalOverlap < -settings.margin - tolerance) {  // a separating face
                clearManifold(manifold);
                return Composed::Done;
            }
            hooks.selectFeatures(frame, normal, /*first=*/false, manifold);
        }
    }

    // Stage 3: the contacts.
    return composeContacts(hooks, frame, normal, normalOverlap, poseA, settings, manifold);
}

/// Two polytopes: the pair construction (A − B in A's frame) and the early out, then the stages.
template <class Hooks>
[[gnu::always_inline]] inline Composed composeStages(Hooks& hooks, const Polytope& a, const Pose& poseA,
                                                     const Polytope& b, const Pose& poseB, const Settings& settings,
                                                     Manifold& manifold) {
    clearManifold(manifold);
    const Pose bInA = poseA.relative(poseB);
    const MinkowskiDifference pair(a, b, bInA, settings.bruteForceSupportLimit);
    const double size = a.radius() + b.radius();
    const double tolerance = 1e-9 * size;
    const Vec3 centreOffset = pair.centreB - pair.centreA;
    const double centreDistance = centreOffset.norm();
    if (separatedByEarlyOut(pair, centreOffset, centreDistance, size, settings.margin, tolerance)) return Composed::Done;
    const PairFrame frame{a, b, bInA, pair, size, tolerance, centreDistance, centreOffset};
    return composeStagesIn(hooks, frame, poseA, settings, manifold);
}

/// A polytope on a half-space: the pair construction is its plane in A's frame (b normalised,
/// poseA checked finite by the caller: a bad pose is reported before a bad plane).
inline HalfSpaceFrame halfSpaceFrame(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b) {
    return {a, planeInA(b, poseA), 1e-9 * a.radius()};
}

/// A polytope on a half-space, its frame made: the stages. No early out of its own: stage 1's
/// support depth is the test.
template <class Hooks>
[[gnu::always_inline]] inline Composed composeStages(Hooks& hooks, const HalfSpaceFrame& frame, const Pose& poseA,
                                                     const Settings& settings, Manifold& manifold) {
    clearManifold(manifold);
    return composeStagesIn(hooks, frame, poseA, settings, manifold);
}

}  // namespace gdc::detail

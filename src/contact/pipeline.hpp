// The paper's three stages composed once, for every pair of polytopes: early out, stage 1 (the
// growth-distance normal and the overhang check), stage 2 (one Gauss-map feature per body and the
// normal refined among their faces), stage 3 (the features intersected in the contact plane), the
// depth confirmation and the manifold written out. What differs between shapes is supplied by a
// hooks struct (Jolt's way: a shape gives its support and supporting face, the algorithm is one):
// collide.cpp's GeneralPairHooks (any polytopes: GJK ray cast or the hull enumeration, Gauss-map
// search, the ray cast's depth confirmation) and box_box.cpp's BoxPairHooks (the boxes' closed
// forms). A template, so that the box pair's hooks inline into straight-line code.
//
// A hooks struct supplies:
//   static constexpr bool kDelegatesRareCases — true: the overhang check and an empty intersection
//       are not handled but returned as Composed::Delegate (the caller runs the general hooks);
//   bool acceptsPoses(poseA, poseB)            — false: Delegate (or throw the input's error);
//   Stage1 growthNormal(frame, centreOffset)   — the normal, its overlap and a bound for the check;
//   void selectFeatures(frame, normal, first, manifold) — manifold.featureA/B for normal;
//   bool preferNearbyFace(frame, normal, normalOverlap, manifold) — the overhang check proper (only
//       where kDelegatesRareCases is false);
//   featureA(frame, feature), featureB(frame, feature) — the features in A's frame (view()-able);
//   bool refinesNormal()                       — false where the normal is exact already (SAT);
//   DepthCheck confirmDepth(frame, kept, deepest, deepestPoint, normal, featureA, featureB).
#pragma once

#include "contact/collide_general.hpp"
#include "contact/feature_intersection.hpp"
#include "contact/reduction.hpp"
#include "geometry/minkowski.hpp"

#include <cmath>

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

/// The pair in A's frame, as every stage sees it.
struct PairFrame {
    const Polytope& a;
    const Polytope& b;
    const Pose& bInA;
    const MinkowskiDifference& pair;
    double size;
    double tolerance;
    double centreDistance;
};

/// The empty answer a new Manifold is (the points beyond pointCount are never read).
inline void clearManifold(Manifold& manifold) {
    manifold.normal = Vec3::UnitZ();
    manifold.pointCount = 0;
    manifold.featureA = Feature{};
    manifold.featureB = Feature{};
}

template <class Hooks>
[[gnu::always_inline]] inline Composed composeStages(Hooks& hooks, const Polytope& a, const Pose& poseA,
                                                     const Polytope& b, const Pose& poseB, const Settings& settings,
                                                     Manifold& manifold) {
    if (!hooks.acceptsPoses(poseA, poseB)) return Composed::Delegate;
    clearManifold(manifold);
    const Pose bInA = poseA.relative(poseB);
    const MinkowskiDifference pair(a, b, bInA, settings.bruteForceSupportLimit);
    const double size = a.radius() + b.radius();
    const double tolerance = 1e-9 * size;
    const Vec3 centreOffset = pair.centreB - pair.centreA;
    const double centreDistance = centreOffset.norm();
    if (separatedByEarlyOut(pair, centreOffset, centreDistance, size, settings.margin, tolerance)) return Composed::Done;
    const PairFrame frame{a, b, bInA, pair, size, tolerance, centreDistance};

    // Stage 1: the contact normal.
    const Stage1 stage1 = hooks.growthNormal(frame, centreOffset);
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
    // on them, and the normal refined among their faces.
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
    const auto featureA = hooks.featureA(frame, manifold.featureA);
    const auto featureB = hooks.featureB(frame, manifold.featureB);
    const FeatureView viewA = view(featureA), viewB = view(featureB);
    if (hooks.refinesNormal()) refineNormal(normal, normalOverlap, viewA, viewB, pair);

    // Stage 3: the intersection in the contact plane, each point with its own depth.
    LiftedPoints kept;
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
        const Vec3 middle = 0.5 * (a.vertices()[pair.supportA(normal)] + pair.vertexB(pair.supportB(-normal)));
        const double gap = normalOverlap;
        if (gap < -settings.margin - tolerance) {
            clearManifold(manifold);
            return Composed::Done;
        }
        kept.push_back({middle, gap, Vec2::Zero()});
    }
    const Vec3 centroids[2] = {pair.centreA, pair.centreB};
    emitManifold(kept, normal, poseA, settings, tolerance, centroids, 2, manifold);
    return Composed::Done;
}

}  // namespace gdc::detail

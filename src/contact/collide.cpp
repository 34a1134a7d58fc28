// The contact query: the general hooks of the paper's three stages (composed once, pipeline.hpp)
// and the public queries, which go to the pair table (pair_table.hpp). Everything is computed in A's frame (precision far from the origin)
// and mapped to the world at the end.
#include <gdcontact/collide.hpp>

#include "contact/collide_general.hpp"
#include "contact/feature_geometry.hpp"
#include "contact/feature_intersection.hpp"
#include "contact/gauss_map.hpp"
#include "geometry/growth_distance.hpp"
#include "contact/half_space.hpp"
#include "contact/pair_table.hpp"
#include "contact/pipeline.hpp"
#include "geometry/hull_gauge.hpp"
#include "geometry/minkowski.hpp"
#include "contact/reduction.hpp"
#include "geometry/separating_axis.hpp"

#include <algorithm>
#include <cmath>

namespace gdc {
namespace detail {

namespace {

// Any two polytopes' hooks for the one composition (pipeline.hpp): the general pipeline, where the
// specialised hooks delegate their rare cases.
struct GeneralPairHooks {
    static constexpr bool kDelegatesRareCases = false;  // it is where the others delegate to
    explicit GeneralPairHooks(const Settings& settings) : settings(settings) {}
    const Settings& settings;
    // What the hull enumeration found (empty unless it ran and carried), and the overlaps
    // along the selected faces' normals that refineNormal reads from it (knownOverlaps()), where
    // the enumeration ran with the carry.
    HullGaugeCarry carry;
    KnownOverlaps known;
    bool carrying = false;
    // featureA's findings for featureB, which decides whether refineNormal reads the carry.
    double faceOverlapA = NAN;
    Vec3 directionA = Vec3::Zero();
    FeatureType manifoldFeatureA = FeatureType::Vertex;
    bool separatingAxis = settings.normalMethod == NormalMethod::SeparatingAxis;
    // With each feature its pieces: a face's cap, an edge's chain.
    SmallVector<int, 8> piecesA, piecesB;


    // Stage 1: contact normal from the growth distance (or, to measure the trade, the SAT's).
    Stage1 growthNormal(const PairFrame& frame, const Vec3&) {
        const MinkowskiDifference& pair = frame.pair;
        Stage1 stage1;
        if (separatingAxis) {
            const SeparatingAxis axis = minimumOverlapAxis(pair);
            stage1.normal = axis.normal, stage1.normalOverlap = axis.overlap;
            return stage1;  // no overhang check: no face overlaps less than the SAT's normal
        }
        const Polytope& a = frame.a;
        const Polytope& b = frame.b;
        const bool searchesWithoutState =
            (a.isBox() || static_cast<int>(a.vertices().size()) <= pair.bruteForceLimit) &&
            (b.isBox() || static_cast<int>(b.vertices().size()) <= pair.bruteForceLimit);
        // The hull's hook: two small polytopes enumerate K's facets (hull_gauge.hpp), the same σ and
        // facet the ray cast converges to; large ones (and two boxes, in closed form) cast. What the
        // enumeration evaluated on the way is carried to the later stages (refineNormal's overlaps,
        // the depth certificate) where no search keeps state: a skipped search of a hill climb
        // would move the later climbs' starting vertices, and with them the ray cast's answer.
        const bool enumerates = hullGaugeApplies(a, b);
        carrying = enumerates && searchesWithoutState;
        const GrowthDistance growth = enumerates ? hullGrowth(pair, carrying ? &carry : nullptr)
                                                 : growthDistance(pair, settings, /*needWitnesses=*/false);
        stage1.normal = growth.valid ? growth.normal : minimumOverlapFaceNormal(pair);
        stage1.normalOverlap = pair.overlapAlong(stage1.normal);
        stage1.growthNormal = growth.valid;
        // A lower bound of every face's overlap, for the overhang check. Any pair has one: along a
        // unit c the overlap is h_{A−c_A}(c) + h_{B−c_B}(−c) − c·d (d = c_B − c_A), and each
        // support value about a centroid is at least the body's inradius, so every overlap is at
        // least r_A + r_B − |d|. For two bodies resting face to face about their centroids (a
        // stack of boxes, as hulls) that is the penetration itself, and the check — 11 % of an
        // 8-vertex hull pair's query — never runs. Only where the supports are searched without a
        // warm start (boxes, brute force): the check's searches move the hill climb's starting
        // vertices, and a climb from elsewhere may stop at another vertex of a face the direction
        // is normal to, which changes later values by a rounding.
        stage1.faceOverlapLowerBound =
            searchesWithoutState
                ? std::max(growth.faceOverlapLowerBound, a.inradius() + b.inradius() - frame.centreDistance)
                : growth.faceOverlapLowerBound;
        // The enumeration's bound of every face's overlap (HullGaugeCarry::faceOverlapBound): on a
        // stack of slabs and prisms the inradius bound above is weak (a slab's inradius is half its
        // thickness), and the overhang check would run on most resting pairs.
        if (carrying && growth.valid)
            stage1.faceOverlapLowerBound = std::max(stage1.faceOverlapLowerBound, carry.faceOverlapBound);
        return stage1;
    }

    // Stage 2: the Gauss-map search from the support vertex. `first`: the last support searches
    // were along n and −n (stage 1 ends in overlapAlong(n)), so their vertices (pair.lastSupportA,
    // lastSupportB) are what the searches here would return — the same directions, and a search
    // started at its answer stays there — and two searches are spared.
    void selectFeatures(const PairFrame& frame, const Vec3& n, bool first, Manifold& manifold) {
        const MinkowskiDifference& pair = frame.pair;
        // Here rather than with the hooks: a pair the early out or stage 1 finds apart never needs
        // its cosine and sine.
        const AngularTolerance angularTolerance(settings.angularTolerance);
        const bool supportsKnown = first && !separatingAxis;
        const Vec3 directionB = frame.bInA.rotation.transpose() * -n;
        const int supportA = supportsKnown ? pair.lastSupportA : pair.supportA(n);
        const int supportB = supportsKnown ? pair.lastSupportB : pair.supportBInB(directionB);
        // The enumeration's face of each body, where it carried one, proved rather than searched
        // (faceIsSelected: the same feature; the search where the proof fails).
        manifold.featureA = carry.faceA >= 0 && faceIsSelected(frame.a, carry.faceA, n, supportA, angularTolerance)
                                ? Feature{FeatureType::Face, carry.faceA}
                                : selectFeature(frame.a, n, supportA, angularTolerance);
        manifold.featureB =
            carry.faceB >= 0 && faceIsSelected(frame.b, carry.faceB, directionB, supportB, angularTolerance)
                ? Feature{FeatureType::Face, carry.faceB}
                : selectFeature(frame.b, directionB, supportB, angularTolerance);
        featurePieces(frame.a, manifold.featureA, n, angularTolerance, piecesA);
        featurePieces(frame.b, manifold.featureB, directionB, angularTolerance, piecesB);
    }
    // Stage 1's check of the growth-distance normal against the faces around the two features.
    bool preferNearbyFace(const PairFrame& frame, Vec3& normal, double& normalOverlap, const Manifold& manifold) const {
        return preferNearbyFaceNormal(frame.pair, manifold.featureA, piecesA, manifold.featureB, piecesB,
                                      frame.tolerance, knownOverlaps(), normal, normalOverlap);
    }
    // The overlaps the enumeration's carry knows (filled as the features are placed), for the
    // overhang check and refineNormal; nullptr where it did not carry.
    const KnownOverlaps* knownOverlaps() const { return carrying ? &known : nullptr; }
    // The features in A's frame. A's vertices need no placing (the identity; it differs only in
    // turning −0 into +0), B's were placed by the enumeration where it carries.
    FeatureGeometry featureA(const PairFrame& frame, const Feature& feature) {
        FeatureGeometry geometry =
            featureGeometry(frame.a, feature, piecesA, Pose{}, frame.a.vertices().data());
        faceOverlapA = carriedFaceOverlap(feature, piecesA, carry.knownA, carry.overlapA);
        manifoldFeatureA = feature.type;
        directionA = geometry.planeNormal;
        return geometry;
    }
    // refineNormal's candidates are the selected faces' normals (A's planeNormal, B's negated, which
    // is how the known overlaps are spelled) and their caps' pieces. The carried overlaps may differ
    // from the searches' in the last bits (B's support among vertices tied along the normal, found
    // in the other frame), so they are used only where that cannot change refineNormal's choice:
    // no caps, and with two faces the overlaps more than 1e-9 of the size apart (an aligned pair,
    // whose two faces overlap alike, searches as before).
    FeatureGeometry featureB(const PairFrame& frame, const Feature& feature) {
        FeatureGeometry geometry =
            featureGeometry(frame.b, feature, piecesB, frame.bInA, carry.exitKnown ? carry.verticesB.data() : nullptr);
        const double faceOverlapB = carriedFaceOverlap(feature, piecesB, carry.knownB, carry.overlapB);
        const bool faceA = manifoldFeatureA == FeatureType::Face, faceB = feature.type == FeatureType::Face;
        const bool knownA = !std::isnan(faceOverlapA), knownB = !std::isnan(faceOverlapB);
        const bool decisive = faceA && faceB ? knownA && knownB && std::abs(faceOverlapA - faceOverlapB) > 1e-9 * frame.size
                                             : (faceA && knownA) || (faceB && knownB);
        if (decisive) {
            if (knownA) known.add(directionA, faceOverlapA);
            if (knownB) known.add(-geometry.planeNormal, faceOverlapB);
        }
        return geometry;
    }
    // The enumeration's overlap along a selected face's normal: NaN where it has none, the feature
    // is no face or has a cap (more than one piece). A face index beyond the carry's 64 bits (a
    // polytope too large for the enumeration, whose `known` is empty) is never shifted by: a shift
    // of 64 or more is undefined (UBSan in the sanitize run found it on 68- and 4529-face hulls).
    static double carriedFaceOverlap(const Feature& feature, const SmallVector<int, 8>& pieces, std::uint64_t known,
                                     const std::array<double, HullGaugeCarry::kMaxFaces>& overlaps) {
        if (feature.type != FeatureType::Face || pieces.size() > 1 || feature.index >= HullGaugeCarry::kMaxFaces ||
            !((known >> feature.index) & 1))
            return NAN;
        return overlaps[feature.index];
    }
    bool refinesNormal() const { return !separatingAxis; }  // SAT's is exact already

    // The deepest contact must carry the whole penetration along n — the distance B must move
    // along n to clear A, the exit of the ray along n through A − B (ODE's contract: moving by
    // 0.96·depth still touches, 1.04·depth separates). The intersection misses it when the
    // projections do not meet (a vertex–vertex touch, or deep overlap, where the features that
    // touch when the bodies are shrunk to the growth distance drift apart at full size), or when
    // the deepest overlap lies beyond the selected features (a face–edge pair whose edge dips
    // below a neighbouring face). The supports' overlap along n bounds that distance from above, so
    // the composition asks only when the lifted points fall short of it, and the ray cast's point
    // is added only when it is deeper by more than 1 % (ODE's contract allows 4 %; the slack
    // absorbs the ray cast's accuracy on the nearly coplanar facets of A − B that near-parallel
    // faces make, where it is a few times the tilt times the size rather than the cast's
    // tolerance). The added point lies midway between the two touching witnesses, so its points on
    // A and B are position ± depth/2·n like every contact; it is never a silently missing contact.
    DepthCheck confirmDepth(const PairFrame& frame, LiftedPoints& kept, double deepest,
                            const LiftedPoint* deepestPoint, const Vec3& normal,
                            const FeatureGeometry& featureA, const FeatureGeometry& featureB) const {
        constexpr double kDepthSlack = 0.01;
        const double slack = (std::isfinite(deepest) ? kDepthSlack * std::abs(deepest) : 0.0) + frame.tolerance;
        // The ray cast converges to within its tolerance of the exit: the certificate keeps that much
        // on the safe side, so that it skips the cast only where the cast could not have added a point.
        const double certifiedSlack = slack - 2 * settings.rayCastTolerance * frame.size;
        // The exit facet of the enumeration first: a plane of A − B, so it bounds the penetration
        // along n like penetrationCertified's candidates (t* ≤ overlap(m)/(m·n) for m·n > 0), and for
        // a resting pair it is mostly the facet the line along n leaves by too (the centre line and
        // n nearly agree): the certificate without projecting the features or searching a support.
        if (deepestPoint && carry.exitKnown) {
            const Vec3& m = carry.exitDirection;
            const double along = m.dot(normal);
            if (along > 1e-6 * m.norm() && carry.exitOverlap / along <= deepestPoint->depth + certifiedSlack)
                return DepthCheck::Confirmed;
        }
        if (deepestPoint &&
            penetrationCertified(*deepestPoint, featureA, featureB, normal, frame.pair, certifiedSlack,
                                 frame.tolerance))
            return DepthCheck::Confirmed;
        const SeparationAlong separation = separationAlong(frame.pair, normal, settings);
        if (kept.empty() && separation.valid && separation.distance < -settings.margin - frame.tolerance)
            return DepthCheck::Separated;  // apart along n by more than the margin
        if (separation.valid && separation.distance > deepest + slack) {
            const Vec3 middle = 0.5 * (separation.witnessA + separation.witnessB);
            Vec3 u, v;
            planeBasis(normal, u, v);
            kept.push_back({middle, separation.distance, Vec2(middle.dot(u), middle.dot(v))});
        }
        return DepthCheck::Confirmed;
    }
};

}  // namespace

namespace {
// The general hooks (default paths) for a caller that needs the points only in `order`.
template <ImportanceOrder order>
struct GeneralPairHooksIn : GeneralPairHooks {
    static constexpr ImportanceOrder kOrder = order;
    explicit GeneralPairHooksIn(const Settings& settings) : GeneralPairHooks(settings) {}
};
}  // namespace

template <ImportanceOrder order>
void collideGeneralInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                        const Settings& settings, Manifold& out) {
    GeneralPairHooksIn<order> hooks(settings);
    composeStages(hooks, a, poseA, b, poseB, settings, out);  // never delegates
}
template void collideGeneralInto<ImportanceOrder::Full>(const Polytope&, const Pose&, const Polytope&, const Pose&,
                                                        const Settings&, Manifold&);
template void collideGeneralInto<ImportanceOrder::AmongEqualDepths>(const Polytope&, const Pose&, const Polytope&,
                                                                    const Pose&, const Settings&, Manifold&);

}  // namespace detail

// The public queries: the pair table's cell for the shapes' kinds.
Manifold collide(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                 const Settings& settings) {
    Manifold manifold;
    detail::collidePair(detail::Shape::of(a), poseA, detail::Shape::of(b), poseB, detail::PairQuery{settings}, manifold);
    return manifold;
}

Manifold collide(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings) {
    const detail::UnitHalfSpace plane = detail::enterHalfSpace(poseA, b);
    Manifold manifold;
    detail::collidePair(detail::Shape::of(a), poseA, detail::Shape::of(plane), Pose{}, detail::PairQuery{settings},
                        manifold);
    return manifold;
}

namespace {

// A public shape as the table takes it, its size checked where it enters (enterRound); a
// half-space normalised into `plane`.
detail::Shape enter(const ShapeRef& shape, const char* which, detail::UnitHalfSpace& plane) {
    switch (shape.kind()) {
        case ShapeRef::Kind::Polytope: return detail::Shape::of(*shape.polytope());
        case ShapeRef::Kind::HalfSpace:
            plane = detail::normaliseHalfSpace(shape.halfSpace());
            return detail::Shape::of(plane);
        default: return detail::enterRound(shape.kind(), shape.radius(), shape.length(), which);
    }
}

}  // namespace

Manifold collide(const ShapeRef& a, const Pose& poseA, const ShapeRef& b, const Pose& poseB, const Settings& settings) {
    // The poses first (a bad pose is reported before a bad shape), as the other queries do.
    if (a.kind() != ShapeRef::Kind::HalfSpace && !poseA.isFinite()) detail::throwPoseNotFinite("A");
    if (b.kind() != ShapeRef::Kind::HalfSpace && !poseB.isFinite()) detail::throwPoseNotFinite("B");
    detail::UnitHalfSpace planeA{}, planeB{};
    const detail::Shape shapeA = enter(a, "A", planeA), shapeB = enter(b, "B", planeB);
    Manifold manifold;
    detail::collidePair(shapeA, poseA, shapeB, poseB, detail::PairQuery{settings}, manifold);
    return manifold;
}

}  // namespace gdc

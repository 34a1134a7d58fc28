// The polytope–half-space query as hooks of the one composition (pipeline.hpp, composeStages): the
// plane supplies the normal (stage 1: −m), the shape its support along it (whose depth is the
// separation test), its Gauss-map feature (stage 2) and each vertex's depth; stage 3 lifts the
// feature onto the plane and ranks and emits its points (plane_contacts.hpp). Three shapes: a
// box's closed forms (box_shape.hpp), a small hull's one loop over its vertices (every depth and
// the support at once), any polytope's support search and Gauss map (collideGeneral, the reference
// the other two are tested equal to: tests/half_space_test.cpp runs them on random poses). Every
// hook computes the same numbers by the same floating-point expressions, so the three return the
// same Manifold. collide() dispatches.
#include "contact/half_space.hpp"

#include "shapes/box_shape.hpp"
#include "contact/collide_general.hpp"
#include "contact/gauss_map.hpp"
#include "contact/pipeline.hpp"
#include "geometry/small_vector.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {
namespace {

// What the three shapes' hooks share: a plane never delegates, never has its normal checked for
// an overhang (it is exact), and its feature is its one face (its Gauss map is the single point −n).
struct OnPlaneHooks {
    static constexpr bool kDelegatesRareCases = false;
    static bool preferNearbyFace(const HalfSpaceFrame&, Vec3&, double&, const Manifold&) { return false; }
    static Feature planeFeature() { return {FeatureType::Face, 0}; }
    int deepest = 0;  // A's support along −m (stage 1), where stage 2's feature search starts
    static constexpr ImportanceOrder kOrder = ImportanceOrder::Full;  // what stage 3 ranks (half_space.hpp)
};

// A box: the closed-form support and Gauss-map feature (box_shape.hpp); a box's face is its whole
// cap (no other face lies within a tolerance below π/4).
struct BoxOnPlaneHooks : OnPlaneHooks {
    explicit BoxOnPlaneHooks(const Settings& settings) : settings(settings) {}
    const Settings& settings;
    const Vec3* vertices = nullptr;

    double supportDepth(const HalfSpaceFrame& frame, const Vec3& normal) {
        deepest = boxSupport(normal);
        vertices = frame.a.vertices().data();
        return frame.plane.depthOf(vertices[deepest]);
    }
    void selectFeatures(const HalfSpaceFrame&, const Vec3& normal, bool /*first*/, Manifold& manifold) {
        LazyAngularTolerance angularTolerance(settings.angularTolerance);
        manifold.featureA = selectBoxFeature(normal, deepest, angularTolerance);
        manifold.featureB = planeFeature();
    }
    static constexpr const SmallVector<int, 8>* cap() { return nullptr; }
    double depthOf(const HalfSpaceFrame& frame, int v) const { return frame.plane.depthOf(vertices[v]); }
};

// A small hull: one loop over its vertices gives every height m·x along the plane's normal and
// the lowest one — the support along −m, the first of equals as supportVertex's brute force finds
// it (x·(−m) is −(m·x) to the bit) — so each depth is a subtraction afterwards.
struct SmallHullOnPlaneHooks : OnPlaneHooks {
    // `given`: AngularTolerance(settings.angularTolerance), when the caller keeps it; else made here.
    SmallHullOnPlaneHooks(const Settings& settings, const AngularTolerance* given) : settings(settings), given(given) {}
    const Settings& settings;
    const AngularTolerance* given;
    double heights[kMaxSmallHullVertices];
    SmallVector<int, 8> capFaces;
    bool hasCap = false;

    double supportDepth(const HalfSpaceFrame& frame, const Vec3&) {
        const std::vector<Vec3>& vertices = frame.a.vertices();
        const Vec3& m = frame.plane.m;
        const int vertexCount = static_cast<int>(vertices.size());
        int lowestVertex = 0;
        double lowest = heights[0] = m.dot(vertices[0]);
        for (int v = 1; v < vertexCount; ++v) {
            const double height = heights[v] = m.dot(vertices[v]);
            if (height < lowest) lowest = height, lowestVertex = v;
        }
        deepest = lowestVertex;
        return frame.plane.offset - lowest;
    }
    void selectFeatures(const HalfSpaceFrame& frame, const Vec3& normal, bool /*first*/, Manifold& manifold) {
        // Made after stage 1's separation test: a separated pair never needs its cosine and sine.
        const AngularTolerance angularTolerance = given ? *given : AngularTolerance(settings.angularTolerance);
        manifold.featureA = selectFeature(frame.a, normal, deepest, angularTolerance);
        manifold.featureB = planeFeature();
        hasCap = manifold.featureA.type == FeatureType::Face &&
                 (faceCap(frame.a, manifold.featureA.index, normal, angularTolerance, capFaces), capFaces.size() > 1);
    }
    const SmallVector<int, 8>* cap() const { return hasCap ? &capFaces : nullptr; }
    double depthOf(const HalfSpaceFrame& frame, int v) const { return frame.plane.offset - heights[v]; }
};

// Any polytope (the general path): the support by Polytope::supportVertex (the brute force up to
// Settings::bruteForceSupportLimit vertices, hill climbing over the adjacency above), the feature
// and its cap by the Gauss map, each depth from the plane where it is needed.
struct AnyPolytopeOnPlaneHooks : OnPlaneHooks {
    explicit AnyPolytopeOnPlaneHooks(const Settings& settings) : settings(settings) {}
    const Settings& settings;
    SmallVector<int, 8> capFaces;  // a face's whole cap of near-coplanar faces rests on the plane
    bool hasCap = false;

    double supportDepth(const HalfSpaceFrame& frame, const Vec3& normal) {
        deepest = frame.a.supportVertex(normal, settings.bruteForceSupportLimit);
        return frame.plane.depthOf(frame.a.vertices()[deepest]);
    }
    void selectFeatures(const HalfSpaceFrame& frame, const Vec3& normal, bool /*first*/, Manifold& manifold) {
        const AngularTolerance angularTolerance(settings.angularTolerance);
        manifold.featureA = selectFeature(frame.a, normal, deepest, angularTolerance);
        manifold.featureB = planeFeature();
        hasCap = manifold.featureA.type == FeatureType::Face &&
                 (faceCap(frame.a, manifold.featureA.index, normal, angularTolerance, capFaces), capFaces.size() > 1);
    }
    const SmallVector<int, 8>* cap() const { return hasCap ? &capFaces : nullptr; }
    double depthOf(const HalfSpaceFrame& frame, int v) const { return frame.plane.depthOf(frame.a.vertices()[v]); }
};

// The entry points write into `manifold` (the caller's; composeStages resets it to an empty
// answer): a Manifold made here and copied out cost its 0.5 KB of zeroed points on every call.
// Each shape's composition is a function of its own, called straight from the entry points:
// inlined into one dispatcher, each made the other's queries dearer (docs/benchmarks.md).
// A shape's hooks asking stage 3 for the points in `order` (a template argument: the ranking's
// test is compiled out of the Full path, which stays the instructions it was).
template <class Hooks, ImportanceOrder order>
struct Ordered : Hooks {
    using Hooks::Hooks;
    static constexpr ImportanceOrder kOrder = order;
};

template <ImportanceOrder order>
[[gnu::noinline]] void collideBox(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b, const Settings& settings,
                                  Manifold& manifold) {
    Ordered<BoxOnPlaneHooks, order> hooks(settings);
    composeStages(hooks, halfSpaceFrame(a, poseA, b), poseA, settings, manifold);
}

template <ImportanceOrder order>
[[gnu::noinline]] void collideSmallHull(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b,
                                        const Settings& settings, const AngularTolerance* given, Manifold& manifold) {
    Ordered<SmallHullOnPlaneHooks, order> hooks(settings, given);
    composeStages(hooks, halfSpaceFrame(a, poseA, b), poseA, settings, manifold);
}

void collideAnyPolytope(const HalfSpaceFrame& frame, const Pose& poseA, const Settings& settings, Manifold& manifold) {
    AnyPolytopeOnPlaneHooks hooks(settings);
    composeStages(hooks, frame, poseA, settings, manifold);
}

}  // namespace

void throwBadHalfSpace(bool overflow) {
    throw InvalidInput(overflow ? "the half-space offset overflows double precision once its normal is normalised"
                                : "the half-space normal must be finite and non-zero");
}

template <ImportanceOrder order>
void collideHalfSpaceInto(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b, const Settings& settings,
                          const AngularTolerance* angularTolerance, Manifold& out) {
    a.isBox() ? collideBox<order>(a, poseA, b, settings, out)
              : collideSmallHull<order>(a, poseA, b, settings, angularTolerance, out);
}
template void collideHalfSpaceInto<ImportanceOrder::Full>(const Polytope&, const Pose&, const UnitHalfSpace&,
                                                          const Settings&, const AngularTolerance*, Manifold&);
template void collideHalfSpaceInto<ImportanceOrder::AmongEqualDepths>(const Polytope&, const Pose&,
                                                                      const UnitHalfSpace&, const Settings&,
                                                                      const AngularTolerance*, Manifold&);

void collideGeneralInto(const Polytope& a, const Pose& poseA, const UnitHalfSpace& b, const Settings& settings,
                        Manifold& out) {
    collideAnyPolytope(halfSpaceFrame(a, poseA, b), poseA, settings, out);
}

}  // namespace gdc::detail

// Contact tracking: the "well-known" baseline the paper compares against. A persistent manifold in
// the manner of Bullet's btPersistentManifold: each step libccd's MPR yields ONE new contact point;
// points are stored in both bodies' local frames, refreshed every step from the new poses, dropped
// when they separate or slide past a breaking threshold, and at most `maxPoints` are kept (the
// deepest, plus the set spanning the largest area). Lives beside the gdcontact core, not inside it:
// it only uses the core's value types (Polytope, Pose, Manifold). No ODE here.
//
// Not thread-safe per object (it is state); distinct objects are independent (no global state).
#pragma once

#include <gdcontact/collide.hpp>
#include <gdcontact/manifold.hpp>
#include <gdcontact/polytope.hpp>
#include <gdcontact/types.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>

namespace gdc::tracking {

/// Every tunable of the tracking baseline, with its unit and the trade-off it controls.
/// Lengths are in the scene's length unit (metres in the samples); like Bullet, the thresholds are
/// absolute, so they must be scaled with the scene.
struct TrackingSettings {
    /// Metres. A stored point whose anchors on A and B drift apart tangentially (perpendicular to
    /// the normal) by more than this, or separate along the normal by more than this, is dropped.
    /// Larger: points survive longer (more points, stabler support) but stale points that no
    /// longer touch act as phantom contacts; smaller: points are lost at the first sliding or
    /// bounce and the manifold degenerates towards MPR's single point. Bullet's default is 0.02.
    double breakingThreshold = 0.02;

    /// Count, 1…kMaxManifoldPoints. Most points kept per pair. Bullet keeps 4 (enough to span a
    /// face); more gives a finer support polygon at a higher solver cost, fewer a wobblier support.
    int maxPoints = 4;

    /// Metres. A new MPR point whose anchor on A lies within this distance of a stored point's
    /// anchor on A replaces that point (refreshing it) instead of taking a slot of its own, as
    /// Bullet does with its breaking threshold. Larger: fewer near-duplicate points, but a resting
    /// contact needs larger motions to collect distinct points; smaller: clusters of almost
    /// identical points that add nothing to the support area.
    double mergeDistance = 0.02;

    /// Metres, ≥ 0. Stored points are reported in update()'s manifold while their depth is at
    /// least −speculativeMargin. 0 reports only touching/overlapping points (what ODE needs: a
    /// negative-depth contact makes a body hover); positive values report speculative points of a
    /// pair that has just separated a little (they stay stored until breakingThreshold either way).
    double speculativeMargin = 0.0;

    /// Unitless, relative to the pair's size (sum of the two polytopes' radii). libccd's MPR portal
    /// tolerance is this times the size. Smaller: a more exact MPR depth and normal, a few more
    /// MPR iterations. Relative, so the same value works at any scale.
    double mprRelativeTolerance = 1e-8;

    /// Count. Cap on libccd's penetration refinement iterations (its `max_iterations`). Reached
    /// only for nearly degenerate portals; lower bounds the worst-case time at the price of a
    /// coarser normal in those cases.
    int maxMprIterations = 100;
};

/// One stored contact point.
struct TrackedPoint {
    Vec3 anchorOnA = Vec3::Zero();  ///< in A's local frame: the point of A's surface at the contact
    Vec3 anchorOnB = Vec3::Zero();  ///< in B's local frame: the point of B's surface at the contact
    Vec3 worldOnA = Vec3::Zero();   ///< anchorOnA in the world, as of the last update()
    Vec3 worldOnB = Vec3::Zero();   ///< anchorOnB in the world, as of the last update()
    /// (worldOnA − worldOnB)·normal as of the last update(): ≥ 0 overlapping, < 0 separated.
    double depth = 0.0;
    /// Number of update() calls this point has survived since it was created or last merged with
    /// a new MPR point (0: created or refreshed from MPR in the last update).
    int age = 0;
};

/// What the last update() did (for diagnostics, samples and tests).
struct UpdateReport {
    bool mprFoundContact = false;   ///< libccd's MPR reported an overlap with a usable normal
    int dropped = 0;                ///< stored points dropped by the breaking threshold this step
    int mergedInto = -1;            ///< index the new point was merged into, or −1
    int added = -1;                 ///< index of the slot the new point took (free or replaced), or −1
    bool replacedExisting = false;  ///< the manifold was full and `added` replaced a stored point
};

/// The persistent manifold of ONE pair of convex shapes (this object is the per-pair state).
class PersistentManifold {
public:
    /// Throws gdc::InvalidInput for settings out of range (non-positive or non-finite thresholds,
    /// maxPoints outside 1…kMaxManifoldPoints, negative margin, non-positive tolerance/iterations).
    explicit PersistentManifold(TrackingSettings settings = {});

    /// One step:
    ///  1. libccd's MPR (ccdMPRPenetration) on the two polytopes at the new poses gives a normal and
    ///     one point in the overlap; its anchors are where the line through that point along the
    ///     normal leaves A (towards B) and leaves B (towards A);
    ///  2. stored points are refreshed from the new poses along the current normal (MPR's, or when
    ///     MPR finds no overlap the previous one carried along with B's rotation) and dropped when
    ///     they separate or drift tangentially by more than breakingThreshold;
    ///  3. the new point merges with a stored point closer than mergeDistance, else takes a free
    ///     slot, else replaces a stored point: never the deepest; the one whose removal leaves the
    ///     largest support area (Bullet's rule, with the exact 2-D hull area in the contact plane).
    /// Returns the stored points with depth ≥ −speculativeMargin as a gdc::Manifold: normal from A
    /// towards B (the core's convention), each point its own depth, position midway between its two
    /// anchors. Empty when no point qualifies. Throws gdc::InvalidInput for non-finite poses.
    /// Computed relative to poseA's position, so far-from-origin scenes keep their precision.
    Manifold update(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB);

    /// The same step against a solid half-space B (an ODE plane), normal −b.normal as in the core.
    /// MPR needs a bounded shape, so B is stood in for by a cube of half size 4·radius(A) whose top
    /// face lies in the plane, centred under A's centroid; B's anchors are kept in a frame fixed to
    /// the plane, so they do not move with that stand-in. Use one object per pair: do not mix the
    /// two overloads on one manifold. Throws gdc::InvalidInput for a non-finite pose or a zero or
    /// non-finite plane normal or offset.
    Manifold update(const Polytope& a, const Pose& poseA, const HalfSpace& b);

    int pointCount() const { return count_; }
    /// Stored point i (0 ≤ i < pointCount()), including ones not reported for being separated.
    const TrackedPoint& point(int index) const;
    /// World normal (from A towards B) of the last update(); meaningful when hasNormal().
    const Vec3& normal() const { return normalWorld_; }
    bool hasNormal() const { return hasNormal_; }
    const UpdateReport& lastUpdate() const { return report_; }
    const TrackingSettings& settings() const { return settings_; }

    /// Forget every point and the normal (the pair stopped touching).
    void clear();
    /// Exchange the roles of A and B (anchors swapped, normal negated), so the same state can be
    /// used by a caller that passes the pair in the other order. PairCache does this for you.
    void swapBodies();

private:
    // The step behind both update()s. MPR runs on `b` placed at `mprPoseB`; B's anchors live in
    // the frame `anchorPoseB` (the same pose for a polytope, the plane's frame for a half-space).
    Manifold step(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& mprPoseB,
                  const Pose& anchorPoseB);
    // Both take poses relative to `origin` (pose A's position) and store world points.
    void refresh(const Pose& poseA, const Pose& poseB, const Vec3& origin);
    void insert(const TrackedPoint& candidate, const Vec3& origin);

    TrackingSettings settings_;
    std::array<TrackedPoint, kMaxManifoldPoints> points_{};
    int count_ = 0;
    Vec3 normalWorld_ = Vec3::UnitZ();
    Vec3 normalInA_ = Vec3::UnitZ();  ///< the normal in A's frame (needed by swapBodies())
    Vec3 normalInB_ = Vec3::UnitZ();  ///< the normal in B's frame, to carry it through MPR misses
    bool hasNormal_ = false;
    UpdateReport report_;
    std::optional<Polytope> proxy_;  ///< the half-space's stand-in box, rebuilt when A's size changes
    double proxyHalfSize_ = 0.0;
};

/// Bullet's replacement rule, generalised to any count and made exact. `stored` are the stored
/// points projected onto the contact plane (2-D, `count` of them, 1 ≤ count ≤ kMaxManifoldPoints),
/// `depths` their depths; the candidate is the new point. The deepest of all count + 1 points is
/// never removed, and the new point is always kept (it is the freshest information). Returns the
/// index of the stored point whose removal leaves the convex hull of the remaining points with the
/// largest area (ties: the largest perimeter, then the lowest index), or −1 when no stored point
/// may be removed (count == 1 and that point is deeper than the candidate).
int choosePointToReplace(const Vec2* stored, const double* depths, int count, const Vec2& candidate,
                         double candidateDepth);

/// Area of the convex hull of `count` 2-D points (0 for fewer than 3 or collinear points).
double convexHullArea(const Vec2* points, int count);

/// Per-pair state for a whole scene, keyed by an opaque, order-insensitive pair key (e.g. two ODE
/// geom pointers). Each step: beginStep(); manifoldFor(first, second) for each pair the broad
/// phase reports; endStep() drops the state of pairs not asked for since beginStep() — "cleaned up
/// when pairs stop touching".
class PairCache {
public:
    explicit PairCache(TrackingSettings settings = {});

    void beginStep();
    /// The manifold of the pair {first, second}, created empty on first use. Normalised
    /// internally: the returned manifold always has A = first and B = second — when a pair is
    /// asked for in the opposite order to last time, its state is swapped (swapBodies()) before
    /// it is returned, so the caller simply calls update(shapeOf(first), …, shapeOf(second), …).
    /// The reference stays valid until endStep() drops this pair or clear() is called.
    /// Throws gdc::InvalidInput for a null key or first == second.
    PersistentManifold& manifoldFor(const void* first, const void* second);
    /// Drop the state of every pair not passed to manifoldFor() since the last beginStep().
    void endStep();

    bool contains(const void* first, const void* second) const;
    std::size_t size() const { return pairs_.size(); }
    void clear() { pairs_.clear(); }

private:
    struct Key {
        std::uintptr_t low, high;
        bool operator==(const Key& other) const { return low == other.low && high == other.high; }
    };
    struct KeyHash {
        std::size_t operator()(const Key& key) const;
    };
    struct Entry {
        PersistentManifold manifold;
        const void* first;       ///< the body the manifold currently treats as A
        std::uint64_t lastSeen;  ///< step number of the last manifoldFor() for this pair
    };
    static Key makeKey(const void* first, const void* second);

    TrackingSettings settings_;
    std::unordered_map<Key, Entry, KeyHash> pairs_;
    std::uint64_t step_ = 0;
};

}  // namespace gdc::tracking

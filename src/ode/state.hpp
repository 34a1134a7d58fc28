// The adapter's process-wide state: the convex registry, the box-polytope cache and the installed
// settings. This is the one place in gdcontact with global mutable state, and it exists because
// ODE leaves no other choice: a dColliderFn carries no user pointer (so the installed settings
// must be found globally), ODE 0.16.2 has no getter for a dConvex's data (so the hull of a
// createConvex geom must be found by the geom's address) and no geom-destroy callback (so the
// registry learns of a destroyed geom through ODE's free handler). The core stays pure.
//
// collide() runs for every pair on every step, so its lookups take no lock and touch no reference
// count: a hull is found in a lock-free index of geom addresses (state.cpp) at any scene size; box
// polytopes and the settings come from per-thread caches, with a generation counter per shared
// value telling a thread when its copy may be stale. Everything else is guarded by locks.
#pragma once

#include <gdcontact/manifold.hpp>
#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>

#include <ode/ode.h>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace gdc::ode::detail {

/// What gdcontact keeps for one createConvex geom.
struct ConvexRecord {
    std::shared_ptr<const Polytope> polytope;
    // The arrays handed to dCreateConvex. ODE keeps only pointers to them, so they must live
    // exactly as long as the geom: the record is dropped when ODE frees the geom's memory.
    std::vector<dReal> planes;
    std::vector<dReal> points;
    std::vector<unsigned> polygons;
};

/// Puts the adapter's free hook (the only notice of a geom's end ODE gives: it forgets the geom's
/// hull and its pair-cache entries) in front of ODE's free handler, if it is not there already.
void ensureFreeHook();

/// Creates the dConvex for `record` (whose arrays must be filled) in `space` and registers it.
dGeomID createRegisteredConvex(dSpaceID space, std::shared_ptr<ConvexRecord> record);

/// The hull of a createConvex geom; nullptr for a geom gdcontact did not create.
std::shared_ptr<const Polytope> registeredConvex(dGeomID geom);

/// Number of live registered convex geoms.
std::size_t registeredConvexCount();

/// For tests: the slots of the convex index collide() reads, the replaced index tables not yet
/// freed because some thread may still be reading them (at most one per thread), and how many
/// tables have been published (each growth, shrink or clean-up of tombstones publishes one).
struct ConvexIndexStats {
    std::size_t capacity;
    std::size_t retiredTables;
    std::size_t tablesPublished;
};
ConvexIndexStats convexIndexStats();

/// A box polytope of the given half extents, shared between all boxes of that size (bounded
/// cache: building a Polytope allocates, and box–box must be cheap).
std::shared_ptr<const Polytope> boxPolytope(double halfX, double halfY, double halfZ);

void setInstalledSettings(const Settings& settings);

/// Whether ODE is initialised (between dInitODE2() and its matching dCloseODE()). ODE 0.16.2 has
/// no public query and asserts inside (without naming the call order) when install() runs
/// before dInitODE2(); Debian's libode exports the hook its initialisation sets (dlsym), so this
/// reads it. True when the hook is not exported (another build of ODE): then it cannot tell.
bool odeIsInitialized();

/// Whether the geom's AABB (which ODE computes from the points it holds) is that of `hull` at
/// `pose` (within rounding), along the first `axes` world axes (1: x only, two support queries;
/// 3: the whole box). False after dGeomSetConvex gave the geom other points.
bool matchesAabb(const Polytope& hull, const Pose& pose, dGeomID geom, int bruteForceLimit, int axes);

// ---- collide()'s lookups: no lock and no reference count on a hit ----

/// Box sizes a thread keeps at once (least recently used evicted).
constexpr int kBorrowedBoxSizes = 8;

struct ConvexIndexReader;  // a thread's hazard slot for the convex index (state.cpp)

/// What one thread keeps so that collide() neither locks nor writes shared memory in the common
/// case. Get it with threadCache(); the lookups below take it so that one call reaches it once.
struct ThreadCache {
    ThreadCache() = default;
    ThreadCache(const ThreadCache&) = delete;
    ThreadCache& operator=(const ThreadCache&) = delete;
    ~ThreadCache();  // gives the thread's convex index slot back

    struct BoxSlot {
        double halfExtents[3] = {NAN, NAN, NAN};    // NaN: never equal, so an empty slot never hits
        std::shared_ptr<const Polytope> polytope;  // keeps the borrowed polytope alive
        std::uint64_t lastUse = 0;
    };
    BoxSlot boxes[kBorrowedBoxSizes];
    std::uint64_t boxClock = 0;
    int lastBox = 0;  // checked first: a scene's boxes mostly share a few sizes

    // This thread's claim on the convex index (state.cpp): the hazard slot announcing the index
    // table it may be reading, and that table. nullptr until the thread's first hull lookup.
    ConvexIndexReader* convexReader = nullptr;
    const void* protectedConvexTable = nullptr;

    struct PlaneSlot {
        double raw[4] = {NAN, NAN, NAN, NAN};  // a, b, c, d; NaN: never equal, so an empty slot never hits
        Vec3 unit = Vec3::Zero();              // (a, b, c) normalised: the HalfSpace the core is given
        // The core's own normalisation of that half-space (normaliseHalfSpace, half_space.hpp),
        // made once per plane instead of per call; false where it refuses the plane (then every
        // call takes the core's full path, which says why).
        bool normalised = false;
        Vec3 normalisedNormal = Vec3::Zero();
        double normalisedOffset = 0;
    };
    static constexpr int kPlaneSlots = 4;
    PlaneSlot planes[kPlaneSlots];
    int lastPlane = 0;  // also the next slot to refill (round robin)

    // Where the x-extent check of a convex's AABB (collide.cpp) found the hull's extreme vertices
    // last time, per geom (direct-mapped by address): the next check climbs from there, a few
    // steps for a body that moved a little. Only a hint: a stale entry costs a longer climb.
    // With it, the inputs of the last check that passed (the hull, the bytes of the pose's first
    // rotation row and position, and of the AABB's x extent): the check is a function of exactly
    // these, so the same inputs pass again without the support queries — a geom in several pairs
    // of a step is checked once (verifiedHull null: nothing verified). Valid only while no
    // registered convex has been forgotten since (convexesForgotten): a new geom and hull may take
    // a freed one's addresses.
    struct AabbHint {
        const void* geom = nullptr;
        int lower = -1;
        int upper = -1;
        const Polytope* verifiedHull = nullptr;
        std::uint64_t verifiedGeneration = 0;
        double verifiedInputs[8] = {};
    };
    static constexpr int kAabbHints = 256;  // 22 KB a thread; at 64, 16 geoms already evicted each other
    AabbHint aabbHints[kAabbHints];

    std::uint64_t settingsGeneration = 0;  // 0: never copied
    Settings settings;

    // Where collide() keeps an answer that is not in a pair cache (no cache, or a carried one)
    // until it is written out: one per thread, so that a call constructs no 0.6 KB Manifold.
    Manifold scratch;
};

inline ThreadCache& threadCache() {
    thread_local ThreadCache cache;
    return cache;
}

/// The hull of a createConvex geom for collide(): borrowed, not shared. It stays valid while the
/// geom lives, since a hull is released only when ODE frees its geom, and a geom may not be
/// destroyed while it is being collided. nullptr for a geom gdcontact did not create.
/// O(1) expected at any number of hulls; takes no lock and never waits for a writer.
const Polytope* borrowedConvex(ThreadCache& cache, dGeomID geom);

/// As boxPolytope, for collide(): borrowed from the thread's cache. The reference stays valid
/// until this thread has looked up kBorrowedBoxSizes − 1 other sizes, which covers both boxes
/// of one pair.
const Polytope& borrowedBoxPolytopeSlow(ThreadCache& cache, double halfX, double halfY, double halfZ);
inline const Polytope& borrowedBoxPolytope(ThreadCache& cache, double halfX, double halfY, double halfZ) {
    ThreadCache::BoxSlot& last = cache.boxes[cache.lastBox];
    if (last.halfExtents[0] == halfX && last.halfExtents[1] == halfY && last.halfExtents[2] == halfZ) {
        last.lastUse = ++cache.boxClock;
        return *last.polytope;
    }
    return borrowedBoxPolytopeSlow(cache, halfX, halfY, halfZ);
}

/// The plane a·x + b·y + c·z = d as the core takes it — (a, b, c) scaled to unit length exactly as
/// Vec3(a, b, c).normalized() gives it, and the core's normalisation of that half-space —
/// remembered for the thread's last few planes: a scene has few planes, and the square roots and
/// divisions in a chain were a fifth of a cheap box–plane call's time. Valid until this thread
/// looks up kPlaneSlots other planes.
const ThreadCache::PlaneSlot& planeSlotSlow(ThreadCache& cache, double a, double b, double c, double d);
inline const ThreadCache::PlaneSlot& planeSlot(ThreadCache& cache, double a, double b, double c, double d) {
    const ThreadCache::PlaneSlot& last = cache.planes[cache.lastPlane];
    if (last.raw[0] == a && last.raw[1] == b && last.raw[2] == c && last.raw[3] == d) return last;
    return planeSlotSlow(cache, a, b, c, d);
}

/// Advanced whenever the free hook forgets a registered convex (its geom was freed): the
/// per-thread AABB memos (ThreadCache::AabbHint) taken before are void.
extern std::atomic<std::uint64_t> convexesForgotten;

/// Advanced by every install() (under the settings lock); starts at 1, so that a thread's
/// never-filled copy (generation 0) is stale.
extern std::atomic<std::uint64_t> installedSettingsGeneration;

/// The settings of the last install() (defaults before), as the thread's copy, refreshed when
/// install() has run since it was taken. Valid until this thread's next lookup.
const Settings& refreshInstalledSettings(ThreadCache& cache);
inline const Settings& installedSettings(ThreadCache& cache) {
    if (cache.settingsGeneration == installedSettingsGeneration.load(std::memory_order_acquire))
        return cache.settings;
    return refreshInstalledSettings(cache);
}

}  // namespace gdc::ode::detail

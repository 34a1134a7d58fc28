// What one thread keeps so that collide() neither locks nor writes shared memory in the common
// case: the box polytopes and planes it met last, where it found each hull's AABB extremes, its
// copy of the installed settings, and a scratch manifold. The lookups that fill it live with what
// they look up (box_cache, installed_settings, convex_registry); the plane cache is here, since it
// has no shared side.
#pragma once

#include <gdcontact/collide.hpp>
#include <gdcontact/manifold.hpp>
#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>

#include "contact/gauss_map.hpp"
#include "contact/half_space.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

namespace gdc::ode::detail {

/// Box sizes a thread keeps at once (least recently used evicted).
constexpr int kBorrowedBoxSizes = 8;
static_assert(kBorrowedBoxSizes >= 3, "one pair's two boxes must both survive the second lookup");

/// Get it with threadCache(); the lookups take it so that one call reaches it once.
struct ThreadCache {
    ThreadCache() = default;
    ThreadCache(const ThreadCache&) = delete;
    ThreadCache& operator=(const ThreadCache&) = delete;

    struct BoxSlot {
        double halfExtents[3] = {NAN, NAN, NAN};    // NaN: never equal, so an empty slot never hits
        // The box lengths (twice the half extents) the slot was last found for, as ODE gave them:
        // the last slot's are compared by their bytes, integer compares in place of the half
        // extents' products and floating-point compares (borrowedBoxPolytope).
        double lengths[3] = {NAN, NAN, NAN};
        std::shared_ptr<const Polytope> polytope;  // keeps the borrowed polytope alive
        std::uint64_t lastUse = 0;
    };
    BoxSlot boxes[kBorrowedBoxSizes];
    std::uint64_t boxClock = 0;
    int lastBox = 0;  // checked first: a scene's boxes mostly share a few sizes
    // While set (spaceCollide, for the pairs it resolved on this thread and collides later), a
    // box polytope evicted from `boxes` is kept here instead of released: borrowed references
    // then stay valid until the owner of the vector clears it.
    std::vector<std::shared_ptr<const Polytope>>* pinnedBoxes = nullptr;

    struct PlaneSlot {
        double raw[4] = {NAN, NAN, NAN, NAN};  // a, b, c, d; NaN: never equal, so an empty slot never hits
        // (a, b, c) normalised and d: the HalfSpace the core is given. As the core takes them, so
        // that a query is handed these by reference, not copied per call.
        HalfSpace halfSpace{Vec3::Zero(), 0.0};
        // The core's own normalisation of that half-space (normaliseHalfSpace, half_space.hpp),
        // made once per plane instead of per call; false where it refuses the plane (then every
        // call takes the core's full path, which says why).
        bool normalised = false;
        gdc::detail::UnitHalfSpace normalisedHalfSpace{Vec3::Zero(), 0.0};
    };
    static constexpr int kPlaneSlots = 4;
    PlaneSlot planes[kPlaneSlots];
    int lastPlane = 0;  // also the next slot to refill (round robin)

    // What this thread remembers of a convex geom (by address), both looked up by one search of
    // its set (geomMemo): before, two direct-mapped tables of 256 entries each took a hash and a
    // compare per geom, and two geoms whose addresses hashed alike evicted each other's entries on
    // every call, paying the two support queries again. Four-way set-associative, the least recently used
    // evicted: the same 256 entries, and five geoms must share a set before one misses.
    struct GeomMemo {
        const void* geom = nullptr;
        std::uint64_t lastUse = 0;  // geomClock when last looked up
        // The hull the registry gave for the geom, while no registered convex has been forgotten
        // or distrusted since (convexesForgotten, hullGeneration): then the geom at that address is
        // still the one registered with that hull, and collide() takes no lock
        // (convex_registry.cpp). nullptr: none remembered.
        const Polytope* hull = nullptr;
        std::uint64_t hullGeneration = 0;
        // Where the x-extent check of the geom's AABB (collide.cpp) found the hull's extreme
        // vertices last time: the next check climbs from there, a few steps for a body that moved a
        // little. Only a hint: a stale entry costs a longer climb (-1: none).
        int lower = -1;
        int upper = -1;
        // The inputs of the last check that passed (the hull, the bytes of the pose's first
        // rotation row and position, and of the AABB's x extent): the check is a function of
        // exactly these, so the same inputs pass again without the support queries — a geom in
        // several pairs of a step is checked once (verifiedHull null: nothing verified). Valid only
        // while no registered convex has been forgotten since (convexesForgotten): a new geom and
        // hull may take a freed one's addresses.
        const Polytope* verifiedHull = nullptr;
        std::uint64_t verifiedGeneration = 0;
        double verifiedInputs[8] = {};
    };
    static constexpr int kGeomMemoSets = 64;
    static constexpr int kGeomMemoWays = 4;
    GeomMemo geomMemos[kGeomMemoSets][kGeomMemoWays];  // 26 KB a thread
    std::uint64_t geomClock = 0;

    std::uint64_t settingsGeneration = 0;  // 0: never copied
    Settings settings;

    // The Gauss-map tolerance (cosine, sine) of the last Settings::angularTolerance a hull–plane
    // query used, kept while the radians stay the same (angularToleranceOf): its cosine and sine
    // are not recomputed per query. It starts as the tolerance of 0.0 rad, whose bits are 0.
    std::uint64_t angularToleranceBits = 0;
    gdc::detail::AngularTolerance angularTolerance{0.0};

    // Where collide() keeps an answer that is not in a pair cache (no cache, or a carried one)
    // until it is written out: one per thread, so that a call constructs no 0.6 KB Manifold.
    Manifold scratch;
    // Where a pair cache's answer carried along with the bodies is written: apart from scratch, so
    // that writeContacts knows the core's own answers (checked finite) by their address.
    Manifold carried;
};

/// The thread's memo of `geom` (ThreadCache::GeomMemo): the one it holds, or else a fresh one for
/// `geom` in place of its set's least recently used. Fibonacci hashing of the address (allocators
/// space geoms regularly), its top 6 bits, picks the set.
inline ThreadCache::GeomMemo& geomMemo(ThreadCache& cache, const void* geom) {
    static_assert(ThreadCache::kGeomMemoSets == 64 && ThreadCache::kGeomMemoWays == 4,
                  "the hash takes the top 6 bits; the search looks at four ways");
    const auto address = static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(geom));
    ThreadCache::GeomMemo* ways = cache.geomMemos[(address * 0x9E3779B97F4A7C15ull) >> 58];
    const std::uint64_t now = ++cache.geomClock;
    ThreadCache::GeomMemo* memo = ways[0].geom == geom   ? &ways[0]
                                  : ways[1].geom == geom ? &ways[1]
                                  : ways[2].geom == geom ? &ways[2]
                                  : ways[3].geom == geom ? &ways[3]
                                                         : nullptr;
    if (!memo) {
        memo = &ways[0];
        for (int i = 1; i < ThreadCache::kGeomMemoWays; ++i)
            if (ways[i].lastUse < memo->lastUse) memo = &ways[i];
        *memo = ThreadCache::GeomMemo{};
        memo->geom = geom;
    }
    memo->lastUse = now;
    return *memo;
}

inline ThreadCache& threadCache() {
    thread_local ThreadCache cache;
    return cache;
}

/// The plane a·x + b·y + c·z = d as the core takes it — (a, b, c) scaled to unit length exactly as
/// Vec3(a, b, c).normalized() gives it, and the core's normalisation of that half-space —
/// remembered for the thread's last few planes: a scene has few planes, and the square roots and
/// divisions in a chain were a fifth of a cheap box–plane call's time. Valid until this thread
/// looks up kPlaneSlots other planes.
const ThreadCache::PlaneSlot& planeSlotSlow(ThreadCache& cache, double a, double b, double c, double d);
/// `parameters`: a, b, c, d as dGeomPlaneGetParams gives them. The last slot is compared by its
/// bytes (integer compares, which need no floating-point registers kept across ODE's calls); the
/// search of the others by value, so that a plane equal by value but not by bytes (±0) finds the
/// slot it found before.
inline const ThreadCache::PlaneSlot& planeSlot(ThreadCache& cache, const double* parameters) {
    const ThreadCache::PlaneSlot& last = cache.planes[cache.lastPlane];
    if (std::memcmp(last.raw, parameters, sizeof last.raw) == 0) return last;
    return planeSlotSlow(cache, parameters[0], parameters[1], parameters[2], parameters[3]);
}
/// The same for a single-precision ODE's parameters (dReal is float): converted to double first.
inline const ThreadCache::PlaneSlot& planeSlot(ThreadCache& cache, const float* parameters) {
    const double asDouble[4] = {parameters[0], parameters[1], parameters[2], parameters[3]};
    return planeSlot(cache, asDouble);
}

}  // namespace gdc::ode::detail

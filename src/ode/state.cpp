#include "state.hpp"

#include <gdcontact/ode.hpp>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <utility>

namespace gdc::ode::detail {
namespace {

struct BoxKey {
    std::array<double, 3> halfExtents;
    bool operator==(const BoxKey& other) const { return halfExtents == other.halfExtents; }
};

struct BoxKeyHash {
    std::size_t operator()(const BoxKey& key) const {
        std::size_t hash = 0;
        for (double value : key.halfExtents)
            hash = hash * 1000003u ^ std::hash<double>{}(value);
        return hash;
    }
};

// Enough for any scene with a sane number of distinct box sizes; a scene with more (random
// rubble) clears and refills it, which costs one Polytope::box() per size per refill.
constexpr std::size_t kBoxCacheCapacity = 4096;

struct ConvexEntry {
    std::shared_ptr<ConvexRecord> record;
    // False when ODE's free handler was replaced behind our back while this entry existed: the
    // geom may have been freed unseen and its address reused, so the entry is checked against the
    // geom's own AABB before use.
    bool trusted = true;
};

struct State {
    mutable std::shared_mutex convexMutex;
    std::unordered_map<const void*, ConvexEntry> convexes;
    std::atomic<std::size_t> convexCount{0};
    // Advanced (under convexMutex) whenever an entry is removed, replaced or loses its trust: a
    // thread's cached hull for an address is current while this has not moved since it was
    // cached. Additions leave it alone, since they cannot change what a cached address maps to.
    // Starts at 1 so that an empty cache slot (generation 0) never matches.
    std::atomic<std::uint64_t> convexGeneration{1};
    // The free handler that was active before ours; ours forwards to it (nullptr: free()).
    std::atomic<dFreeFunction*> previousFree{nullptr};
    // Serialises installing the free hook (a read-modify-write of ODE's handler).
    std::mutex hookMutex;

    mutable std::shared_mutex boxMutex;
    std::unordered_map<BoxKey, std::shared_ptr<const Polytope>, BoxKeyHash> boxes;

    mutable std::shared_mutex settingsMutex;
    Settings settings;  // installedSettingsGeneration moves with it
};

static_assert(kBorrowedBoxSizes >= 3, "one pair's two boxes must both survive the second lookup");

std::size_t convexSlotOf(const void* geom) {
    // Geoms are heap blocks at least 16-byte aligned: the low bits carry nothing.
    const auto address = reinterpret_cast<std::uintptr_t>(geom);
    return static_cast<std::size_t>((address >> 4) ^ (address >> 11)) % ThreadCache::kConvexSlots;
}

// Intentionally never destroyed: ODE may free geoms from static destructors that run after ours
// would have, and the free hook must still find the state then.
State& state() {
    static State* const instance = new State;
    return *instance;
}

void forgetConvex(const void* address) noexcept {
    State& s = state();
    std::shared_ptr<ConvexRecord> released;  // destroyed after the lock is dropped
    {
        std::unique_lock lock(s.convexMutex);
        auto found = s.convexes.find(address);
        if (found == s.convexes.end()) return;
        released = std::move(found->second.record);
        s.convexGeneration.fetch_add(1, std::memory_order_release);
        s.convexes.erase(found);
        s.convexCount.fetch_sub(1, std::memory_order_relaxed);
    }
}

// ODE frees every geom through dFree (its objects' operator delete), after the geom's destructor
// ran. This is the only notice of a geom's end ODE 0.16.2 gives; the hull arrays are released here.
void freeHook(void* pointer, dsizeint size) {
    State& s = state();
    if (pointer && s.convexCount.load(std::memory_order_relaxed) != 0) {
        bool registered;
        {
            std::shared_lock lock(s.convexMutex);
            registered = s.convexes.count(pointer) != 0;
        }
        if (registered) forgetConvex(pointer);
    }
    if (dFreeFunction* previous = s.previousFree.load(std::memory_order_acquire))
        previous(pointer, size);
    else
        std::free(pointer);  // ODE's own behaviour without a handler
}

// Puts freeHook in front of whatever free handler is active. Entries that existed while another
// handler had replaced ours lose their trust (see ConvexEntry::trusted).
void ensureFreeHook() {
    State& s = state();
    std::lock_guard hookLock(s.hookMutex);
    dFreeFunction* current = dGetFreeHandler();
    if (current == &freeHook) return;
    {
        std::unique_lock lock(s.convexMutex);
        for (auto& entry : s.convexes) entry.second.trusted = false;
        s.convexGeneration.fetch_add(1, std::memory_order_release);
    }
    s.previousFree.store(current, std::memory_order_release);
    dSetFreeHandler(&freeHook);
}

// Whether the geom at a distrusted entry's address is still the convex that entry describes:
// its ODE AABB (computed by ODE from the points it was given) must match the hull's at its pose.
bool matchesGeom(const Polytope& hull, dGeomID geom) {
    if (dGeomGetClass(geom) != dConvexClass) return false;
    const Pose pose = poseOf(geom);
    Vec3 lower = Vec3::Constant(INFINITY), upper = Vec3::Constant(-INFINITY);
    for (const Vec3& vertex : hull.vertices()) {
        const Vec3 world = pose.apply(vertex);
        lower = lower.cwiseMin(world);
        upper = upper.cwiseMax(world);
    }
    dReal box[6];
    dGeomGetAABB(geom, box);
    const double tolerance = 1e-9 * (hull.radius() + pose.position.norm()) + 1e-300;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(static_cast<double>(box[2 * axis]) - lower[axis]) > tolerance) return false;
        if (std::abs(static_cast<double>(box[2 * axis + 1]) - upper[axis]) > tolerance) return false;
    }
    return true;
}

}  // namespace

dGeomID createRegisteredConvex(dSpaceID space, std::shared_ptr<ConvexRecord> record) {
    ensureFreeHook();
    dGeomID geom = dCreateConvex(space, record->planes.data(),
                                 static_cast<unsigned>(record->planes.size() / 4),
                                 record->points.data(),
                                 static_cast<unsigned>(record->points.size() / 3),
                                 record->polygons.data());
    State& s = state();
    std::shared_ptr<ConvexRecord> replaced;  // a stale entry at a reused address (hook was away)
    {
        std::unique_lock lock(s.convexMutex);
        ConvexEntry& entry = s.convexes[geom];
        if (entry.record) {
            replaced = std::move(entry.record);
            s.convexGeneration.fetch_add(1, std::memory_order_release);
        } else
            s.convexCount.fetch_add(1, std::memory_order_relaxed);
        entry.record = std::move(record);
        entry.trusted = true;
    }
    return geom;
}

std::shared_ptr<const Polytope> registeredConvex(dGeomID geom) {
    State& s = state();
    if (s.convexCount.load(std::memory_order_relaxed) == 0) return nullptr;
    std::shared_ptr<ConvexRecord> record;
    bool trusted;
    {
        std::shared_lock lock(s.convexMutex);
        auto found = s.convexes.find(geom);
        if (found == s.convexes.end()) return nullptr;
        record = found->second.record;
        trusted = found->second.trusted;
    }
    // Our hook may have been replaced since the geom was registered: then nothing told us about
    // frees in between, and the address may now hold a different geom.
    // A mismatch is reported as "not ours" but the entry is kept: should the check ever be wrong
    // about a live geom, ODE still points into the entry's arrays. A stale entry is replaced when
    // createConvex reuses its address.
    if (!trusted || dGetFreeHandler() != &freeHook) {
        if (!matchesGeom(*record->polytope, geom)) return nullptr;
    }
    return record->polytope;
}

const Polytope* borrowedConvex(ThreadCache& cache, dGeomID geom) {
    State& s = state();
    if (s.convexCount.load(std::memory_order_relaxed) == 0) return nullptr;
    // With another free handler in front of ours, frees go unseen and the generation cannot be
    // trusted: every lookup then takes registeredConvex's checked path.
    // (The registry keeps holding the hull after the temporary shared_ptr is gone.)
    if (dGetFreeHandler() != &freeHook) return registeredConvex(geom).get();
    ThreadCache::ConvexSlot& slot = cache.convexes[convexSlotOf(geom)];
    if (slot.geom == geom && slot.generation == s.convexGeneration.load(std::memory_order_acquire))
        return slot.hull;
    const Polytope* hull;
    bool trusted;
    std::uint64_t generation;
    {
        std::shared_lock lock(s.convexMutex);
        auto found = s.convexes.find(geom);
        if (found == s.convexes.end()) return nullptr;
        hull = found->second.record->polytope.get();
        trusted = found->second.trusted;
        generation = s.convexGeneration.load(std::memory_order_relaxed);  // moves only under the lock
    }
    if (!trusted) return matchesGeom(*hull, geom) ? hull : nullptr;  // checked each time, not cached
    slot = ThreadCache::ConvexSlot{geom, hull, generation};
    return hull;
}

std::size_t registeredConvexCount() { return state().convexCount.load(); }

std::shared_ptr<const Polytope> boxPolytope(double halfX, double halfY, double halfZ) {
    State& s = state();
    const BoxKey key{{halfX, halfY, halfZ}};
    {
        std::shared_lock lock(s.boxMutex);
        auto found = s.boxes.find(key);
        if (found != s.boxes.end()) return found->second;
    }
    auto built = std::make_shared<const Polytope>(Polytope::box(Vec3(halfX, halfY, halfZ)));
    std::unique_lock lock(s.boxMutex);
    if (s.boxes.size() >= kBoxCacheCapacity) s.boxes.clear();  // holders keep their copies alive
    return s.boxes.emplace(key, std::move(built)).first->second;
}

const Polytope& borrowedBoxPolytopeSlow(ThreadCache& cache, double halfX, double halfY, double halfZ) {
    const std::uint64_t now = ++cache.boxClock;
    ThreadCache::BoxSlot* oldest = &cache.boxes[0];
    for (ThreadCache::BoxSlot& slot : cache.boxes) {
        if (slot.halfExtents[0] == halfX && slot.halfExtents[1] == halfY && slot.halfExtents[2] == halfZ) {
            slot.lastUse = now;
            cache.lastBox = static_cast<int>(&slot - cache.boxes);
            return *slot.polytope;
        }
        if (slot.lastUse < oldest->lastUse) oldest = &slot;
    }
    // The least recently used slot is never one this thread used within the last
    // kBorrowedBoxSizes − 1 lookups, so no reference handed out in that window dangles.
    std::shared_ptr<const Polytope> polytope = boxPolytope(halfX, halfY, halfZ);  // may throw: slot untouched
    oldest->polytope = std::move(polytope);
    oldest->halfExtents[0] = halfX;
    oldest->halfExtents[1] = halfY;
    oldest->halfExtents[2] = halfZ;
    oldest->lastUse = now;
    cache.lastBox = static_cast<int>(oldest - cache.boxes);
    return *oldest->polytope;
}

Vec3 unitPlaneNormalSlow(ThreadCache& cache, double a, double b, double c) {
    for (int i = 0; i < ThreadCache::kPlaneSlots; ++i) {
        const ThreadCache::PlaneSlot& slot = cache.planes[i];
        if (slot.raw[0] == a && slot.raw[1] == b && slot.raw[2] == c) {
            cache.lastPlane = i;
            return slot.unit;
        }
    }
    cache.lastPlane = (cache.lastPlane + 1) % ThreadCache::kPlaneSlots;
    ThreadCache::PlaneSlot& slot = cache.planes[cache.lastPlane];
    slot.raw[0] = a;
    slot.raw[1] = b;
    slot.raw[2] = c;
    slot.unit = Vec3(a, b, c).normalized();
    return slot.unit;
}

std::atomic<std::uint64_t> installedSettingsGeneration{1};

const Settings& refreshInstalledSettings(ThreadCache& cache) {
    State& s = state();
    std::shared_lock lock(s.settingsMutex);
    cache.settings = s.settings;
    cache.settingsGeneration = installedSettingsGeneration.load(std::memory_order_relaxed);  // moves only under the lock
    return cache.settings;
}

void setInstalledSettings(const Settings& settings) {
    State& s = state();
    std::unique_lock lock(s.settingsMutex);
    s.settings = settings;
    installedSettingsGeneration.fetch_add(1, std::memory_order_release);
}

}  // namespace gdc::ode::detail

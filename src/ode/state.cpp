#include "state.hpp"

#include "../half_space.hpp"

#include "pair_cache_table.hpp"

#include <gdcontact/ode.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <functional>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <utility>
#include <vector>

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

// ---- The convex index: geom address → hull, read by collide() without a lock ----
//
// State::convexes (a map under convexMutex) owns the records; the index mirrors it for collide(),
// which must find a hull in O(1) whatever the scene size, on many threads at once, while other
// threads create and destroy convex geoms. An open-addressing table with linear probing, whose
// slots are pairs of atomics (key, value). Writers (createConvex, the free hook, ensureFreeHook)
// hold convexMutex exclusively, so they are serialised among themselves; readers take no lock,
// write nothing shared in the common case and never wait for a writer. Why a reader always finds
// its geom:
//  - A reader only looks up a geom that is alive for the whole lookup: ODE's contract forbids
//    destroying a geom while it is collided, and a geom reaches collide() only after createConvex
//    returned it. So its key is in the current table from before the lookup to after it.
//  - Writers never move a key within a table: removal turns the key into a tombstone, insertion
//    fills an empty slot or a tombstone. A probe from the key's home slot therefore reaches it
//    whatever writers do meanwhile, and since no slot of a published table ever becomes empty
//    again, no probe stops early.
//  - Tombstones, growth and shrinking are handled by building a fresh table (from the map) and
//    publishing it (release; readers load it with acquire). A reader that still probes the old
//    table finds its geom there too: the old table held every geom alive when it was replaced,
//    and a geom created later was created after the new table was published, so a reader that
//    was handed that geom loads the new table (or a newer one).
// A replaced table is freed once no reader can be probing it: each reading thread announces the
// table it reads in a hazard slot (M. M. Michael, "Hazard pointers: safe memory reclamation for
// lock-free objects", IEEE TPDS 15(6), 2004). The announcement is kept between lookups, so a
// lookup pays for it (a sequentially consistent store and a re-check) only when the table changed
// since the thread's previous one; the cost is that an idle thread keeps at most one old table
// alive until its next lookup or its exit.
struct IndexSlot {
    std::atomic<std::uintptr_t> key{0};    // a geom address, or kEmptyKey / kTombstoneKey
    std::atomic<std::uintptr_t> value{0};  // the hull's address, | kUntrusted (see ConvexEntry)
};
constexpr std::uintptr_t kEmptyKey = 0;
constexpr std::uintptr_t kTombstoneKey = 1;  // geoms are aligned heap blocks: never at address 1
constexpr std::uintptr_t kUntrusted = 1;     // a Polytope is aligned: its address's low bit is free

struct IndexTable {
    explicit IndexTable(unsigned log2Capacity)
        : shift(64 - log2Capacity), mask((std::size_t{1} << log2Capacity) - 1), slots(new IndexSlot[mask + 1]) {}
    unsigned shift;
    std::size_t mask;
    std::unique_ptr<IndexSlot[]> slots;
    std::size_t used = 0;  // keys and tombstones (writers only)

    // Fibonacci hashing (Knuth, TAOCP vol. 3, §6.4): the top bits of address × 2⁶⁴/φ, which
    // spreads the regularly spaced addresses of an allocator's blocks over the table.
    std::size_t home(std::uintptr_t key) const {
        return static_cast<std::size_t>((static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ull) >> shift);
    }
    std::size_t capacity() const { return mask + 1; }
};

// The smallest table. A table is at most half full (keys + tombstones; storeInIndex), which keeps
// a linear probe short (Knuth: ≈ 1.5 slots for a hit, 2.5 for a miss) and guarantees that every
// probe meets an empty slot.
constexpr unsigned kMinLog2Capacity = 6;

}  // namespace

// One thread's hazard slot; slots are never freed (a thread that ends gives its slot back for the
// next thread to claim), so a writer may always walk the list.
struct ConvexIndexReader {
    std::atomic<const IndexTable*> table{nullptr};  // the table this thread may be probing
    std::atomic<bool> claimed{true};
    ConvexIndexReader* next = nullptr;  // set before the slot is pushed, then constant
};

namespace {

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
    // The index of `convexes` for collide() (see IndexSlot). Replaced only under convexMutex.
    std::atomic<IndexTable*> index{new IndexTable(kMinLog2Capacity)};
    std::vector<IndexTable*> retiredIndexes;  // replaced, not yet freed (under convexMutex)
    std::size_t indexesPublished = 1;         // for tests (under convexMutex)
    std::atomic<ConvexIndexReader*> indexReaders{nullptr};  // every thread's hazard slot
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

// Intentionally never destroyed: ODE may free geoms from static destructors that run after ours
// would have, and the free hook must still find the state then.
State& state() {
    static State* const instance = new State;
    return *instance;
}

// ---- writers of the convex index: State::convexMutex held exclusively ----

std::uintptr_t keyOf(const void* geom) { return reinterpret_cast<std::uintptr_t>(geom); }

std::uintptr_t indexValueOf(const ConvexEntry& entry) {
    return reinterpret_cast<std::uintptr_t>(entry.record->polytope.get()) | (entry.trusted ? 0 : kUntrusted);
}

// Sets the value of `key`, adding the key (into the first tombstone on its probe, else the empty
// slot that ends it) if absent. The value is stored before the key is published. Returns false,
// changing nothing, when adding the key would fill more than half the table.
bool storeInIndex(IndexTable& table, std::uintptr_t key, std::uintptr_t value) {
    IndexSlot* reusable = nullptr;
    for (std::size_t i = table.home(key);; i = (i + 1) & table.mask) {
        IndexSlot& slot = table.slots[i];
        const std::uintptr_t current = slot.key.load(std::memory_order_relaxed);
        if (current == key) {
            slot.value.store(value, std::memory_order_release);
            return true;
        }
        if (current == kTombstoneKey && !reusable) reusable = &slot;
        if (current == kEmptyKey) {
            if (!reusable) {
                if (2 * (table.used + 1) > table.capacity()) return false;
                ++table.used;
                reusable = &slot;
            }
            reusable->value.store(value, std::memory_order_relaxed);
            reusable->key.store(key, std::memory_order_release);
            return true;
        }
    }
}

void eraseFromIndex(IndexTable& table, std::uintptr_t key) {
    for (std::size_t i = table.home(key);; i = (i + 1) & table.mask) {
        IndexSlot& slot = table.slots[i];
        const std::uintptr_t current = slot.key.load(std::memory_order_relaxed);
        if (current == kEmptyKey) return;
        if (current == key) {
            slot.key.store(kTombstoneKey, std::memory_order_release);  // stays used: never empty again
            slot.value.store(0, std::memory_order_relaxed);
            return;
        }
    }
}

// Frees the replaced tables that no thread announces any more (see IndexSlot). The loads are
// sequentially consistent so that, with the reader's store-then-recheck, a reader either is seen
// here or has seen the table that replaced this one.
void freeUnreadIndexes(State& s) {
    std::vector<IndexTable*>& retired = s.retiredIndexes;
    auto announced = [&](const IndexTable* table) {
        for (ConvexIndexReader* reader = s.indexReaders.load(std::memory_order_acquire); reader; reader = reader->next)
            if (reader->table.load(std::memory_order_seq_cst) == table) return true;
        return false;
    };
    for (std::size_t i = 0; i < retired.size();) {
        if (announced(retired[i])) {
            ++i;
            continue;
        }
        delete retired[i];
        retired[i] = retired.back();
        retired.pop_back();
    }
}

// Replaces the index by a fresh table holding `convexes` plus room for `extra` more, at most a
// quarter full: tombstones are dropped, and the table grows or shrinks with the scene.
void rebuildIndex(State& s, std::size_t extra) {
    unsigned log2Capacity = kMinLog2Capacity;
    while ((std::size_t{1} << log2Capacity) < 4 * (s.convexes.size() + extra)) ++log2Capacity;
    auto fresh = std::make_unique<IndexTable>(log2Capacity);
    for (const auto& [geom, entry] : s.convexes) storeInIndex(*fresh, keyOf(geom), indexValueOf(entry));
    s.retiredIndexes.reserve(s.retiredIndexes.size() + 1);  // so that retiring cannot throw
    IndexTable* replaced = s.index.exchange(fresh.release(), std::memory_order_seq_cst);
    s.retiredIndexes.push_back(replaced);
    ++s.indexesPublished;
    freeUnreadIndexes(s);
}

// Makes sure the index can take one more key without a rebuild (may throw: changes nothing then).
void reserveIndexSlot(State& s) {
    const IndexTable& table = *s.index.load(std::memory_order_relaxed);
    if (2 * (table.used + 1) > table.capacity()) rebuildIndex(s, 1);
}

void forgetConvex(const void* address) noexcept {
    State& s = state();
    std::shared_ptr<ConvexRecord> released;  // destroyed after the lock is dropped
    {
        std::unique_lock lock(s.convexMutex);
        auto found = s.convexes.find(address);
        if (found == s.convexes.end()) return;
        IndexTable& index = *s.index.load(std::memory_order_relaxed);
        eraseFromIndex(index, keyOf(address));  // before the hull goes
        released = std::move(found->second.record);
        s.convexes.erase(found);
        // A scene that lost most of its hulls gets a smaller table (the rebuild sizes it 4× the
        // hulls left, so shrinking again takes another 4× fewer: amortised O(1) per removal).
        if (index.capacity() > (std::size_t{1} << kMinLog2Capacity) && 16 * s.convexes.size() < index.capacity()) {
            try {
                rebuildIndex(s, 0);
            } catch (...) {  // out of memory: the larger table serves as well
            }
        } else if (!s.retiredIndexes.empty()) {
            freeUnreadIndexes(s);
        }
        s.convexCount.fetch_sub(1, std::memory_order_relaxed);
        convexesForgotten.fetch_add(1, std::memory_order_release);  // every thread's AABB memo is void
    }
}

// ODE frees every geom through dFree (its objects' operator delete), after the geom's destructor
// ran. This is the only notice of a geom's end ODE 0.16.2 gives; the hull arrays are released here.
// ODE calls it from C: nothing may leave it (a lock failure leaves the hull registered — an AABB
// mismatch later keeps it from a new geom at that address — and the memory is still freed).
void freeHook(void* pointer, dsizeint size) noexcept {
    State& s = state();
    if (pointer) pairCacheTable().noteFreed(pointer);
    if (pointer && s.convexCount.load(std::memory_order_relaxed) != 0) {
        try {
            bool registered;
            {
                std::shared_lock lock(s.convexMutex);
                registered = s.convexes.count(pointer) != 0;
            }
            if (registered) forgetConvex(pointer);
        } catch (...) {
        }
    }
    if (dFreeFunction* previous = s.previousFree.load(std::memory_order_acquire))
        previous(pointer, size);
    else
        std::free(pointer);  // ODE's own behaviour without a handler
}

}  // namespace

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
        IndexTable& index = *s.index.load(std::memory_order_relaxed);
        for (std::size_t i = 0; i < index.capacity(); ++i) {
            IndexSlot& slot = index.slots[i];
            if (slot.key.load(std::memory_order_relaxed) > kTombstoneKey)
                slot.value.store(slot.value.load(std::memory_order_relaxed) | kUntrusted, std::memory_order_release);
        }
    }
    s.previousFree.store(current, std::memory_order_release);
    dSetFreeHandler(&freeHook);
}

namespace {

// Whether the geom at a distrusted entry's address is still the convex that entry describes:
// its ODE AABB (computed by ODE from the points it was given) must match the hull's at its pose.
bool matchesGeom(const Polytope& hull, dGeomID geom) {
    if (dGeomGetClass(geom) != dConvexClass) return false;
    return matchesAabb(hull, poseOf(geom), geom, 32, 3);
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
    try {
        std::unique_lock lock(s.convexMutex);
        reserveIndexSlot(s);  // may rebuild (allocates): before the map changes, so a throw leaves it as it was
        if (!s.retiredIndexes.empty()) freeUnreadIndexes(s);
        ConvexEntry& entry = s.convexes[geom];
        if (entry.record)
            replaced = std::move(entry.record);
        else
            s.convexCount.fetch_add(1, std::memory_order_relaxed);
        entry.record = std::move(record);
        entry.trusted = true;
        storeInIndex(*s.index.load(std::memory_order_relaxed), keyOf(geom), indexValueOf(entry));
    } catch (...) {
        dGeomDestroy(geom);  // ODE must not keep pointers into the record's arrays
        throw;
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

namespace {

ConvexIndexReader* claimIndexReader(State& s) {
    for (ConvexIndexReader* reader = s.indexReaders.load(std::memory_order_acquire); reader; reader = reader->next) {
        bool free = false;
        if (!reader->claimed.load(std::memory_order_relaxed) &&
            reader->claimed.compare_exchange_strong(free, true, std::memory_order_acquire))
            return reader;
    }
    auto* reader = new ConvexIndexReader;  // claimed; never freed (writers walk the list)
    reader->next = s.indexReaders.load(std::memory_order_relaxed);
    while (!s.indexReaders.compare_exchange_weak(reader->next, reader, std::memory_order_release,
                                                 std::memory_order_relaxed)) {
    }
    return reader;
}

// Announces the current index table in this thread's hazard slot and returns it: announce, then
// check that it is still current (sequentially consistent, paired with freeUnreadIndexes), else
// retry with the newer one. Lock-free: a retry means a writer published a table meanwhile.
const IndexTable* protectIndex(ThreadCache& cache) {
    State& s = state();
    if (!cache.convexReader) cache.convexReader = claimIndexReader(s);
    const IndexTable* table = s.index.load(std::memory_order_acquire);
    for (;;) {
        cache.convexReader->table.store(table, std::memory_order_seq_cst);
        const IndexTable* current = s.index.load(std::memory_order_seq_cst);
        if (current == table) break;
        table = current;
    }
    cache.protectedConvexTable = table;
    return table;
}

// The index value of `geom` (0 if absent). The thread's announcement of its last table stays
// valid, so a lookup in an unchanged index costs one load more than the probe.
std::uintptr_t lookUpIndex(ThreadCache& cache, const void* geom) {
    const IndexTable* table = state().index.load(std::memory_order_acquire);
    if (table != cache.protectedConvexTable) table = protectIndex(cache);
    const std::uintptr_t key = keyOf(geom);
    for (std::size_t i = table->home(key);; i = (i + 1) & table->mask) {
        const IndexSlot& slot = table->slots[i];
        const std::uintptr_t current = slot.key.load(std::memory_order_acquire);
        if (current == key) return slot.value.load(std::memory_order_acquire);
        if (current == kEmptyKey) return 0;  // a table is at most half full: a probe always ends
    }
}

}  // namespace

ThreadCache::~ThreadCache() {
    if (!convexReader) return;
    convexReader->table.store(nullptr, std::memory_order_release);  // its last table may go
    convexReader->claimed.store(false, std::memory_order_release);
}

const Polytope* borrowedConvex(ThreadCache& cache, dGeomID geom) {
    // With another free handler in front of ours, frees go unseen and an address may now hold
    // another geom: every lookup then takes registeredConvex's checked path.
    // (The registry keeps holding the hull after the temporary shared_ptr is gone.)
    if (dGetFreeHandler() != &freeHook) return registeredConvex(geom).get();
    const std::uintptr_t value = lookUpIndex(cache, geom);
    const auto* hull = reinterpret_cast<const Polytope*>(value & ~kUntrusted);
    if (value & kUntrusted) return matchesGeom(*hull, geom) ? hull : nullptr;  // checked each time
    return hull;
}

std::size_t registeredConvexCount() { return state().convexCount.load(); }

ConvexIndexStats convexIndexStats() {
    State& s = state();
    std::shared_lock lock(s.convexMutex);
    return {s.index.load(std::memory_order_relaxed)->capacity(), s.retiredIndexes.size(), s.indexesPublished};
}

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

const ThreadCache::PlaneSlot& planeSlotSlow(ThreadCache& cache, double a, double b, double c, double d) {
    for (int i = 0; i < ThreadCache::kPlaneSlots; ++i) {
        const ThreadCache::PlaneSlot& slot = cache.planes[i];
        if (slot.raw[0] == a && slot.raw[1] == b && slot.raw[2] == c && slot.raw[3] == d) {
            cache.lastPlane = i;
            return slot;
        }
    }
    cache.lastPlane = (cache.lastPlane + 1) % ThreadCache::kPlaneSlots;
    ThreadCache::PlaneSlot& slot = cache.planes[cache.lastPlane];
    slot.raw[0] = a;
    slot.raw[1] = b;
    slot.raw[2] = c;
    slot.raw[3] = d;
    slot.unit = Vec3(a, b, c).normalized();
    slot.normalised = false;
    try {
        const gdc::detail::UnitHalfSpace normalised = gdc::detail::normaliseHalfSpace(HalfSpace{slot.unit, d});
        slot.normalisedNormal = normalised.normal;
        slot.normalisedOffset = normalised.offset;
        slot.normalised = true;
    } catch (const InvalidInput&) {  // a bad plane: each call's core query reports it
    }
    return slot;
}

bool matchesAabb(const Polytope& hull, const Pose& pose, dGeomID geom, int bruteForceLimit, int axes) {
    // The world AABB of the hull: along each world axis, the support of the hull in the local
    // direction the axis has (a row of the rotation).
    Vec3 lower, upper;
    for (int axis = 0; axis < axes; ++axis) {
        const Vec3 direction = pose.rotation.row(axis).transpose();
        const Vec3& top = hull.vertices()[hull.supportVertex(direction, bruteForceLimit)];
        const Vec3& bottom = hull.vertices()[hull.supportVertex(-direction, bruteForceLimit)];
        upper[axis] = direction.dot(top) + pose.position[axis];
        lower[axis] = direction.dot(bottom) + pose.position[axis];
    }
    dReal box[6];
    dGeomGetAABB(geom, box);
    const double tolerance = 1e-9 * (hull.radius() + pose.position.norm()) + 1e-300;
    for (int axis = 0; axis < axes; ++axis) {
        if (!(std::abs(static_cast<double>(box[2 * axis]) - lower[axis]) <= tolerance)) return false;
        if (!(std::abs(static_cast<double>(box[2 * axis + 1]) - upper[axis]) <= tolerance)) return false;
    }
    return true;
}

bool odeIsInitialized() {
    // Set by dInitODE2's first call (odeou's assertion handler), reset by the matching dCloseODE.
    static void* const hook =
        dlsym(RTLD_DEFAULT, "_ZN5odeou28CAssertionCheckCustomization24g_fnAssertFailureHandlerE");
    if (!hook) return true;
    return *static_cast<void* const volatile*>(hook) != nullptr;
}

std::atomic<std::uint64_t> installedSettingsGeneration{1};

std::atomic<std::uint64_t> convexesForgotten{0};

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

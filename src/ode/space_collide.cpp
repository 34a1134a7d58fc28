// gdc::ode::spaceCollide / setThreadCount: a whole step's collision in one call. ODE's broad phase
// (dSpaceCollide, nested spaces through dSpaceCollide2) lists the candidate pairs on the calling
// thread; the pairs gdcontact handles are collided on a small pool of threads, each into its own
// slot, as soon as the broad phase lists them (the pool works while the broad phase still runs);
// the other pairs go to dCollide on the calling thread, inside the broad phase; then the handler
// runs on the calling thread for every touching pair, in the broad phase's order, while the pool
// finishes the narrow phase (the calling thread collides pairs too whenever the next pair in order
// is not done yet). So the output (and the contact joints a handler makes from it) does not depend
// on the thread count.
//
// Why the pool may read geoms while the broad phase runs: ODE's spaces (simple, hash) clean every
// geom of the space tree — world pose and AABB, recursively into nested spaces — before they report
// the first pair, and afterwards only read the geoms (dSpaceCollide2 on a nested space re-cleans
// nothing that is clean). The pool reads only gdcontact pairs' geoms (pose, class, box lengths, the
// convex registry), ODE's colliders on the calling thread only read them too.
//
// The pool of threads: worker_pool.hpp.
#include <gdcontact/ode.hpp>

#include "body_pair.hpp"
#include "pair_cache_table.hpp"
#include "resolved_pair.hpp"
#include "round_geoms.hpp"
#include "space_collide_profile.hpp"
#include "convex_registry.hpp"
#include "installed_settings.hpp"
#include "thread_cache.hpp"
#include "worker_pool.hpp"
#include "space_collide_scratch.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gdc::ode {
namespace {

using detail::Pair;
using detail::Scratch;
using detail::Slot;
using detail::SlotBlock;
using detail::blockOf;
using detail::kFirstBlock;

constexpr int kMaxThreads = 256;

// The phase timing of space_collide_profile.hpp: compiled in with GDCONTACT_PHASE_PROFILING, and
// then off unless a benchmark asks.
#ifndef GDCONTACT_PHASE_PROFILING
#define GDCONTACT_PHASE_PROFILING 0
#endif
constexpr bool kPhaseProfilingBuilt = GDCONTACT_PHASE_PROFILING;
std::atomic<bool> profiling{false};
thread_local detail::SpaceCollideProfile lastProfile;
using ProfileClock = std::chrono::steady_clock;

std::int64_t nanosSince(ProfileClock::time_point start) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(ProfileClock::now() - start).count();
}

// 0: one per hardware thread.
std::atomic<int> requestedThreads{0};

int effectiveThreadCount() {
    const int requested = requestedThreads.load(std::memory_order_relaxed);
    if (requested > 0) return requested;
    const unsigned hardware = std::thread::hardware_concurrency();
    return hardware == 0 ? 1 : static_cast<int>(std::min<unsigned>(hardware, kMaxThreads));
}

struct Call {
    Scratch& scratch;
    int maxContacts;  // the caller's maxContactsPerPair
    int slotSize;     // contacts kept per gdcontact pair: min(maxContacts, kMaxManifoldPoints)
    detail::ThreadCache& cache;
    const Settings& settings;  // the installed settings, read once for the call
    Job& job;  // publishes each gdcontact pair to the pool as soon as it is listed
    bool serial;  // no pool: collide each gdcontact pair at once, as a near callback would
    std::exception_ptr failure;  // thrown inside ODE's broad phase, rethrown after it
    // This call's hold on the pair cache: each gdcontact pair's entry is found here, on the calling
    // thread, and handed to whichever thread collides the pair (one thread per pair: never shared).
    detail::PairCacheTable::Lease& pairCache;
    std::int64_t* serialNarrowNanos = nullptr;  // profiling, serial: gdcontact's collide calls
    std::size_t serialGdcontactPairs = 0;       // profiling, serial: how many
};

void addPair(Call& call, dGeomID o1, dGeomID o2) {
    const int class1 = dGeomGetClass(o1);
    const int class2 = dGeomGetClass(o2);
    Scratch& scratch = call.scratch;
    const bool ourClasses = detail::isGdcontactPair(class1, class2);
    if (ourClasses && !call.serial) {
        // Resolved here, once, on the calling thread: ODE's getters recompute a stale world pose
        // here (the broad phase has normally done it), so the workers read only the resolved pair.
        const std::size_t index = scratch.gdcontactPairs;
        dContactGeom* contacts;
        Slot& slot = scratch.slotFor(index, call.slotSize, contacts);  // may throw: before publishing
        // False: a convex gdcontact did not create, ODE's pair (dCollide, below).
        if (detail::resolvePair(o1, class1, o2, class2, call.settings, call.cache, slot.pair)) {
            if (slot.pair.plane) {
                slot.plane = *slot.pair.plane;
                slot.pair.plane = &slot.plane;
            }
            scratch.pairs.push_back(Pair{o1, o2, index, 0, true});  // may throw: before publishing
            slot.count.store(-1, std::memory_order_relaxed);  // published by Job::ready (release)
            slot.cache = call.pairCache && detail::pairCacheWorthIt(o1, o2, call.settings) ? call.pairCache.find(o1, o2)
                                                                                          : nullptr;
            scratch.gdcontactPairs = index + 1;
            call.job.ready(index + 1);
            return;
        }
    }
    // ODE's own collider as a near callback would call it (or, when serial, gdcontact's), here and
    // now on the calling thread, the contacts packed one pair after the other.
    detail::ResolvedPair resolved;
    const bool ours = ourClasses && call.serial &&
                      detail::resolvePair(o1, class1, o2, class2, call.settings, call.cache, resolved);
    const int room = ours ? call.slotSize : call.maxContacts;
    dContactGeom* out = scratch.packed.reserve(static_cast<std::size_t>(room));
    PairCache* cache = ours && call.pairCache && detail::pairCacheWorthIt(o1, o2, call.settings)
                           ? call.pairCache.find(o1, o2)
                           : nullptr;
    int count;
    if (ours && call.serialNarrowNanos) {
        const auto start = ProfileClock::now();
        count = detail::collideResolved(resolved, room, out, sizeof(dContactGeom), call.settings, call.cache, cache);
        *call.serialNarrowNanos += nanosSince(start);
        ++call.serialGdcontactPairs;
    } else {
        count = ours ? detail::collideResolved(resolved, room, out, sizeof(dContactGeom), call.settings, call.cache,
                                               cache)  // never throws
                     : dCollide(o1, o2, room, out, sizeof(dContactGeom));
    }
    if (cache) call.pairCache.count(*cache);
    scratch.pairs.push_back(Pair{o1, o2, scratch.packed.size, count, false});
    scratch.packed.size += static_cast<std::size_t>(std::max(count, 0));
}

// ODE's near callback, with nested spaces handled as ODE's documentation describes.
void nearCallback(void* data, dGeomID o1, dGeomID o2) {
    Call& call = *static_cast<Call*>(data);
    if (call.failure) return;
    try {
        if (dGeomIsSpace(o1) || dGeomIsSpace(o2)) {
            dSpaceCollide2(o1, o2, data, &nearCallback);
            if (dGeomIsSpace(o1)) dSpaceCollide(reinterpret_cast<dSpaceID>(o1), data, &nearCallback);
            if (dGeomIsSpace(o2)) dSpaceCollide(reinterpret_cast<dSpaceID>(o2), data, &nearCallback);
            return;
        }
        addPair(call, o1, o2);
    } catch (...) {  // no exception may cross ODE's C frames
        call.failure = std::current_exception();
    }
}

// The pool's loop body: gdcontact pairs [begin, end) into their slots.
struct NarrowPhase {
    Scratch* scratch = nullptr;
    int slotSize = 0;
    const Settings* settings = nullptr;
    // Profiling only (collideRangeProfiled):
    std::atomic<std::int64_t> narrowNanos{0};  // summed over the threads
    std::thread::id caller;
    std::int64_t callerNanos = 0;               // the calling thread's share
    ProfileClock::time_point callStart;
    std::atomic<std::int64_t> poolStartNanos{-1};  // a pool thread's first chunk, from callStart
};

void collideRange(void* context, std::size_t begin, std::size_t end) {
    NarrowPhase& phase = *static_cast<NarrowPhase*>(context);
    for (std::size_t i = begin; i < end; ++i) {
        std::size_t offset;
        SlotBlock& block = phase.scratch->blocks[blockOf(i, offset)];
        Slot& slot = block.slots[offset];
        // Never throws: a failure becomes a dMessage and 0 contacts.
        const int count = detail::collideResolved(
            slot.pair, phase.slotSize, block.contacts.get() + offset * static_cast<std::size_t>(phase.slotSize),
            sizeof(dContactGeom), *phase.settings, detail::threadCache(), slot.cache);
        slot.count.store(count, std::memory_order_release);
    }
}

// collideRange with the clock read around each chunk (a few microseconds of work): the profile's
// narrow-phase time, by thread.
void collideRangeProfiled(void* context, std::size_t begin, std::size_t end) {
    NarrowPhase& phase = *static_cast<NarrowPhase*>(context);
    const auto start = ProfileClock::now();
    const bool onCaller = std::this_thread::get_id() == phase.caller;
    if (!onCaller && phase.poolStartNanos.load(std::memory_order_relaxed) < 0) {
        std::int64_t none = -1;
        phase.poolStartNanos.compare_exchange_strong(
            none, std::chrono::duration_cast<std::chrono::nanoseconds>(start - phase.callStart).count());
    }
    collideRange(context, begin, end);
    const std::int64_t spent = nanosSince(start);
    phase.narrowNanos.fetch_add(spent, std::memory_order_relaxed);
    if (onCaller) phase.callerNanos += spent;
}

// The calling thread's scratch; a fresh one when spaceCollide is re-entered from a handler.
struct ScratchLease {
    Scratch* scratch;
    Scratch* owned = nullptr;
    detail::ThreadCache& cache = detail::threadCache();
    std::vector<std::shared_ptr<const Polytope>>* pinnedBefore = nullptr;
    ScratchLease() {
        thread_local Scratch mine;
        if (mine.inUse) {
            owned = new Scratch;
            scratch = owned;
        } else {
            scratch = &mine;
        }
        scratch->inUse = true;
        scratch->pairs.clear();
        scratch->packed.size = 0;
        scratch->gdcontactPairs = 0;
        scratch->pinnedBoxes.clear();
        // Until this call ends, box polytopes the calling thread's cache evicts are kept.
        pinnedBefore = cache.pinnedBoxes;
        cache.pinnedBoxes = &scratch->pinnedBoxes;
    }
    ~ScratchLease() {
        // A call made from a handler hands its pins to the call around it, whose pool may still
        // be colliding pairs resolved with the boxes this call's lookups evicted.
        cache.pinnedBoxes = pinnedBefore;
        if (pinnedBefore)
            for (auto& box : scratch->pinnedBoxes) pinnedBefore->push_back(std::move(box));  // (bad_alloc: terminate)
        scratch->pinnedBoxes.clear();
        scratch->inUse = false;
        delete owned;
    }
    ScratchLease(const ScratchLease&) = delete;
    ScratchLease& operator=(const ScratchLease&) = delete;
};

}  // namespace

void setThreadCount(int threads) {
    if (threads < 0 || threads > kMaxThreads)
        throw InvalidInput("gdc::ode::setThreadCount: threads must be in 0..256 (0: one per hardware "
                           "thread), got " + std::to_string(threads));
    requestedThreads.store(threads, std::memory_order_relaxed);
}

void spaceCollide(dSpaceID space, int maxContactsPerPair, void* data, ContactHandler handler) {
    if (!space) throw InvalidInput("gdc::ode::spaceCollide: null space");
    if (!dGeomIsSpace(reinterpret_cast<dGeomID>(space)))
        throw InvalidInput("gdc::ode::spaceCollide: the first argument is a geom, not a space");
    if (!handler) throw InvalidInput("gdc::ode::spaceCollide: null handler");
    if (maxContactsPerPair < 1 || maxContactsPerPair > 0xffff)
        throw InvalidInput("gdc::ode::spaceCollide: maxContactsPerPair must be in 1..65535, got " +
                           std::to_string(maxContactsPerPair));

    const bool profile = kPhaseProfilingBuilt && profiling.load(std::memory_order_relaxed);
    const auto callStart = profile ? ProfileClock::now() : ProfileClock::time_point{};
    ScratchLease lease;
    Scratch& scratch = *lease.scratch;
    const int slotSize = std::min(maxContactsPerPair, kMaxManifoldPoints);
    NarrowPhase phase;
    phase.scratch = &scratch;
    phase.slotSize = slotSize;
    phase.caller = std::this_thread::get_id();
    phase.callStart = callStart;
    Job job;
    job.body = profile ? &collideRangeProfiled : &collideRange;
    job.context = &phase;
    job.chunk = 8;  // a few microseconds of work: balances uneven pairs, keeps the counter quiet
    const int threads = effectiveThreadCount();
    WorkerPool& pool = workerPool();
    std::unique_lock<std::mutex> poolLock(pool.use, std::defer_lock);
    // Else serial: 1 thread, or the pool busy — with another thread's call, or with this thread's own
    // (a handler calling spaceCollide: the pool is held until the handler loop ends).
    thread_local bool holdingPool = false;
    const bool parallel = threads > 1 && !holdingPool && poolLock.try_lock();
    struct PoolHeld {  // holdingPool while this call holds the pool, even when the handler throws
        bool& flag;
        bool held;
        ~PoolHeld() {
            if (held) flag = false;
        }
    } poolHeld{holdingPool, parallel};
    if (parallel) holdingPool = true;
    detail::PairCacheTable::Lease pairCache(detail::pairCacheTable());
    // The installed settings, once for the call: every pair of a step is collided with the same.
    const Settings settings = detail::installedSettings(lease.cache);
    phase.settings = &settings;
    Call call{scratch, maxContactsPerPair, slotSize, lease.cache, settings, job, !parallel, nullptr, pairCache};
    std::int64_t serialNarrowNanos = 0;
    if (profile && !parallel) call.serialNarrowNanos = &serialNarrowNanos;

    // 1. The broad phase (ODE's, serial, on this thread): ODE's pairs collided at once; gdcontact's
    //    listed, and collided on the pool threads as soon as listed (2.) — or at once when serial.
    if (parallel) pool.start(job, threads - 1);
    dSpaceCollide(space, &call, &nearCallback);
    job.close(scratch.gdcontactPairs);
    const auto broadPhaseEnd = profile ? ProfileClock::now() : ProfileClock::time_point{};

    // Every pair collided and the pool released: after a failure, or an exception from the handler
    // (the pool's threads may still be colliding pairs into this call's slots).
    auto finishPool = [&] {
        if (!parallel) return;
        job.work();
        pool.finish();
        poolLock.unlock();
    };
    if (call.failure) {
        finishPool();
        std::rethrow_exception(call.failure);
    }

    // 2. The handler, on the calling thread, in the broad phase's order. With the pool, the
    //    narrow phase is still running: a gdcontact pair not yet collided has this thread collide
    //    the next chunk of pairs (or, when none is left, wait for the pool thread colliding it), so
    //    the handler's work overlaps the pool's instead of following it.
    std::int64_t waitNanos = 0;
    // A pair's contacts once collided (waiting for, or taking part in, the narrow phase).
    auto collided = [&](const Pair& pair, int& count) -> dContactGeom* {
        if (!pair.gdcontact) {
            count = pair.count;
            return scratch.packed.data.get() + pair.index;
        }
        std::size_t offset;
        SlotBlock& block = scratch.blocks[blockOf(pair.index, offset)];
        const Slot& slot = block.slots[offset];
        while ((count = slot.count.load(std::memory_order_acquire)) < 0) {
            if (job.workChunk()) continue;
            const auto waitStart = profile ? ProfileClock::now() : ProfileClock::time_point{};
            for (int spins = 0; (count = slot.count.load(std::memory_order_acquire)) < 0; ++spins)
                if (spins >= 64) std::this_thread::yield();
            if (profile) waitNanos += nanosSince(waitStart);
        }
        return block.contacts.get() + offset * static_cast<std::size_t>(slotSize);
    };
    // The per-body-pair budget: where two bodies touch through several geom pairs, all their
    // contacts are reduced together (on this thread, in the broad phase's order of the pairs, so
    // the result does not depend on the thread count) when the first of those pairs is handed
    // over; each pair then keeps its survivors, compacted in its own contacts.
    const bool bodyPairBudget = settings.maxBodyPairContacts > 0 && scratch.linkBodyPairs();
    auto reduceBodyPair = [&](int head) {
        scratch.bodyPairContacts.clear();
        scratch.bodyPairOwner.clear();
        for (int i = head; i >= 0; i = scratch.bodyPairNext[static_cast<std::size_t>(i)]) {
            int count;
            const dContactGeom* contacts = collided(scratch.pairs[static_cast<std::size_t>(i)], count);
            scratch.bodyPairContacts.insert(scratch.bodyPairContacts.end(), contacts, contacts + std::max(count, 0));
            scratch.bodyPairOwner.insert(scratch.bodyPairOwner.end(), static_cast<std::size_t>(std::max(count, 0)), i);
            scratch.reducedCount[static_cast<std::size_t>(i)] = 0;
        }
        const Pair& first = scratch.pairs[static_cast<std::size_t>(head)];
        const int total = static_cast<int>(scratch.bodyPairContacts.size());
        int kept;
        try {
            kept = detail::chooseBodyPairContacts(dGeomGetBody(first.o1), dGeomGetBody(first.o2),
                                                  scratch.bodyPairContacts.data(), total, sizeof(dContactGeom),
                                                  settings, scratch.bodyPairPoints, scratch.bodyPairKept);
        } catch (const InvalidInput&) {  // a contact with a zero normal (ODE's convex collider): all as they were
            scratch.bodyPairKept.resize(static_cast<std::size_t>(total));
            for (int k = 0; k < total; ++k) scratch.bodyPairKept[static_cast<std::size_t>(k)] = k;
            kept = total;
        }
        // Ascending indices, pair by pair: each survivor moves to the front of its own pair's contacts.
        for (int k = 0; k < kept; ++k) {
            const int index = scratch.bodyPairKept[static_cast<std::size_t>(k)];
            const int owner = scratch.bodyPairOwner[static_cast<std::size_t>(index)];
            int count;
            dContactGeom* contacts = collided(scratch.pairs[static_cast<std::size_t>(owner)], count);
            contacts[scratch.reducedCount[static_cast<std::size_t>(owner)]++] =
                scratch.bodyPairContacts[static_cast<std::size_t>(index)];
        }
    };
    try {
        for (std::size_t i = 0; i < scratch.pairs.size(); ++i) {
            const Pair& pair = scratch.pairs[i];
            int count;
            dContactGeom* contacts = collided(pair, count);
            if (pair.gdcontact) {
                std::size_t offset;
                const Slot& slot = scratch.blocks[blockOf(pair.index, offset)].slots[offset];
                if (slot.cache) pairCache.count(*slot.cache);
            }
            if (bodyPairBudget && scratch.bodyPairHead[i] >= 0) {
                if (scratch.reducedCount[i] < 0) reduceBodyPair(scratch.bodyPairHead[i]);
                count = scratch.reducedCount[i];
            }
            if (count > 0) handler(data, pair.o1, pair.o2, contacts, count);
        }
    } catch (...) {
        finishPool();
        throw;
    }
    finishPool();

    if (profile) {
        const auto end = ProfileClock::now();
        auto seconds = [](ProfileClock::duration d) { return std::chrono::duration<double>(d).count(); };
        detail::SpaceCollideProfile& p = lastProfile;
        p.threads = parallel ? threads : 1;
        p.gdcontactPairs = parallel ? scratch.gdcontactPairs : call.serialGdcontactPairs;
        p.otherPairs = scratch.pairs.size() - p.gdcontactPairs;
        p.totalSeconds = seconds(end - callStart);
        p.broadPhaseSeconds = seconds(broadPhaseEnd - callStart);
        const std::int64_t narrow = parallel ? phase.narrowNanos.load() : serialNarrowNanos;
        p.narrowSeconds = 1e-9 * static_cast<double>(narrow);
        p.narrowOnCallerSeconds = 1e-9 * static_cast<double>(parallel ? phase.callerNanos : serialNarrowNanos);
        const std::int64_t poolStart = phase.poolStartNanos.load();
        p.poolStartSeconds = poolStart < 0 ? -1.0 : 1e-9 * static_cast<double>(poolStart);
        // After the broad phase the calling thread ran the handler, with (parallel) its share of
        // the narrow phase and waits for the pool in between: the handler is what is left.
        const double afterBroadPhase = seconds(end - broadPhaseEnd);
        p.drainSeconds = parallel ? p.narrowOnCallerSeconds + 1e-9 * static_cast<double>(waitNanos) : 0.0;
        p.handlerSeconds = std::max(0.0, afterBroadPhase - p.drainSeconds);
    }
}

namespace detail {

bool spaceCollideProfilingBuilt() { return kPhaseProfilingBuilt; }

void setSpaceCollideProfiling(bool enabled) {
    if (enabled && !kPhaseProfilingBuilt)
        throw InvalidInput("gdcontact was built without GDCONTACT_PHASE_PROFILING: spaceCollide records no phase times");
    profiling.store(enabled, std::memory_order_relaxed);
}

SpaceCollideProfile lastSpaceCollideProfile() { return lastProfile; }

}  // namespace detail

}  // namespace gdc::ode

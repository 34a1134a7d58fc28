// gdc::ode::spaceCollide / setThreadCount: a whole step's collision in one call. ODE's broad phase
// (dSpaceCollide, nested spaces through dSpaceCollide2) lists the candidate pairs on the calling
// thread; the pairs gdcontact handles are collided on a small pool of threads, each into its own
// slot, as soon as the broad phase lists them (the pool works while the broad phase still runs);
// the other pairs go to dCollide on the calling thread, inside the broad phase; then the handler
// runs on the calling thread for every touching pair, in the broad phase's order. So the output
// (and the contact joints a handler makes from it) does not depend on the thread count.
//
// Why the pool may read geoms while the broad phase runs: ODE's spaces (simple, hash) clean every
// geom of the space tree — world pose and AABB, recursively into nested spaces — before they report
// the first pair, and afterwards only read the geoms (dSpaceCollide2 on a nested space re-cleans
// nothing that is clean). The pool reads only gdcontact pairs' geoms (pose, class, box lengths, the
// convex registry), ODE's colliders on the calling thread only read them too.
//
// Why a std::thread pool and not oneTBB: the work is one flat loop over independent pairs per
// step, which a pool of a few dozen lines does with an atomic counter; oneTBB would become a
// dependency of the installed library (its CMake config, pkg-config file and Debian package) for
// that one loop, and its own synchronisation is not visible to ThreadSanitizer unless TBB itself is
// instrumented. The pool's threads sleep on a condition variable between calls.
#include <gdcontact/ode.hpp>

#include "pair_cache_table.hpp"
#include "state.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <vector>

namespace gdc::ode {
namespace {

constexpr int kMaxThreads = 256;

// 0: one per hardware thread.
std::atomic<int> requestedThreads{0};

int effectiveThreadCount() {
    const int requested = requestedThreads.load(std::memory_order_relaxed);
    if (requested > 0) return requested;
    const unsigned hardware = std::thread::hardware_concurrency();
    return hardware == 0 ? 1 : static_cast<int>(std::min<unsigned>(hardware, kMaxThreads));
}

// One parallel loop over indices that a producer publishes while the loop runs: body(context,
// begin, end) in chunks, taken in any order by any participant (each index writes only its own
// output, so the order of execution is invisible). The producer stores `available` after each
// index it makes ready and sets `closed` after the last; a participant ahead of it waits.
struct Job {
    void (*body)(void* context, std::size_t begin, std::size_t end) = nullptr;
    void* context = nullptr;
    std::size_t chunk = 1;
    std::atomic<std::size_t> next{0};
    std::atomic<std::size_t> available{0};
    std::atomic<bool> closed{false};

    void work() {
        for (;;) {
            const std::size_t begin = next.fetch_add(chunk, std::memory_order_relaxed);
            std::size_t end = begin + chunk;
            for (int spins = 0;; ++spins) {
                if (available.load(std::memory_order_acquire) >= end) break;
                if (closed.load(std::memory_order_acquire)) {  // `available` is final now
                    end = std::min(end, available.load(std::memory_order_acquire));
                    break;
                }
                if (spins >= 64) std::this_thread::yield();  // the broad phase is behind
            }
            if (begin >= end) return;
            body(context, begin, end);
        }
    }
};

// Worker threads that sleep between jobs. One thread at a time posts a job (it holds
// WorkerPool::use) and works on it too. A worker joins a job only while it is open: one that wakes
// after the caller has finished every index (the machine busy with other work) finds it closed and
// sleeps again, so the caller never waits for a thread that has not yet run.
class WorkerPool {
public:
    std::mutex use;  // held by the thread running a job (spaceCollide try-locks it)

    ~WorkerPool() { resize(0); }

    // Sets `workers` pool threads (≥ 1) working on `job`; finish() waits for those that joined.
    // The caller publishes the job's indices meanwhile, closes it, and works on it too.
    void start(Job& job, int workers) {
        if (static_cast<int>(threads_.size()) != workers) resize(workers);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            job_ = &job;
            ++generation_;
        }
        wake_.notify_all();
    }
    // Call when every index of the job is taken (Job::work has returned on the caller).
    void finish() {
        std::unique_lock<std::mutex> lock(mutex_);
        job_ = nullptr;  // no worker joins from now on
        finished_.wait(lock, [&] { return active_ == 0; });
    }

private:
    void resize(int workers) {
        if (!threads_.empty()) {
            {
                std::lock_guard<std::mutex> lock(mutex_);
                stopping_ = true;
            }
            wake_.notify_all();
            for (std::thread& thread : threads_) thread.join();
            threads_.clear();
            stopping_ = false;
        }
        threads_.reserve(static_cast<std::size_t>(workers));
        // A new thread must not take the generation current when it starts: the next job may have
        // been posted by then. Only start() changes it, on this thread, so it is read here.
        for (int i = 0; i < workers; ++i) threads_.emplace_back([this, seen = generation_] { loop(seen); });
    }

    void loop(std::uint64_t seen) {
        for (;;) {
            Job* job;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
                if (stopping_) return;
                seen = generation_;
                job = job_;
                if (!job) continue;  // woke too late: the caller has done it all
                ++active_;
            }
            job->work();
            bool last;
            {
                std::lock_guard<std::mutex> lock(mutex_);
                last = --active_ == 0;
            }
            if (last) finished_.notify_one();
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable finished_;
    std::vector<std::thread> threads_;
    std::uint64_t generation_ = 0;
    Job* job_ = nullptr;  // the open job; nullptr once the caller has finished it
    int active_ = 0;      // workers inside job_->work()
    bool stopping_ = false;
};

WorkerPool& workerPool() {
    static WorkerPool pool;
    return pool;
}

// A candidate pair in the broad phase's order: a gdcontact pair collided on the pool by its index in
// the slot store; a pair collided at once on the calling thread by its contacts' offset in the
// packed buffer (`count` contacts).
struct Pair {
    dGeomID o1;
    dGeomID o2;
    std::size_t index;
    int count;
    bool gdcontact;
};

// gdcontact's pairs and their output slots, written by the broad phase while the pool reads the
// ones published: blocks that never move, block k holding kFirstBlock << k pairs.
constexpr std::size_t kFirstBlock = 1024;
constexpr int kBlocks = 40;  // kFirstBlock · (2^40 − 1) pairs: more than memory holds

struct Slot {
    dGeomID o1;
    dGeomID o2;
    int count;
    PairCache* cache;  // the pair's entry in the adapter's pair cache; nullptr: none
};

struct SlotBlock {
    std::unique_ptr<Slot[]> slots;
    std::unique_ptr<dContactGeom[]> contacts;  // slotSize per pair
    int slotSize = 0;
};

inline int blockOf(std::size_t index, std::size_t& offset) {
    const std::size_t scaled = index / kFirstBlock + 1;  // block k holds scaled in [2^k, 2^(k+1))
    const int block = 63 - __builtin_clzll(static_cast<unsigned long long>(scaled));
    offset = index - kFirstBlock * ((std::size_t{1} << block) - 1);
    return block;
}

// One spaceCollide call's buffers, kept per calling thread so that a step allocates nothing once
// the scene's size has been seen (a handler calling spaceCollide again gets fresh ones).
struct Scratch {
    std::vector<Pair> pairs;
    SlotBlock blocks[kBlocks];
    // The contacts of the pairs collided on the calling thread (ODE's; gdcontact's when serial),
    // one pair after the other. Not a std::vector: room for a pair is made without filling it.
    struct Packed {
        std::unique_ptr<dContactGeom[]> data;
        std::size_t size = 0, capacity = 0;
        dContactGeom* reserve(std::size_t room) {  // room for `room` more; their address
            if (size + room > capacity) {
                const std::size_t grown = std::max(2 * capacity, size + room + 1024);
                std::unique_ptr<dContactGeom[]> bigger(new dContactGeom[grown]);
                std::copy(data.get(), data.get() + size, bigger.get());
                data = std::move(bigger);
                capacity = grown;
            }
            return data.get() + size;
        }
    } packed;
    std::size_t gdcontactPairs = 0;
    bool inUse = false;

    // The slot of gdcontact pair `index`, its block made ready for `slotSize` contacts a pair.
    Slot& slotFor(std::size_t index, int slotSize, dContactGeom*& contacts) {
        std::size_t offset;
        SlotBlock& block = blocks[blockOf(index, offset)];
        const std::size_t size = kFirstBlock << (&block - blocks);
        if (!block.slots) block.slots.reset(new Slot[size]);
        if (block.slotSize != slotSize) {
            block.contacts.reset(new dContactGeom[size * static_cast<std::size_t>(slotSize)]);
            block.slotSize = slotSize;
        }
        contacts = block.contacts.get() + offset * static_cast<std::size_t>(slotSize);
        return block.slots[offset];
    }
};

struct Call {
    Scratch& scratch;
    int maxContacts;  // the caller's maxContactsPerPair
    int slotSize;     // contacts kept per gdcontact pair: min(maxContacts, kMaxManifoldPoints)
    detail::ThreadCache& cache;
    Job& job;  // publishes each gdcontact pair to the pool as soon as it is listed
    bool serial;  // no pool: collide each gdcontact pair at once, as a near callback would
    std::exception_ptr failure;  // thrown inside ODE's broad phase, rethrown after it
    // This call's hold on the pair cache: each gdcontact pair's entry is found here, on the calling
    // thread, and handed to whichever thread collides the pair (one thread per pair: never shared).
    detail::PairCacheTable::Lease& pairCache;
};

// Box, createConvex convex or plane (not plane–plane): the pairs collide() handles.
bool isGdcontactGeom(dGeomID geom, int geomClass, detail::ThreadCache& cache) {
    if (geomClass == dBoxClass || geomClass == dPlaneClass) return true;
    return geomClass == dConvexClass && detail::borrowedConvex(cache, geom) != nullptr;
}

void addPair(Call& call, dGeomID o1, dGeomID o2) {
    const int class1 = dGeomGetClass(o1);
    const int class2 = dGeomGetClass(o2);
    Scratch& scratch = call.scratch;
    const bool ours = !(class1 == dPlaneClass && class2 == dPlaneClass) &&
                      isGdcontactGeom(o1, class1, call.cache) && isGdcontactGeom(o2, class2, call.cache);
    if (ours && !call.serial) {
        // Settles the geoms' world poses here, on the calling thread (dGeomGetPosition recomputes a
        // stale one), so that the workers only read them. The broad phase has normally done it.
        if (class1 != dPlaneClass) dGeomGetPosition(o1);
        if (class2 != dPlaneClass) dGeomGetPosition(o2);
        const std::size_t index = scratch.gdcontactPairs;
        scratch.pairs.push_back(Pair{o1, o2, index, 0, true});  // may throw: before publishing
        dContactGeom* contacts;
        Slot& slot = scratch.slotFor(index, call.slotSize, contacts);
        slot.o1 = o1;
        slot.o2 = o2;
        slot.count = 0;
        slot.cache = call.pairCache && detail::pairCacheWorthIt(o1, o2, detail::installedSettings(call.cache))
                         ? call.pairCache.find(o1, o2)
                         : nullptr;
        scratch.gdcontactPairs = index + 1;
        call.job.available.store(index + 1, std::memory_order_release);
        return;
    }
    // ODE's own collider as a near callback would call it (or, when serial, gdcontact's), here and
    // now on the calling thread, the contacts packed one pair after the other.
    const int room = ours ? call.slotSize : call.maxContacts;
    dContactGeom* out = scratch.packed.reserve(static_cast<std::size_t>(room));
    PairCache* cache = ours && call.pairCache && detail::pairCacheWorthIt(o1, o2, detail::installedSettings(call.cache))
                           ? call.pairCache.find(o1, o2)
                           : nullptr;
    const int count = ours ? detail::collideWithPairCache(o1, o2, room, out, sizeof(dContactGeom), cache)  // never throws
                           : dCollide(o1, o2, room, out, sizeof(dContactGeom));
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
    Scratch* scratch;
    int slotSize;
};

void collideRange(void* context, std::size_t begin, std::size_t end) {
    NarrowPhase& phase = *static_cast<NarrowPhase*>(context);
    for (std::size_t i = begin; i < end; ++i) {
        std::size_t offset;
        SlotBlock& block = phase.scratch->blocks[blockOf(i, offset)];
        Slot& slot = block.slots[offset];
        // collide() never throws: a failure becomes a dMessage and 0 contacts.
        slot.count = detail::collideWithPairCache(
            slot.o1, slot.o2, phase.slotSize, block.contacts.get() + offset * static_cast<std::size_t>(phase.slotSize),
            sizeof(dContactGeom), slot.cache);
    }
}

// The calling thread's scratch; a fresh one when spaceCollide is re-entered from a handler.
struct ScratchLease {
    Scratch* scratch;
    Scratch* owned = nullptr;
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
    }
    ~ScratchLease() {
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

    ScratchLease lease;
    Scratch& scratch = *lease.scratch;
    const int slotSize = std::min(maxContactsPerPair, kMaxManifoldPoints);
    NarrowPhase phase{&scratch, slotSize};
    Job job;
    job.body = &collideRange;
    job.context = &phase;
    job.chunk = 8;  // a few microseconds of work: balances uneven pairs, keeps the counter quiet
    const int threads = effectiveThreadCount();
    WorkerPool& pool = workerPool();
    std::unique_lock<std::mutex> poolLock(pool.use, std::defer_lock);
    const bool parallel = threads > 1 && poolLock.try_lock();  // else serial: 1 thread, or pool busy
    detail::PairCacheTable::Lease pairCache(detail::pairCacheTable());
    Call call{scratch, maxContactsPerPair, slotSize, detail::threadCache(), job, !parallel, nullptr, pairCache};

    // 1. The broad phase (ODE's, serial, on this thread): ODE's pairs collided at once; gdcontact's
    //    listed, and collided on the pool threads as soon as listed (2.) — or at once when serial.
    if (parallel) pool.start(job, threads - 1);
    dSpaceCollide(space, &call, &nearCallback);
    job.closed.store(true, std::memory_order_release);

    // 2. The rest of gdcontact's pairs, on this thread too; then every pair is done.
    if (parallel) {
        job.work();
        pool.finish();
        poolLock.unlock();
    }
    if (call.failure) std::rethrow_exception(call.failure);

    // 3. The handler, on the calling thread, in the broad phase's order.
    for (const Pair& pair : scratch.pairs) {
        dContactGeom* contacts;
        int count;
        if (pair.gdcontact) {
            std::size_t offset;
            SlotBlock& block = scratch.blocks[blockOf(pair.index, offset)];
            const Slot& slot = block.slots[offset];
            count = slot.count;
            if (slot.cache) pairCache.count(*slot.cache);
            contacts = block.contacts.get() + offset * static_cast<std::size_t>(slotSize);
        } else {
            count = pair.count;
            contacts = scratch.packed.data.get() + pair.index;
        }
        if (count > 0) handler(data, pair.o1, pair.o2, contacts, count);
    }
}

}  // namespace gdc::ode

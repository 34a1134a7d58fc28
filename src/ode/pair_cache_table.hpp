// The adapter's pair cache: one gdc::PairCache per geom pair ODE asks about, so that a pair that
// did not move is answered without a query (exact), and with Settings::manifoldReuseDistance a
// pair that moved little gets its contacts carried along. The core stays pure — the cache is the
// explicit object collide() takes; this table is where the adapter keeps one per pair.
//
// Who touches the table: a thread that holds its lease. spaceCollide holds it for the whole call
// — its calling thread finds each pair's entry while ODE's broad phase lists the pair, and the
// pool's threads then use only the entries handed to them (each pair is collided by exactly one
// thread, so a PairCache is never shared). A plain collide() call (a near callback, ODE's
// dCollide) tries to take the lease for its one pair and, if another thread holds it, runs the
// query without the cache — it never waits. The answers are the same either way (the cache is
// exact unless manifoldReuseDistance is set).
//
// Memory: an entry dies when ODE frees one of its geoms (the adapter's free hook notes the address;
// the next lease removes its entries) or when its pair has not been asked about for a whole ageing
// round (the pairs of bodies that moved apart); and there are never more than capacity() entries.
#pragma once

#include <gdcontact/pair_cache.hpp>

#include <ode/ode.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace gdc::ode::detail {

class PairCacheTable {
public:
    struct Stats {
        std::size_t entries = 0;
        std::size_t capacity = 0;
        std::size_t bytes = 0;  // entry storage and index
        std::uint64_t repeated = 0, carried = 0, computed = 0;
    };

    /// The table for one thread's use, or nothing (another thread has it, or this thread already
    /// holds it, or the cache is switched off).
    class Lease {
    public:
        explicit Lease(PairCacheTable& table);
        ~Lease();
        Lease(const Lease&) = delete;
        Lease& operator=(const Lease&) = delete;
        explicit operator bool() const { return table_ != nullptr; }
        /// The cache of the pair {geom1, geom2} (either order), made empty if new; nullptr when the
        /// table is full, or when this lease has handed it out already (a pair listed twice must not
        /// have one cache used by two threads at once). Valid until the lease ends.
        PairCache* find(const void* geom1, const void* geom2);
        /// Counts how the entry handed out by find() answered its last query.
        void count(const PairCache& cache);

    private:
        PairCacheTable* table_ = nullptr;
    };

    void setEnabled(bool enabled);
    bool enabled() const { return enabled_.load(std::memory_order_relaxed); }
    /// At most `entries` entries (0: no new entries); shrinking drops the least recently used.
    void setCapacity(std::size_t entries);
    /// Empties the table (statistics too). Waits for a running lease.
    void clear();
    Stats stats();
    /// ODE freed `address` (maybe a geom): its entries go at the next lease. Never blocks on the
    /// table (a free may happen while a lease is held); safe from any thread.
    void noteFreed(const void* address) noexcept;

private:
    struct Entry {
        const void* first = nullptr;  // the pair's geoms, lower address first
        const void* second = nullptr;
        std::uint64_t lastUse = 0;  // the lease that last found it
        PairCache cache;
    };
    struct Slot {
        const void* first = nullptr;
        const void* second = nullptr;
        Entry* entry = nullptr;  // nullptr: empty (erasures rebuild the index: no tombstones)
    };

    Entry* lookUp(const void* first, const void* second);
    Entry* insert(const void* first, const void* second);
    void place(const Slot& slot);
    void rebuildIndex(std::size_t slots);
    void purgeFreed();
    void age();
    void erase(const std::vector<Entry*>& doomed);
    std::size_t home(const void* first, const void* second) const;

    // The lease: a flag, not a mutex — a plain collide() only ever tries it (a try of an
    // uncontended std::mutex and its unlock is a measurable part of a repeated answer).
    std::atomic<bool> held_{false};
    // For the rare calls that must wait (clear, setCapacity, stats): false when this thread holds
    // the lease already (inside a spaceCollide handler), which then needs no taking.
    bool acquireWaiting();
    struct Waited;
    std::atomic<bool> enabled_{true};
    std::size_t capacity_ = std::size_t{1} << 16;
    std::uint64_t clock_ = 0;            // leases so far
    std::uint64_t lastAgeing_ = 0;       // clock_ at the last ageing round
    std::size_t insertsSinceAgeing_ = 0;
    std::vector<Slot> index_;            // open addressing, linear probing, at most half full
    std::vector<std::unique_ptr<Entry[]>> chunks_;  // entries never move: workers hold pointers
    std::vector<Entry*> freeEntries_;
    std::size_t liveEntries_ = 0;
    std::uint64_t repeated_ = 0, carried_ = 0, computed_ = 0;

    std::atomic<bool> everFilled_{false};  // the free hook has nothing to note before the first entry
    std::mutex freedMutex_;  // guards freed_ only: the free hook never waits for a lease
    std::vector<const void*> freed_;
    std::atomic<bool> freedPending_{false};
};

/// The adapter's one table.
PairCacheTable& pairCacheTable();

/// Whether a pair is worth its cache entry. With the exact default only a pair whose geoms are
/// static or belong to disabled bodies can repeat its poses bit for bit — ODE moves every enabled
/// body each step, if only by a solver's jitter — so only such a pair is looked up; every other
/// pair skips the table (a lookup, a comparison and a store it could never profit from: before
/// this rule the big-world benchmark's moving piles collided slower with the cache than without).
/// With manifoldReuseDistance every pair may be carried.
inline bool pairCacheWorthIt(dGeomID o1, dGeomID o2, const Settings& settings) {
    if (settings.manifoldReuseDistance > 0) return true;
    const dBodyID body1 = dGeomGetBody(o1), body2 = dGeomGetBody(o2);
    return (!body1 || !dBodyIsEnabled(body1)) && (!body2 || !dBodyIsEnabled(body2));
}

/// gdc::ode::collide with the installed settings and the pair's cache `cache` (which the caller
/// holds through its lease; nullptr: none). Never throws.
int collideWithPairCache(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip,
                         PairCache* cache) noexcept;

}  // namespace gdc::ode::detail

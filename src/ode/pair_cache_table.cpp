// The adapter's pair cache table (pair_cache_table.hpp).
#include "pair_cache_table.hpp"

#include "free_hook.hpp"

#include <algorithm>
#include <functional>
#include <thread>
#include <unordered_set>

namespace gdc::ode::detail {
namespace {

constexpr std::size_t kChunkEntries = 256;
// An ageing round comes after this many new entries, or as many as there are, whichever is more:
// a resting scene (no new pairs) never ages; a moving one drops the pairs that stopped touching
// within about one round of their last query.
constexpr std::size_t kMinimumAgeingRound = 1024;

// Whether this thread holds a lease (a handler inside spaceCollide calling collide() must not try
// the lock it already holds).
thread_local bool leaseHeld = false;

}  // namespace

PairCacheTable& pairCacheTable() {
    // Never destroyed, like the adapter's other state: ODE may free geoms (and so call the free
    // hook, which notes them here) from static destructors that run after ours would have.
    static PairCacheTable* const table = new PairCacheTable;
    return *table;
}

PairCacheTable::Lease::Lease(PairCacheTable& table) {
    if (leaseHeld || !table.enabled() || table.held_.load(std::memory_order_relaxed) ||
        table.held_.exchange(true, std::memory_order_acquire))
        return;
    leaseHeld = true;
    table_ = &table;
    ++table.clock_;
    if (table.freedPending_.load(std::memory_order_acquire)) table.purgeFreed();
}

PairCacheTable::Lease::~Lease() {
    if (!table_) return;
    leaseHeld = false;
    table_->held_.store(false, std::memory_order_release);
}

PairCache* PairCacheTable::Lease::find(const void* geom1, const void* geom2) {
    const bool ordered = std::less<const void*>{}(geom1, geom2);
    const void* first = ordered ? geom1 : geom2;
    const void* second = ordered ? geom2 : geom1;
    Entry* entry = table_->lookUp(first, second);
    // Handed out already under this lease: the broad phase listed the pair twice (ODE's near-callback
    // pattern for nested spaces collides a sub-space once per geom it overlaps), and spaceCollide's
    // threads may collide the two listings at once — so the second goes without the cache (the
    // exact cache's answer is the query's anyway).
    if (entry && entry->lastUse == table_->clock_) return nullptr;
    if (!entry) entry = table_->insert(first, second);
    if (!entry) return nullptr;
    entry->lastUse = table_->clock_;
    return &entry->cache;
}

void PairCacheTable::Lease::count(const PairCache& cache) {
    switch (cache.lastAnswer()) {
        case CacheAnswer::Repeated: ++table_->repeated_; break;
        case CacheAnswer::Carried: ++table_->carried_; break;
        case CacheAnswer::Computed: ++table_->computed_; break;
    }
}

std::size_t PairCacheTable::home(const void* first, const void* second) const {
    // Fibonacci hashing (Knuth) of the two addresses; the index size is a power of two.
    const auto a = static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(first));
    const auto b = static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(second));
    const std::uint64_t mixed = (a ^ (b * 0xC2B2AE3D27D4EB4Full)) * 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(mixed >> 32) & (index_.size() - 1);
}

PairCacheTable::Entry* PairCacheTable::lookUp(const void* first, const void* second) {
    if (index_.empty()) return nullptr;
    for (std::size_t i = home(first, second);; i = (i + 1) & (index_.size() - 1)) {
        const Slot& slot = index_[i];
        if (!slot.entry) return nullptr;
        if (slot.first == first && slot.second == second) return slot.entry;
    }
}

PairCacheTable::Entry* PairCacheTable::insert(const void* first, const void* second) {
    if (liveEntries_ >= capacity_ || ++insertsSinceAgeing_ >= std::max(kMinimumAgeingRound, liveEntries_)) age();
    if (liveEntries_ >= capacity_) return nullptr;
    // Every new entry checks that the free hook is in place (another library may have replaced
    // ODE's free handler since); it is a lock and a compare, and new pairs are rare in a step.
    ensureFreeHook();  // may throw (a lock): before anything changed
    everFilled_.store(true, std::memory_order_relaxed);
    if (freeEntries_.empty()) {
        chunks_.emplace_back(new Entry[kChunkEntries]);
        for (std::size_t i = kChunkEntries; i-- > 0;) freeEntries_.push_back(&chunks_.back()[i]);
    }
    if (2 * (liveEntries_ + 1) > index_.size()) rebuildIndex(std::max<std::size_t>(64, 4 * (liveEntries_ + 1)));
    Entry* entry = freeEntries_.back();
    freeEntries_.pop_back();
    entry->first = first;
    entry->second = second;
    entry->cache.clear();
    ++liveEntries_;
    place(Slot{first, second, entry});
    return entry;
}

// Linear probing: into the first empty slot from the pair's home (the index is at most half full).
void PairCacheTable::place(const Slot& slot) {
    for (std::size_t i = home(slot.first, slot.second);; i = (i + 1) & (index_.size() - 1))
        if (!index_[i].entry) {
            index_[i] = slot;
            return;
        }
}

void PairCacheTable::rebuildIndex(std::size_t slots) {
    std::size_t size = 64;
    while (size < slots) size *= 2;
    std::vector<Slot> old = std::move(index_);
    index_.assign(size, Slot{});
    for (const Slot& slot : old)
        if (slot.entry) place(slot);
}

void PairCacheTable::erase(const std::vector<Entry*>& doomed) {
    if (doomed.empty()) return;
    for (Entry* entry : doomed) {
        entry->first = entry->second = nullptr;
        entry->cache.clear();
        freeEntries_.push_back(entry);
    }
    liveEntries_ -= doomed.size();
    // Linear probing without tombstones: the survivors are placed again.
    for (Slot& slot : index_)
        if (slot.entry && !slot.entry->first) slot = Slot{};
    rebuildIndex(index_.size());
}

// Entries not found since the last round: the pairs ODE stopped asking about. Entries found in
// the current lease are never among them (their lastUse is the current clock), so the pointers a
// running spaceCollide handed out stay valid.
void PairCacheTable::age() {
    std::vector<Entry*> doomed;
    for (const Slot& slot : index_)
        if (slot.entry && slot.entry->lastUse < lastAgeing_) doomed.push_back(slot.entry);
    erase(doomed);
    lastAgeing_ = clock_;
    insertsSinceAgeing_ = 0;
}

void PairCacheTable::purgeFreed() {
    std::vector<const void*> freed;
    {
        std::lock_guard<std::mutex> lock(freedMutex_);
        freed.swap(freed_);
        freedPending_.store(false, std::memory_order_release);
    }
    if (liveEntries_ == 0 || freed.empty()) return;
    const std::unordered_set<const void*> gone(freed.begin(), freed.end());
    std::vector<Entry*> doomed;
    for (const Slot& slot : index_)
        if (slot.entry && (gone.count(slot.first) || gone.count(slot.second))) doomed.push_back(slot.entry);
    erase(doomed);
}

void PairCacheTable::noteFreed(const void* address) noexcept {
    if (!everFilled_.load(std::memory_order_relaxed)) return;
    try {
        std::lock_guard<std::mutex> lock(freedMutex_);
        freed_.push_back(address);
        freedPending_.store(true, std::memory_order_release);
    } catch (...) {
        // Out of memory (or a lock failure): the entry then ages out instead — never wrong, since
        // a PairCache recognises its shapes and poses, not its geoms.
    }
}

void PairCacheTable::setEnabled(bool enabled) { enabled_.store(enabled, std::memory_order_relaxed); }

bool PairCacheTable::acquireWaiting() {
    if (leaseHeld) return false;
    while (held_.load(std::memory_order_relaxed) || held_.exchange(true, std::memory_order_acquire))
        std::this_thread::yield();  // a lease lasts one pair, or one spaceCollide call
    return true;
}

// Releases what acquireWaiting took, at the end of the scope.
struct PairCacheTable::Waited {
    PairCacheTable& table;
    bool taken;
    ~Waited() {
        if (taken) table.held_.store(false, std::memory_order_release);
    }
};

void PairCacheTable::setCapacity(std::size_t entries) {
    const Waited lock{*this, acquireWaiting()};
    capacity_ = entries;
    if (liveEntries_ <= capacity_) return;
    std::vector<Entry*> byAge;
    for (const Slot& slot : index_)
        if (slot.entry) byAge.push_back(slot.entry);
    std::sort(byAge.begin(), byAge.end(), [](const Entry* x, const Entry* y) { return x->lastUse < y->lastUse; });
    byAge.resize(liveEntries_ - capacity_);
    erase(byAge);
}

void PairCacheTable::clear() {
    const Waited lock{*this, acquireWaiting()};
    index_.clear();
    chunks_.clear();
    freeEntries_.clear();
    liveEntries_ = 0;
    insertsSinceAgeing_ = 0;
    repeated_ = carried_ = computed_ = 0;
}

PairCacheTable::Stats PairCacheTable::stats() {
    const Waited lock{*this, acquireWaiting()};
    if (freedPending_.load(std::memory_order_acquire)) purgeFreed();
    Stats stats;
    stats.entries = liveEntries_;
    stats.capacity = capacity_;
    stats.bytes = chunks_.size() * kChunkEntries * sizeof(Entry) + index_.capacity() * sizeof(Slot);
    stats.repeated = repeated_;
    stats.carried = carried_;
    stats.computed = computed_;
    return stats;
}

}  // namespace gdc::ode::detail

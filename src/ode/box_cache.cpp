#include "box_cache.hpp"

#include <array>
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

struct BoxCache {
    std::shared_mutex mutex;
    std::unordered_map<BoxKey, std::shared_ptr<const Polytope>, BoxKeyHash> boxes;
};

// Never destroyed: a thread's cache may give its borrowed polytopes back after static destructors.
BoxCache& boxCache() {
    static BoxCache* const instance = new BoxCache;
    return *instance;
}

}  // namespace

std::shared_ptr<const Polytope> boxPolytope(double halfX, double halfY, double halfZ) {
    BoxCache& cache = boxCache();
    const BoxKey key{{halfX, halfY, halfZ}};
    {
        std::shared_lock lock(cache.mutex);
        auto found = cache.boxes.find(key);
        if (found != cache.boxes.end()) return found->second;
    }
    auto built = std::make_shared<const Polytope>(Polytope::box(Vec3(halfX, halfY, halfZ)));
    std::unique_lock lock(cache.mutex);
    if (cache.boxes.size() >= kBoxCacheCapacity) cache.boxes.clear();  // holders keep their copies alive
    return cache.boxes.emplace(key, std::move(built)).first->second;
}

const Polytope& borrowedBoxPolytopeSlow(ThreadCache& cache, const double* lengths) {
    const double halfX = 0.5 * lengths[0], halfY = 0.5 * lengths[1], halfZ = 0.5 * lengths[2];
    const std::uint64_t now = ++cache.boxClock;
    ThreadCache::BoxSlot* oldest = &cache.boxes[0];
    for (ThreadCache::BoxSlot& slot : cache.boxes) {
        if (slot.halfExtents[0] == halfX && slot.halfExtents[1] == halfY && slot.halfExtents[2] == halfZ) {
            slot.lastUse = now;
            std::memcpy(slot.lengths, lengths, sizeof slot.lengths);
            cache.lastBox = static_cast<int>(&slot - cache.boxes);
            return *slot.polytope;
        }
        if (slot.lastUse < oldest->lastUse) oldest = &slot;
    }
    // The least recently used slot is never one this thread used within the last
    // kBorrowedBoxSizes − 1 lookups, so no reference handed out in that window dangles.
    std::shared_ptr<const Polytope> polytope = boxPolytope(halfX, halfY, halfZ);  // may throw: slot untouched
    if (cache.pinnedBoxes && oldest->polytope) cache.pinnedBoxes->push_back(oldest->polytope);  // likewise
    oldest->polytope = std::move(polytope);
    oldest->halfExtents[0] = halfX;
    oldest->halfExtents[1] = halfY;
    oldest->halfExtents[2] = halfZ;
    std::memcpy(oldest->lengths, lengths, sizeof oldest->lengths);
    oldest->lastUse = now;
    cache.lastBox = static_cast<int>(oldest - cache.boxes);
    return *oldest->polytope;
}

}  // namespace gdc::ode::detail

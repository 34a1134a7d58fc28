// Per-pair persistent manifolds for a scene, keyed by two opaque pointers regardless of order.
#include <gdcontact/tracking.hpp>

#include <functional>

namespace gdc::tracking {

PairCache::PairCache(TrackingSettings settings) : settings_(settings) {
    PersistentManifold validate(settings);  // reject bad settings here, not at the first contact
    (void)validate;
}

std::size_t PairCache::KeyHash::operator()(const Key& key) const {
    const std::size_t low = std::hash<std::uintptr_t>{}(key.low);
    const std::size_t high = std::hash<std::uintptr_t>{}(key.high);
    return low ^ (high + 0x9e3779b97f4a7c15ULL + (low << 6) + (low >> 2));
}

PairCache::Key PairCache::makeKey(const void* first, const void* second) {
    if (first == nullptr || second == nullptr) throw InvalidInput("tracking: null pair key");
    if (first == second) throw InvalidInput("tracking: a pair key needs two distinct objects");
    const auto x = reinterpret_cast<std::uintptr_t>(first);
    const auto y = reinterpret_cast<std::uintptr_t>(second);
    return x < y ? Key{x, y} : Key{y, x};
}

void PairCache::beginStep() {
    ++step_;
}

PersistentManifold& PairCache::manifoldFor(const void* first, const void* second) {
    const Key key = makeKey(first, second);
    auto found = pairs_.find(key);
    if (found == pairs_.end())
        found = pairs_.emplace(key, Entry{PersistentManifold(settings_), first, step_}).first;
    Entry& entry = found->second;
    if (entry.first != first) {  // asked for in the other order than last time
        entry.manifold.swapBodies();
        entry.first = first;
    }
    entry.lastSeen = step_;
    return entry.manifold;
}

void PairCache::endStep() {
    for (auto it = pairs_.begin(); it != pairs_.end();) {
        if (it->second.lastSeen != step_)
            it = pairs_.erase(it);
        else
            ++it;
    }
}

bool PairCache::contains(const void* first, const void* second) const {
    return pairs_.count(makeKey(first, second)) != 0;
}

}  // namespace gdc::tracking

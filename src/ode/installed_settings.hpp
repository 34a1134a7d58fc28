// The settings of the last install(): a dColliderFn carries no user pointer, so collide() must
// find them globally. Each thread keeps a copy, refreshed when a generation counter says install()
// has run since: the common case reads one atomic and takes no lock.
#pragma once

#include "thread_cache.hpp"

#include <atomic>
#include <cstdint>

namespace gdc::ode::detail {

void setInstalledSettings(const Settings& settings);

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

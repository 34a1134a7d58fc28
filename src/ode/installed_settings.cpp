#include "installed_settings.hpp"

#include <mutex>
#include <shared_mutex>

namespace gdc::ode::detail {
namespace {

struct Installed {
    std::shared_mutex mutex;
    Settings settings;  // installedSettingsGeneration moves with it
};

Installed& installed() {
    static Installed* const instance = new Installed;  // never destroyed, like the other state
    return *instance;
}

}  // namespace

std::atomic<std::uint64_t> installedSettingsGeneration{1};

const Settings& refreshInstalledSettings(ThreadCache& cache) {
    Installed& s = installed();
    std::shared_lock lock(s.mutex);
    cache.settings = s.settings;
    cache.settingsGeneration = installedSettingsGeneration.load(std::memory_order_relaxed);  // moves only under the lock
    return cache.settings;
}

void setInstalledSettings(const Settings& settings) {
    Installed& s = installed();
    std::unique_lock lock(s.mutex);
    s.settings = settings;
    installedSettingsGeneration.fetch_add(1, std::memory_order_release);
}

}  // namespace gdc::ode::detail

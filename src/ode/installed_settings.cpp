#include "installed_settings.hpp"

#include "ode_real.hpp"

#include <gdcontact/ode.hpp>

#include <mutex>
#include <shared_mutex>

namespace gdc::ode::detail {
namespace {

struct Installed {
    std::shared_mutex mutex;
    Settings settings = defaultSettings();  // installedSettingsGeneration moves with it
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

namespace gdc::ode {

Settings defaultSettings() {
    Settings settings;
    // Against a single-precision ODE, 6 points a face pair let dWorldStep's Dantzig LCP stop on
    // exact ties (a row without force left exactly on its bound, then asked to move: the rows after
    // it get no force for that step) in stacks of turned plates far more often than dBox's points
    // or 8 of ours, and there the stacks tilt; dWorldQuickStep fails no more seeds with 8
    // (docs/install.md, "Single precision: 8 points a face").
    if constexpr (!detail::kOdeRealIsDouble) settings.maxContacts = 8;
    return settings;
}

}  // namespace gdc::ode

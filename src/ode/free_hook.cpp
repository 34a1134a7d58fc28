#include "free_hook.hpp"

#include "convex_registry.hpp"
#include "pair_cache_table.hpp"
#include "trimesh_geoms.hpp"

#include <ode/ode.h>

#include <atomic>
#include <cstdlib>
#include <mutex>

namespace gdc::ode::detail {
namespace {

struct Hook {
    // The free handler that was active before ours; ours forwards to it (nullptr: free()).
    std::atomic<dFreeFunction*> previousFree{nullptr};
    // Serialises installing the hook (a read-modify-write of ODE's handler).
    std::mutex mutex;
};

// Never destroyed: ODE may free geoms from static destructors that run after ours would have,
// and the hook must still find its predecessor then.
Hook& hook() {
    static Hook* const instance = new Hook;
    return *instance;
}

// ODE frees every geom through dFree (its objects' operator delete), after the geom's destructor
// ran. ODE calls it from C: nothing may leave it (a lock failure leaves the hull registered — an
// AABB mismatch later keeps it from a new geom at that address — and the memory is still freed).
void freeHook(void* pointer, dsizeint size) noexcept {
    if (pointer) {
        pairCacheTable().noteFreed(pointer);
        forgetConvex(pointer);
        forgetTrimeshData(pointer);
    }
    if (dFreeFunction* previous = hook().previousFree.load(std::memory_order_acquire))
        previous(pointer, size);
    else
        std::free(pointer);  // ODE's own behaviour without a handler
}

}  // namespace

void ensureFreeHook() {
    Hook& h = hook();
    std::lock_guard lock(h.mutex);
    dFreeFunction* current = dGetFreeHandler();
    if (current == &freeHook) return;
    distrustRegisteredConvexes();
    h.previousFree.store(current, std::memory_order_release);
    dSetFreeHandler(&freeHook);
}

bool freeHookActive() { return dGetFreeHandler() == &freeHook; }

}  // namespace gdc::ode::detail

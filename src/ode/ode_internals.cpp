#include "ode_internals.hpp"

#include <dlfcn.h>

namespace gdc::ode::detail {

bool odeIsInitialized() {
    // Set by dInitODE2's first call (odeou's assertion handler), reset by the matching dCloseODE.
    static void* const hook =
        dlsym(RTLD_DEFAULT, "_ZN5odeou28CAssertionCheckCustomization24g_fnAssertFailureHandlerE");
    if (!hook) return true;
    return *static_cast<void* const volatile*>(hook) != nullptr;
}

const OdeColliders& odeColliders() {
    static const OdeColliders colliders = [] {
        auto find = [](const char* name) { return reinterpret_cast<dColliderFn*>(dlsym(RTLD_DEFAULT, name)); };
        return OdeColliders{find("_Z23dCollideConvexConvexCCDP6dxGeomS0_iP12dContactGeomi"),
                            find("_Z20dCollideConvexBoxCCDP6dxGeomS0_iP12dContactGeomi"),
                            find("_Z19dCollideConvexPlaneP6dxGeomS0_iP12dContactGeomi")};
    }();
    return colliders;
}

}  // namespace gdc::ode::detail

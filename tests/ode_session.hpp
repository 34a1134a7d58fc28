// ODE's process-wide state as an RAII guard, for the tests that drive a real ODE (scenes, viewer).
#pragma once

#include <ode/ode.h>

namespace gdc::testing {

/// dInitODE2 for its lifetime, dCloseODE after. Worlds, geoms and scenes must be destroyed before
/// it (declare it first).
struct OdeSession {
    OdeSession() { dInitODE2(0); }
    ~OdeSession() { dCloseODE(); }
    OdeSession(const OdeSession&) = delete;
    OdeSession& operator=(const OdeSession&) = delete;
};

}  // namespace gdc::testing

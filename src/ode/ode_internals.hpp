// The one place that reaches past ODE 0.16.2's public API: symbols Debian's libode exports but
// does not declare, found once with dlsym. Each lookup degrades gracefully where a build of ODE
// does not export it.
#pragma once

#include <ode/ode.h>

namespace gdc::ode::detail {

/// Whether ODE is initialised (between dInitODE2() and its matching dCloseODE()). ODE 0.16.2 has
/// no public query and asserts inside (without naming the call order) when install() runs
/// before dInitODE2(); Debian's libode exports the hook its initialisation sets, so this reads it.
/// True when the hook is not exported (another build of ODE): then it cannot tell.
bool odeIsInitialized();

/// ODE's own colliders for dConvex geoms gdcontact did not create. ODE 0.16.2 keeps only pointers
/// to a dConvex's arrays and has no getter for them, and its dxConvex layout is private:
/// gdcontact cannot read a convex it did not create (reading ODE's private struct would tie it to
/// one build of ODE). dSetColliderOverride replaced ODE's table entries for those pairs and ODE
/// has no getter for them either, but Debian's libode exports the colliders themselves (C++
/// names, dColliderFn's signature). nullptr where this libode does not export one.
struct OdeColliders {
    dColliderFn* convexConvex;  // libccd MPR (dLIBCCD_CONVEX_CONVEX)
    dColliderFn* convexBox;     // libccd MPR (dLIBCCD_CONVEX_BOX)
    dColliderFn* convexPlane;
};
const OdeColliders& odeColliders();

}  // namespace gdc::ode::detail

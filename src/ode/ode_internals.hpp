// What gdcontact needs of ODE beyond its public API, and what it does where that is out of reach.
// ODE 0.16.x has no public way to (1) ask whether it is initialised, (2) read a dConvex's data
// (it keeps only pointers to the caller's arrays), or (3) call the collider a dSetColliderOverride
// replaced. So (1) and (3) use symbols a shared libode exports but does not declare, looked up
// with dlsym — and degrade, as documented in docs/ode.md ("Plain dCreateConvex geoms"), where a
// build of ODE (static, hidden symbols) does not export them. Nothing here is needed by
// gdcontact's own geoms: box, createConvex and plane pairs never reach ODE's internals.
#pragma once

#include <ode/ode.h>

#include <string>

namespace gdc::ode::detail {

/// Whether ODE is initialised (between dInitODE2() and its matching dCloseODE()). ODE 0.16.x has
/// no public query and asserts inside (without naming the call order) when install() runs before
/// dInitODE2(); a shared libode exports the hook its initialisation sets, so this reads it.
/// True when the hook is not exported (a static ODE): then it cannot tell.
bool odeIsInitialized();
/// Whether odeIsInitialized() can tell (the hook is exported by the ODE linked).
bool odeInitializationKnown();

/// The configuration problem of the ODE linked, "" if none: a library of another precision than
/// the headers gdcontact was compiled with (dCheckConfiguration, public) — two ODEs mixed up.
std::string odeConfigurationProblem();

/// What a pair with a plain dCreateConvex geom (whose data gdcontact cannot read) gets after
/// install(), per pair kind: ODE's own collider when it is reachable, else none.
enum class OdeFallback {
    OdeCollider,  ///< ODE's own collider, identified as the one ODE's table held (same answer)
    OdeGivesNone, ///< ODE's own collider answers no contact for overlapping shapes (a stub: ODE
                  ///< without libccd for convex–box): the pair gets what ODE gives, nothing
    Unreachable,  ///< ODE's collider answers, but this ODE does not export it: no contacts, one message
};
struct OdeCollider {
    OdeFallback fallback = OdeFallback::Unreachable;
    dColliderFn* function = nullptr;  // set for OdeCollider
    bool convexSecond = false;        // ODE's function takes the other geom first (sphere–convex without libccd)
};
struct OdeColliders {
    OdeCollider convexConvex, convexBox, convexPlane, convexCylinder, convexCapsule, convexSphere, convexTrimesh;
    /// The collider for a plain convex against a geom of `otherClass`; nullptr for a pair with none.
    const OdeCollider* against(int otherClass) const;
};
/// ODE's own colliders for convex–convex, convex–box (convex first), convex–plane and convex
/// against a cylinder, a capsule, a sphere and a trimesh (the pairs install() takes over), found once,
/// at the first install() of the process, before it overrides them (ODE's table is then ODE's):
/// each pair's answer through dCollide on two overlapping scratch geoms is compared, contact for
/// contact, with the answer of each exported candidate (libccd's and ODE's own); the one that
/// gives the same is ODE's. Public calls only, apart from the dlsym of the candidates.
/// Call with ODE initialised; before install()'s first dSetColliderOverride.
void captureOdeColliders();
/// What captureOdeColliders found; runs it first where no install() has (collide() used alone:
/// ODE's table is then still ODE's). Requires ODE initialised.
const OdeColliders& odeColliders();
/// One line for messages and tests: "convex-convex: ODE's collider, convex-box: ...".
std::string describeOdeColliders();

}  // namespace gdc::ode::detail

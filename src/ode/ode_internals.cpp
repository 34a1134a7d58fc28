#include "ode_internals.hpp"

#include <dlfcn.h>

#include <cstring>
#include <initializer_list>
#include <mutex>
#include <vector>

namespace gdc::ode::detail {
namespace {

void* initializationHook() {
    // Set by dInitODE2's first call (odeou's assertion handler), reset by the matching dCloseODE.
    static void* const hook =
        dlsym(RTLD_DEFAULT, "_ZN5odeou28CAssertionCheckCustomization24g_fnAssertFailureHandlerE");
    return hook;
}

dColliderFn* exported(const char* name) { return reinterpret_cast<dColliderFn*>(dlsym(RTLD_DEFAULT, name)); }

OdeColliders& found() {
    static OdeColliders colliders;
    return colliders;
}

// Set while this thread probes ODE's table: a table that already sends convex pairs to gdcontact
// (a program that set gdc::ode::collide with dSetColliderOverride itself) comes back here.
thread_local bool probing = false;
thread_local bool reentered = false;

constexpr int kProbeContacts = 8;
struct Answer {
    int count = 0;
    dContactGeom contacts[kProbeContacts];
};

// Both answers zero-filled first (ODE leaves the padding of pos and normal unwritten).
Answer answerOf(dColliderFn* function, dGeomID o1, dGeomID o2) {
    Answer answer;
    std::memset(answer.contacts, 0, sizeof answer.contacts);
    answer.count = function ? function(o1, o2, kProbeContacts, answer.contacts, sizeof(dContactGeom))
                            : dCollide(o1, o2, kProbeContacts, answer.contacts, sizeof(dContactGeom));
    return answer;
}

bool same(const Answer& a, const Answer& b) {
    return a.count == b.count && std::memcmp(a.contacts, b.contacts, sizeof(dContactGeom) * a.count) == 0;
}

// ODE's answer for (o1, o2) through its table, and which candidate gives the same: ODE's table
// holds (convex, X) unreversed for every X here (collision_kernel.cpp's setCollider order).
OdeCollider identify(dGeomID o1, dGeomID o2, std::initializer_list<const char*> candidates) {
    reentered = false;
    const Answer ode = answerOf(nullptr, o1, o2);
    if (reentered) return OdeCollider{OdeFallback::Unreachable, nullptr};  // the table is not ODE's
    if (ode.count == 0) return OdeCollider{OdeFallback::OdeGivesNone, nullptr};
    for (const char* name : candidates)
        if (dColliderFn* function = exported(name); function && same(answerOf(function, o1, o2), ode))
            return OdeCollider{OdeFallback::OdeCollider, function};
    return OdeCollider{OdeFallback::Unreachable, nullptr};
}

const char* describe(const OdeCollider& collider) {
    switch (collider.fallback) {
        case OdeFallback::OdeCollider: return "ODE's own collider";
        case OdeFallback::OdeGivesNone: return "none (ODE's own collider gives none)";
        case OdeFallback::Unreachable: break;
    }
    return "none (ODE's own collider is not exported by this ODE)";
}

}  // namespace

bool odeInitializationKnown() { return initializationHook() != nullptr; }

bool odeIsInitialized() {
    void* const hook = initializationHook();
    if (!hook) return true;
    return *static_cast<void* const volatile*>(hook) != nullptr;
}

std::string odeConfigurationProblem() {
    const bool headersDouble = sizeof(dReal) == sizeof(double);
    const char* wanted = headersDouble ? "ODE_double_precision" : "ODE_single_precision";
    if (dCheckConfiguration(wanted)) return "";
    return std::string("gdcontact was compiled with the headers of a ") + (headersDouble ? "double" : "single") +
           "-precision ODE, but the libode it runs with is not one (dGetConfiguration: \"" + dGetConfiguration() +
           "\"): rebuild gdcontact against the ODE the program links";
}

void captureOdeColliders() {
    static std::once_flag once;
    std::call_once(once, [] {
        probing = true;
        // A cube of half size 0.5 as dCreateConvex takes it (planes, points, polygons).
        static const dReal planes[] = {1, 0, 0, 0.5, -1, 0, 0, 0.5, 0, 1, 0, 0.5,
                                       0, -1, 0, 0.5, 0, 0, 1, 0.5, 0, 0, -1, 0.5};
        static const dReal points[] = {-0.5, -0.5, -0.5, 0.5, -0.5, -0.5, 0.5, 0.5, -0.5, -0.5, 0.5, -0.5,
                                       -0.5, -0.5, 0.5,  0.5, -0.5, 0.5,  0.5, 0.5, 0.5,  -0.5, 0.5, 0.5};
        static const unsigned polygons[] = {4, 1, 2, 6, 5, 4, 0, 4, 7, 3, 4, 3, 7, 6, 2,
                                            4, 0, 1, 5, 4, 4, 4, 5, 6, 7, 4, 0, 3, 2, 1};
        dGeomID a = dCreateConvex(nullptr, planes, 6, points, 8, polygons);
        dGeomID b = dCreateConvex(nullptr, planes, 6, points, 8, polygons);
        dGeomID box = dCreateBox(nullptr, 1, 1, 1);
        dGeomID plane = dCreatePlane(nullptr, 0, 0, 1, 0);
        dMatrix3 tilt;
        dRFromAxisAndAngle(tilt, 1, 2, 3, 0.3);
        dGeomSetPosition(a, 0, 0, 0.3);  // 0.2 below the plane z = 0, overlapping b and box
        for (dGeomID other : {b, box}) {
            dGeomSetPosition(other, 0.1, 0.2, 1.1);
            dGeomSetRotation(other, tilt);
        }
        OdeColliders& colliders = found();
        colliders.convexConvex = identify(a, b, {"_Z23dCollideConvexConvexCCDP6dxGeomS0_iP12dContactGeomi",
                                                 "_Z20dCollideConvexConvexP6dxGeomS0_iP12dContactGeomi"});
        colliders.convexBox = identify(a, box, {"_Z20dCollideConvexBoxCCDP6dxGeomS0_iP12dContactGeomi",
                                                "_Z17dCollideConvexBoxP6dxGeomS0_iP12dContactGeomi"});
        colliders.convexPlane = identify(a, plane, {"_Z19dCollideConvexPlaneP6dxGeomS0_iP12dContactGeomi"});
        // The curved geoms install() takes over, overlapping a as b does.
        dGeomID cylinder = dCreateCylinder(nullptr, 0.4, 1);
        dGeomID capsule = dCreateCapsule(nullptr, 0.3, 0.6);
        dGeomID sphere = dCreateSphere(nullptr, 0.5);
        for (dGeomID other : {cylinder, capsule, sphere}) {
            dGeomSetPosition(other, 0.1, 0.2, 1.0);
            dGeomSetRotation(other, tilt);
        }
        colliders.convexCylinder = identify(a, cylinder, {"_Z25dCollideConvexCylinderCCDP6dxGeomS0_iP12dContactGeomi"});
        colliders.convexCapsule = identify(a, capsule, {"_Z24dCollideConvexCapsuleCCDP6dxGeomS0_iP12dContactGeomi",
                                                         "_Z21dCollideConvexCapsuleP6dxGeomS0_iP12dContactGeomi"});
        colliders.convexSphere = identify(a, sphere, {"_Z23dCollideConvexSphereCCDP6dxGeomS0_iP12dContactGeomi"});
        if (colliders.convexSphere.fallback == OdeFallback::Unreachable) {
            // Without libccd ODE's table holds (sphere, convex): its function takes the sphere first.
            colliders.convexSphere = identify(sphere, a, {"_Z20dCollideSphereConvexP6dxGeomS0_iP12dContactGeomi"});
            colliders.convexSphere.convexSecond = true;
        }
        // A trimesh floor at z = 0 (two triangles, face angles built as ODE's demo_trimesh does).
        // (dGeomTriMeshDataBuildSimple: dReal vertices at a dVector3's stride, either precision.)
        static const dReal floorVertices[] = {-5, -5, 0, 0, 5, -5, 0, 0, 5, 5, 0, 0, -5, 5, 0, 0};
        static const dTriIndex floorIndices[] = {0, 1, 2, 0, 2, 3};
        dTriMeshDataID floorData = dGeomTriMeshDataCreate();
        dGeomTriMeshDataBuildSimple(floorData, floorVertices, 4, floorIndices, 6);
        dGeomTriMeshDataPreprocess2(floorData, 1U << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES, nullptr);
        dGeomID trimesh = dCreateTriMesh(nullptr, floorData, nullptr, nullptr, nullptr);
        colliders.convexTrimesh = identify(a, trimesh, {"_Z21dCollideConvexTrimeshP6dxGeomS0_iP12dContactGeomi"});
        for (dGeomID geom : {a, b, box, plane, cylinder, capsule, sphere, trimesh}) dGeomDestroy(geom);
        dGeomTriMeshDataDestroy(floorData);
        probing = false;
    });
}

const OdeCollider* OdeColliders::against(int otherClass) const {
    switch (otherClass) {
        case dConvexClass: return &convexConvex;
        case dBoxClass: return &convexBox;
        case dPlaneClass: return &convexPlane;
        case dCylinderClass: return &convexCylinder;
        case dCapsuleClass: return &convexCapsule;
        case dSphereClass: return &convexSphere;
        case dTriMeshClass: return &convexTrimesh;
        default: return nullptr;
    }
}

const OdeColliders& odeColliders() {
    if (probing) {
        reentered = true;
        static const OdeColliders none;
        return none;
    }
    captureOdeColliders();  // collide() without install(): ODE's table is still ODE's
    return found();
}

std::string describeOdeColliders() {
    const OdeColliders& colliders = found();
    return std::string("convex-convex: ") + describe(colliders.convexConvex) +
           "; convex-box: " + describe(colliders.convexBox) + "; convex-plane: " + describe(colliders.convexPlane) +
           "; convex-cylinder: " + describe(colliders.convexCylinder) +
           "; convex-capsule: " + describe(colliders.convexCapsule) +
           "; convex-sphere: " + describe(colliders.convexSphere) +
           "; convex-trimesh: " + describe(colliders.convexTrimesh);
}

}  // namespace gdc::ode::detail

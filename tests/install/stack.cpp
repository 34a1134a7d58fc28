// Built by scripts/install-check against an installed gdcontact, through find_package only
// (tests/install/CMakeLists.txt). The same stack as stack.c with the C++ API
// (gdc::ode::install, gdc::ode::createConvex), and the core's API beside it (gdc::collide).
#include <gdcontact/gdcontact.hpp>
#include <gdcontact/ode.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

constexpr int kCubes = 4;
constexpr int kSteps = 300;
constexpr double kEdge = 0.5;
constexpr double kStep = 0.01;
constexpr double kOverlap = 1e-4;  // each cube starts resting 0.1 mm into the one below

struct World {
    dWorldID world;
    dJointGroupID contacts;
    int mostContactsPerCubePair = 0;
};

void nearCallback(void* data, dGeomID a, dGeomID b) {
    auto& w = *static_cast<World*>(data);
    dContact contact[4] = {};
    const int n = dCollide(a, b, 4, &contact[0].geom, sizeof(dContact));
    if (dGeomGetClass(a) == dConvexClass && dGeomGetClass(b) == dConvexClass && n > w.mostContactsPerCubePair)
        w.mostContactsPerCubePair = n;
    for (int i = 0; i < n; ++i) {
        contact[i].surface.mode = dContactApprox1;  // friction scaled by the normal force
        contact[i].surface.mu = 0.8;
        dJointAttach(dJointCreateContact(w.world, w.contacts, &contact[i]), dGeomGetBody(a), dGeomGetBody(b));
    }
}

}  // namespace

int main() {
    bool failed = false;
    // The version the headers say is the version CMake found.
    if (std::string(GDCONTACT_VERSION_STRING) != GDCONTACT_EXPECTED_VERSION) {
        std::fprintf(stderr, "version.hpp says %s, find_package found %s\n", GDCONTACT_VERSION_STRING,
                     GDCONTACT_EXPECTED_VERSION);
        failed = true;
    }

    // The core alone: two boxes, one resting on the other, touch along a face (four corners).
    const gdc::Polytope box = gdc::Polytope::box(gdc::Vec3::Constant(0.5 * kEdge));
    gdc::Pose upper;
    upper.position = gdc::Vec3(0, 0, kEdge - 0.001);
    const gdc::Manifold manifold = gdc::collide(box, gdc::Pose{}, box, upper);
    if (manifold.pointCount != 4) {
        std::fprintf(stderr, "gdc::collide: %d points for a face contact, not 4\n", manifold.pointCount);
        failed = true;
    }
    try {
        gdc::Polytope::fromPoints({gdc::Vec3(0, 0, 0), gdc::Vec3(1, 0, 0), gdc::Vec3(0, 1, 0)});
        std::fprintf(stderr, "three points made a polytope\n");
        failed = true;
    } catch (const gdc::InvalidInput&) {  // thrown inside the library, caught here
    }

    std::vector<dReal> points;
    for (int i = 0; i < 8; ++i)
        for (int axis = 0; axis < 3; ++axis) points.push_back(((i >> axis) & 1 ? 0.5 : -0.5) * kEdge);

    dInitODE2(0);
    gdc::ode::install();
    World w{dWorldCreate(), dJointGroupCreate(0)};
    dWorldSetGravity(w.world, 0, 0, -9.81);
    dWorldSetCFM(w.world, 1e-5);
    dSpaceID space = dSimpleSpaceCreate(nullptr);
    dCreatePlane(space, 0, 0, 1, 0);
    dBodyID bodies[kCubes];
    gdc::Vec3 start[kCubes];
    for (int i = 0; i < kCubes; ++i) {
        dGeomID cube = gdc::ode::createConvex(space, points.data(), 8);
        bodies[i] = dBodyCreate(w.world);
        dMass mass;
        dMassSetBoxTotal(&mass, 1.0, kEdge, kEdge, kEdge);
        dBodySetMass(bodies[i], &mass);
        dGeomSetBody(cube, bodies[i]);
        start[i] = gdc::Vec3(0, 0, 0.5 * kEdge + i * (kEdge - kOverlap));
        dBodySetPosition(bodies[i], start[i].x(), start[i].y(), start[i].z());
    }
    for (int step = 0; step < kSteps; ++step) {
        dSpaceCollide(space, &w, &nearCallback);
        dWorldStep(w.world, kStep);
        dJointGroupEmpty(w.contacts);
    }
    double worstDrift = 0;
    for (int i = 0; i < kCubes; ++i) {
        const dReal* p = dBodyGetPosition(bodies[i]);
        const double drift = (gdc::Vec3(p[0], p[1], p[2]) - start[i]).norm();
        if (!(drift < 1e-3)) failed = true;
        if (!(drift <= worstDrift)) worstDrift = drift;
    }
    std::printf("C++ stack of %d convex cubes after %.1f s: largest drift %.3g mm, %d contacts per cube pair\n",
                kCubes, kSteps * kStep, worstDrift * 1e3, w.mostContactsPerCubePair);
    if (w.mostContactsPerCubePair < 4) {
        std::fprintf(stderr, "a cube resting on a cube got %d contacts: gdcontact is not the collider\n",
                     w.mostContactsPerCubePair);
        failed = true;
    }
    dSpaceDestroy(space);
    dJointGroupDestroy(w.contacts);
    dWorldDestroy(w.world);
    dCloseODE();
    if (failed) std::fprintf(stderr, "FAIL\n");
    return failed ? 1 : 0;
}

// ODE's demo_boxstack, headless, migrated as docs/ode.md says: the header, install() after
// dInitODE2, gdc::ode::createConvex with dCreateConvex's arguments. The keys a user would press
// are scripted: 'b' drops a box, 'c' ODE's demo convex, 'v' an icosahedron whose data was printed
// with 6 decimals and whose planes point inwards, 'p' a hexagonal prism with its planes listed in
// another order than its polygons.
#include <ode/ode.h>
#include <gdcontact/ode.hpp>  // 1. the header

#include "demo_support.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

constexpr int kMaxObjects = 40;
constexpr int kMaxContacts = 8;

dWorldID world;
dSpaceID space;
dJointGroupID contactgroup;
dBodyID bodies[kMaxObjects];
int objectCount = 0;
dropin::Audit audit;
dropin::ConvexData cube, icosahedron, prism;

void nearCallback(void*, dGeomID o1, dGeomID o2) {
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
    dContact contact[kMaxContacts];
    for (dContact& c : contact) {
        c.surface.mode = dContactBounce | dContactSoftCFM;
        c.surface.mu = dInfinity;
        c.surface.mu2 = 0;
        c.surface.bounce = 0.1;
        c.surface.bounce_vel = 0.1;
        c.surface.soft_cfm = 0.01;
    }
    const int numc = dCollide(o1, o2, kMaxContacts, &contact[0].geom, sizeof(dContact));
    for (int i = 0; i < numc; ++i) {
        audit.check(contact[i].geom);
        dJointID joint = dJointCreateContact(world, contactgroup, contact + i);
        dJointAttach(joint, b1, b2);
    }
}

void command(int key) {
    if (objectCount == kMaxObjects) return;
    dBodyID body = dBodyCreate(world);
    const double x = 0.6 * (std::rand() / double(RAND_MAX) - 0.5), y = 0.6 * (std::rand() / double(RAND_MAX) - 0.5);
    dBodySetPosition(body, x, y, 1.0 + 0.35 * objectCount);
    dMatrix3 R;
    dRFromAxisAndAngle(R, std::rand() / double(RAND_MAX), std::rand() / double(RAND_MAX),
                       std::rand() / double(RAND_MAX), std::rand() / double(RAND_MAX) * 6.28);
    dBodySetRotation(body, R);
    dMass m;
    dGeomID geom = nullptr;
    if (key == 'b') {
        geom = dCreateBox(space, 0.4, 0.3, 0.2);
        dMassSetBox(&m, 5, 0.4, 0.3, 0.2);
    } else {
        const dropin::ConvexData& data = key == 'c' ? cube : key == 'v' ? icosahedron : prism;
        // 3. the same arguments as dCreateConvex
        geom = gdc::ode::createConvex(space, data.planes.data(), data.planeCount(), data.points.data(),
                                      data.pointCount(), data.polygons.data());
        dMassSetBox(&m, 5, 0.4, 0.4, 0.4);
    }
    dBodySetMass(body, &m);
    dGeomSetBody(geom, body);
    bodies[objectCount++] = body;
}

}  // namespace

int runBoxStack() {
    std::srand(3);
    cube = dropin::demoCube();
    icosahedron = dropin::roundedIcosahedron(0.22, true);
    prism = dropin::roundedPrismShuffled(0.2, 0.12);
    dInitODE2(0);
    gdc::ode::install();  // 2. after dInitODE2
    world = dWorldCreate();
    space = dHashSpaceCreate(0);
    contactgroup = dJointGroupCreate(0);
    dWorldSetGravity(world, 0, 0, -0.5);
    dWorldSetCFM(world, 1e-5);
    dWorldSetAutoDisableFlag(world, 1);
    dWorldSetContactMaxCorrectingVel(world, 0.1);
    dWorldSetContactSurfaceLayer(world, 0.001);
    dCreatePlane(space, 0, 0, 1, 0);

    const char* script = "bcvpbbcvpcbvpbcvbpcbbvcpbcvb";
    for (int step = 0; step < 2000; ++step) {
        if (step % 25 == 0 && step / 25 < static_cast<int>(std::strlen(script))) command(script[step / 25]);
        dSpaceCollide(space, nullptr, &nearCallback);
        dWorldQuickStep(world, 0.05);
        dJointGroupEmpty(contactgroup);
        ++audit.steps;
    }
    int fallen = 0;
    for (int i = 0; i < objectCount; ++i) {
        const dReal* p = dBodyGetPosition(bodies[i]);
        if (!(p[2] > -0.05) || !std::isfinite(p[0]) || !std::isfinite(p[1])) ++fallen;
    }
    std::fprintf(stderr, "dropin: objects %d contacts %ld invalid %ld fallen %d steps %ld %s\n", objectCount,
                 audit.contacts, audit.invalid, fallen, audit.steps, audit.firstInvalid.c_str());
    dJointGroupDestroy(contactgroup);
    dSpaceDestroy(space);
    dWorldDestroy(world);
    dCloseODE();
    return 0;
}

// An ODE program that only adds install(): its convexes stay plain dCreateConvex geoms (so their
// pairs go to ODE's own convex collider, with one message), its boxes and plane get gdcontact.
#include <ode/ode.h>
#include <gdcontact/ode.hpp>

#include "demo_support.hpp"

#include <cstdio>
#include <vector>

namespace {

constexpr int kMaxContacts = 4;
dWorldID world;
dJointGroupID contactgroup;
dropin::Audit audit;

void nearCallback(void*, dGeomID o1, dGeomID o2) {
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    dContact contact[kMaxContacts];
    for (dContact& c : contact) {
        c.surface.mode = dContactApprox1;
        c.surface.mu = 0.5;
    }
    const int numc = dCollide(o1, o2, kMaxContacts, &contact[0].geom, sizeof(dContact));
    for (int i = 0; i < numc; ++i) {
        audit.check(contact[i].geom);
        dJointAttach(dJointCreateContact(world, contactgroup, contact + i), b1, b2);
    }
}

}  // namespace

int runInstallOnly() {
    const dropin::ConvexData cube = dropin::demoCube();  // ODE keeps pointers to it: it outlives the geoms
    dInitODE2(0);
    gdc::ode::install();  // the only line added to the ODE program
    world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(0);
    contactgroup = dJointGroupCreate(0);
    dWorldSetGravity(world, 0, 0, -9.81);
    dWorldSetCFM(world, 1e-5);
    dCreatePlane(space, 0, 0, 1, 0);
    std::vector<dBodyID> bodies;
    for (int i = 0; i < 12; ++i) {
        dBodyID body = dBodyCreate(world);
        dBodySetPosition(body, 0.3 * (i % 3) - 0.3, 0.05 * (i % 2), 0.3 + 0.55 * (i / 3));
        dMass m;
        dMassSetBox(&m, 500, 0.5, 0.5, 0.5);
        dBodySetMass(body, &m);
        dGeomID geom = i % 2 ? dCreateBox(space, 0.5, 0.5, 0.5)
                             : dCreateConvex(space, cube.planes.data(), cube.planeCount(), cube.points.data(),
                                             cube.pointCount(), cube.polygons.data());
        dGeomSetBody(geom, body);
        bodies.push_back(body);
    }
    for (int step = 0; step < 500; ++step) {
        dSpaceCollide(space, nullptr, &nearCallback);
        dWorldQuickStep(world, 0.01);
        dJointGroupEmpty(contactgroup);
        ++audit.steps;
    }
    int fallen = 0;
    for (dBodyID body : bodies) {
        const dReal* p = dBodyGetPosition(body);
        if (!(p[2] > 0.1)) ++fallen;
    }
    std::fprintf(stderr, "dropin: objects %zu contacts %ld invalid %ld fallen %d steps %ld %s\n", bodies.size(),
                 audit.contacts, audit.invalid, fallen, audit.steps, audit.firstInvalid.c_str());
    dJointGroupDestroy(contactgroup);
    dSpaceDestroy(space);
    dWorldDestroy(world);
    dCloseODE();
    return 0;
}

// A pile of convexes from rounded data, in the style of ODE's demo_convex: icosahedra printed with
// 6 decimals (planes pointing inwards in every other one), prisms with their planes in another
// order than their polygons, ODE's demo cube — 30 objects dropped into a pile under dWorldStep.
#include <ode/ode.h>
#include <gdcontact/ode.hpp>

#include "demo_support.hpp"

#include <cstdio>
#include <cstdlib>

namespace {

constexpr int kObjects = 30;
constexpr int kMaxContacts = 8;

dWorldID world;
dSpaceID space;
dJointGroupID contactgroup;
dropin::Audit audit;

void nearCallback(void*, dGeomID o1, dGeomID o2) {
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    dContact contact[kMaxContacts];
    for (dContact& c : contact) {
        c.surface.mode = dContactApprox1;
        c.surface.mu = 0.6;
    }
    const int numc = dCollide(o1, o2, kMaxContacts, &contact[0].geom, sizeof(dContact));
    for (int i = 0; i < numc; ++i) {
        audit.check(contact[i].geom);
        dJointAttach(dJointCreateContact(world, contactgroup, contact + i), b1, b2);
    }
}

}  // namespace

int runConvexPile() {
    std::srand(5);
    const dropin::ConvexData shapes[] = {dropin::roundedIcosahedron(0.2, false), dropin::roundedIcosahedron(0.25, true),
                                         dropin::roundedPrismShuffled(0.18, 0.15), dropin::demoCube()};
    dInitODE2(0);
    gdc::ode::install();
    world = dWorldCreate();
    space = dSimpleSpaceCreate(0);
    contactgroup = dJointGroupCreate(0);
    dWorldSetGravity(world, 0, 0, -9.81);
    dWorldSetERP(world, 0.2);
    dWorldSetCFM(world, 1e-5);
    dCreatePlane(space, 0, 0, 1, 0);
    // Four walls (boxes) keep the pile together.
    for (int side = 0; side < 4; ++side) {
        dGeomID wall = dCreateBox(space, side < 2 ? 0.2 : 2.4, side < 2 ? 2.4 : 0.2, 6.0);
        dGeomSetPosition(wall, side == 0 ? -1.1 : side == 1 ? 1.1 : 0, side == 2 ? -1.1 : side == 3 ? 1.1 : 0, 3.0);
    }
    dBodyID bodies[kObjects];
    for (int i = 0; i < kObjects; ++i) {
        const dropin::ConvexData& data = shapes[i % 4];
        dBodyID body = dBodyCreate(world);
        dBodySetPosition(body, 0.25 * (i % 3) - 0.25, 0.25 * ((i / 3) % 3) - 0.25, 0.4 + 0.45 * (i / 3));
        dMatrix3 R;
        dRFromAxisAndAngle(R, 1, std::rand() / double(RAND_MAX), 0.3, std::rand() / double(RAND_MAX) * 6.28);
        dBodySetRotation(body, R);
        dMass m;
        dMassSetSphere(&m, 500, 0.2);
        dBodySetMass(body, &m);
        dGeomID geom = gdc::ode::createConvex(space, data.planes.data(), data.planeCount(), data.points.data(),
                                              data.pointCount(), data.polygons.data());
        dGeomSetBody(geom, body);
        bodies[i] = body;
    }
    for (int step = 0; step < 600; ++step) {
        dSpaceCollide(space, nullptr, &nearCallback);
        dWorldStep(world, 0.01);
        dJointGroupEmpty(contactgroup);
        ++audit.steps;
    }
    int fallen = 0;
    for (dBodyID body : bodies) {
        const dReal* p = dBodyGetPosition(body);
        if (!(p[2] > 0.05) || !(std::abs(p[0]) < 1.0) || !(std::abs(p[1]) < 1.0)) ++fallen;
    }
    std::fprintf(stderr, "dropin: objects %d contacts %ld invalid %ld fallen %d steps %ld %s\n", kObjects,
                 audit.contacts, audit.invalid, fallen, audit.steps, audit.firstInvalid.c_str());
    dJointGroupDestroy(contactgroup);
    dSpaceDestroy(space);
    dWorldDestroy(world);
    dCloseODE();
    return 0;
}

// A trimesh and a heightfield (ODE's demo_trimesh / demo_heightfield style) with convex objects
// and boxes dropped on them: convex–trimesh and convex–heightfield stay with ODE's colliders,
// convex–convex, convex–box and the pairs with the plane around them are gdcontact's.
#include <ode/ode.h>
#include <gdcontact/ode.hpp>

#include "demo_support.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

constexpr int kMaxContacts = 8;
dWorldID world;
dJointGroupID contactgroup;
dropin::Audit audit;

void nearCallback(void*, dGeomID o1, dGeomID o2) {
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (!b1 && !b2) return;
    dContact contact[kMaxContacts];
    for (dContact& c : contact) {
        c.surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
        c.surface.mu = 0.8;
        c.surface.soft_erp = 0.5;
        c.surface.soft_cfm = 1e-4;
    }
    const int numc = dCollide(o1, o2, kMaxContacts, &contact[0].geom, sizeof(dContact));
    for (int i = 0; i < numc; ++i) {
        audit.check(contact[i].geom);
        dJointAttach(dJointCreateContact(world, contactgroup, contact + i), b1, b2);
    }
}

dReal heightAt(void*, int x, int z) { return 0.15 * std::sin(0.7 * x) * std::cos(0.5 * z); }

}  // namespace

int runTerrain() {
    const dropin::ConvexData cube = dropin::demoCube(), icosahedron = dropin::roundedIcosahedron(0.2, true);
    dInitODE2(0);
    gdc::ode::install();
    world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(0);
    contactgroup = dJointGroupCreate(0);
    dWorldSetGravity(world, 0, 0, -9.81);
    dWorldSetCFM(world, 1e-5);
    dWorldSetAngularDamping(world, 0.02);  // icosahedra would roll off the terrain
    dCreatePlane(space, 0, 0, 1, -1.0);  // a floor below both, as a backstop

    // A trimesh: a 24 x 24 grid of 0.25 m squares with a gentle bump, centred at x = -3.5.
    std::vector<dReal> vertices;
    std::vector<dTriIndex> indices;
    const int n = 24;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = -6.5 + 0.25 * i, y = -3.0 + 0.25 * j;
            vertices.insert(vertices.end(), {x, y, 0.1 * std::exp(-((x + 3.5) * (x + 3.5) + y * y))});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const dTriIndex a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            indices.insert(indices.end(), {a, b, d, a, d, c});
        }
    dTriMeshDataID mesh = dGeomTriMeshDataCreate();
    dGeomTriMeshDataBuildDouble(mesh, vertices.data(), 3 * sizeof(dReal), static_cast<int>(vertices.size() / 3),
                                indices.data(), static_cast<int>(indices.size()), 3 * sizeof(dTriIndex));
    // ODE's convex–trimesh collider needs the face angles (as ODE's demo_trimesh does).
    dGeomTriMeshDataPreprocess2(mesh, 1U << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES, nullptr);
    dCreateTriMesh(space, mesh, nullptr, nullptr, nullptr);

    // A heightfield (ODE's is y-up: turned so that its up is z), 6 m x 6 m centred at x = +3.5.
    dHeightfieldDataID field = dGeomHeightfieldDataCreate();
    dGeomHeightfieldDataBuildCallback(field, nullptr, &heightAt, 6.0, 6.0, 25, 25, 1.0, 0.0, 0.2, 0);
    dGeomHeightfieldDataSetBounds(field, -1.0, 1.0);
    dGeomID heightfield = dCreateHeightfield(space, field, 1);
    dMatrix3 R;
    dRFromAxisAndAngle(R, 1, 0, 0, M_PI / 2);
    dGeomSetRotation(heightfield, R);
    dGeomSetPosition(heightfield, 3.5, 0, 0);

    std::vector<dBodyID> bodies;
    for (int i = 0; i < 24; ++i) {
        dBodyID body = dBodyCreate(world);
        const double x = (i % 2 ? 3.5 : -3.5) + 0.6 * ((i / 2) % 3) - 0.6, y = 0.6 * ((i / 6) % 2) - 0.3;
        dBodySetPosition(body, x, y, 0.6 + 0.8 * (i / 12));  // apart: no initial overlap
        dRFromAxisAndAngle(R, 0.3, 1, 0.2, 0.4 * i);
        dBodySetRotation(body, R);
        dMass m;
        dMassSetBox(&m, 300, 0.4, 0.4, 0.4);
        dBodySetMass(body, &m);
        dGeomID geom;
        if (i % 3 == 2) {
            geom = dCreateBox(space, 0.4, 0.3, 0.3);
        } else {
            const dropin::ConvexData& data = i % 3 ? icosahedron : cube;
            geom = gdc::ode::createConvex(space, data.planes.data(), data.planeCount(), data.points.data(),
                                          data.pointCount(), data.polygons.data());
        }
        dGeomSetBody(geom, body);
        bodies.push_back(body);
    }
    for (int step = 0; step < 600; ++step) {
        dSpaceCollide(space, nullptr, &nearCallback);
        dWorldQuickStep(world, 0.01);
        dJointGroupEmpty(contactgroup);
        ++audit.steps;
    }
    int fallen = 0;
    for (dBodyID body : bodies) {
        const dReal* p = dBodyGetPosition(body);
        if (!(p[2] > -0.5)) ++fallen;  // through the trimesh or the heightfield onto the floor
    }
    std::fprintf(stderr, "dropin: objects %zu contacts %ld invalid %ld fallen %d steps %ld %s\n", bodies.size(),
                 audit.contacts, audit.invalid, fallen, audit.steps, audit.firstInvalid.c_str());
    dJointGroupDestroy(contactgroup);
    dSpaceDestroy(space);
    dGeomTriMeshDataDestroy(mesh);
    dGeomHeightfieldDataDestroy(field);
    dWorldDestroy(world);
    dCloseODE();
    return 0;
}

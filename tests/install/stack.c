/* Built by scripts/install-check against an installed gdcontact, through pkg-config only:
 *   cc -std=c99 stack.c $(pkg-config --cflags --libs gdcontact)          (shared library)
 *   cc -std=c99 stack.c $(pkg-config --static --cflags --libs gdcontact) (static library)
 * A stack of four convex cubes (gdcCreateConvexFromPoints) on a plane under dWorldStep: after
 * 3 s every cube must stand where it was put (drift below 1 mm), and a cube–cube pair must get a
 * face's four contacts (ODE's own convex collider gives one): gdcontact did the collisions. */
#include <gdcontact/ode.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

enum { kCubes = 4, kSteps = 300 };
static const double kEdge = 0.5, kStep = 0.01, kOverlap = 1e-4;

typedef struct World {
    dWorldID world;
    dJointGroupID contacts;
    int mostContactsPerCubePair;
} World;

static void nearCallback(void* data, dGeomID a, dGeomID b) {
    World* w = (World*)data;
    dContact contact[4];
    int i, n;
    memset(contact, 0, sizeof contact);
    n = dCollide(a, b, 4, &contact[0].geom, sizeof(dContact));
    if (dGeomGetClass(a) == dConvexClass && dGeomGetClass(b) == dConvexClass && n > w->mostContactsPerCubePair)
        w->mostContactsPerCubePair = n;
    for (i = 0; i < n; ++i) {
        dJointID joint;
        contact[i].surface.mode = dContactApprox1; /* friction scaled by the normal force */
        contact[i].surface.mu = 0.8;
        joint = dJointCreateContact(w->world, w->contacts, &contact[i]);
        dJointAttach(joint, dGeomGetBody(a), dGeomGetBody(b));
    }
}

int main(void) {
    dReal points[8 * 3];
    dBodyID bodies[kCubes];
    double start[kCubes][3];
    World w;
    dSpaceID space;
    int i, step, failed = 0;
    double worstDrift = 0.0;

    for (i = 0; i < 8; ++i) {
        points[3 * i + 0] = (i & 1 ? 0.5 : -0.5) * kEdge;
        points[3 * i + 1] = (i & 2 ? 0.5 : -0.5) * kEdge;
        points[3 * i + 2] = (i & 4 ? 0.5 : -0.5) * kEdge;
    }
    dInitODE2(0);
    if (gdcInstall(NULL) != GDC_OK) {
        fprintf(stderr, "gdcInstall failed: %s\n", gdcLastError());
        return 1;
    }
    w.world = dWorldCreate();
    w.contacts = dJointGroupCreate(0);
    w.mostContactsPerCubePair = 0;
    dWorldSetGravity(w.world, 0, 0, -9.81);
    dWorldSetCFM(w.world, 1e-5);
    space = dSimpleSpaceCreate(0);
    dCreatePlane(space, 0, 0, 1, 0);
    for (i = 0; i < kCubes; ++i) {
        dMass mass;
        dGeomID cube = gdcCreateConvexFromPoints(space, points, 8);
        if (!cube) {
            fprintf(stderr, "gdcCreateConvexFromPoints failed: %s\n", gdcLastError());
            return 1;
        }
        bodies[i] = dBodyCreate(w.world);
        dMassSetBoxTotal(&mass, 1.0, kEdge, kEdge, kEdge);
        dBodySetMass(bodies[i], &mass);
        dGeomSetBody(cube, bodies[i]);
        start[i][0] = 0.0;
        start[i][1] = 0.0;
        start[i][2] = 0.5 * kEdge + i * (kEdge - kOverlap); /* resting, 0.1 mm into the one below */
        dBodySetPosition(bodies[i], start[i][0], start[i][1], start[i][2]);
    }
    for (step = 0; step < kSteps; ++step) {
        dSpaceCollide(space, &w, &nearCallback);
        dWorldStep(w.world, kStep);
        dJointGroupEmpty(w.contacts);
    }
    for (i = 0; i < kCubes; ++i) {
        const dReal* p = dBodyGetPosition(bodies[i]);
        const double drift = sqrt((p[0] - start[i][0]) * (p[0] - start[i][0]) +
                                  (p[1] - start[i][1]) * (p[1] - start[i][1]) +
                                  (p[2] - start[i][2]) * (p[2] - start[i][2]));
        if (!(drift < 1e-3)) failed = 1; /* also catches NaN */
        if (drift > worstDrift || drift != drift) worstDrift = drift;
    }
    printf("C stack of %d convex cubes after %.1f s: largest drift %.3g mm, %d contacts per cube pair\n",
           kCubes, kSteps * kStep, worstDrift * 1e3, w.mostContactsPerCubePair);
    if (w.mostContactsPerCubePair < 4) {
        fprintf(stderr, "a cube resting on a cube got %d contacts: gdcontact is not the collider\n",
                w.mostContactsPerCubePair);
        failed = 1;
    }
    dSpaceDestroy(space);
    dJointGroupDestroy(w.contacts);
    dWorldDestroy(w.world);
    dCloseODE();
    if (failed) fprintf(stderr, "FAIL: the stack did not stand\n");
    return failed;
}

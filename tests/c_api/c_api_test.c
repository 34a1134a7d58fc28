/* The C API from C99: every function of <gdcontact/ode.h>, its errors and ODE's contact convention.
 * Exits non-zero naming each failed check. */
#include <gdcontact/ode.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* 1e-9, or float's rounding where ODE's dReal is float (64 ulps: tests/ode_precision.hpp's rule). */
#define TOLERANCE (sizeof(dReal) == sizeof(double) ? 1e-9 : 64.0 * FLT_EPSILON)

static int failures = 0;

#define CHECK(condition)                                                          \
    do {                                                                          \
        if (!(condition)) {                                                       \
            fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #condition); \
            ++failures;                                                           \
        }                                                                         \
    } while (0)

/* A unit cube (half extent 0.5) in dCreateConvex's layout; faces counter-clockwise from outside. */
static const dReal cubePoints[8 * 3] = {
    -0.5, -0.5, -0.5, 0.5, -0.5, -0.5, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5,
    -0.5, -0.5, 0.5,  0.5, -0.5, 0.5,  -0.5, 0.5, 0.5,  0.5, 0.5, 0.5};
static const dReal cubePlanes[6 * 4] = {1, 0, 0, 0.5, -1, 0, 0, 0.5, 0, 1, 0, 0.5,
                                        0, -1, 0, 0.5, 0, 0, 1, 0.5, 0, 0, -1, 0.5};
static const unsigned cubePolygons[6 * 5] = {4, 1, 3, 7, 5, 4, 0, 4, 6, 2, 4, 2, 6, 7, 3,
                                             4, 0, 1, 5, 4, 4, 4, 5, 7, 6, 4, 0, 2, 3, 1};

/* gdcInstall with one field changed must fail naming that field (so each C field reaches the
 * gdc::Settings field of the same name). */
static void checkRejected(gdcSettings settings, const char* field) {
    const int code = gdcInstall(&settings);
    CHECK(code == GDC_ERROR_INVALID_ARGUMENT);
    if (strstr(gdcLastError(), field) == NULL) {
        fprintf(stderr, "gdcInstall error for %s does not name it: \"%s\"\n", field, gdcLastError());
        ++failures;
    }
}

static void checkSettings(void) {
    gdcSettings defaults;
    gdcSettings bad;
    memset(&defaults, 0xff, sizeof defaults);
    gdcDefaultSettings(&defaults);
    /* 8 against a single-precision ODE (gdc::ode::defaultSettings) */
    CHECK(defaults.maxContacts == (sizeof(dReal) == sizeof(double) ? 6 : 8));
    CHECK(defaults.contactOrder == GDC_ORDER_DEEPEST_FIRST_WHEN_LOADED);
    CHECK(defaults.loadedDepthFraction == 0.01);
    CHECK(defaults.reductionHysteresis > 0.0 && defaults.reductionHysteresis <= 0.1);
    CHECK(defaults.maxRayCastIterations == 64);
    CHECK(defaults.spanContactRegion == 0);
    CHECK(defaults.normalMethod == GDC_NORMAL_GROWTH_DISTANCE);
    CHECK(defaults.margin == 0.0);
    CHECK(defaults.angularTolerance > 0.0 && defaults.angularTolerance < 0.1);
    gdcDefaultSettings(NULL); /* no crash */

    CHECK(gdcInstall(NULL) == GDC_OK);
    CHECK(strcmp(gdcLastError(), "") == 0);
    CHECK(gdcInstall(&defaults) == GDC_OK);

    bad = defaults; bad.rayCastTolerance = -1.0;        checkRejected(bad, "rayCastTolerance");
    bad = defaults; bad.maxRayCastIterations = 0;       checkRejected(bad, "maxRayCastIterations");
    bad = defaults; bad.angularTolerance = NAN;         checkRejected(bad, "angularTolerance");
    bad = defaults; bad.margin = -0.1;                  checkRejected(bad, "margin");
    bad = defaults; bad.maxContacts = 17;               checkRejected(bad, "maxContacts");
    bad = defaults; bad.manifoldReuseDistance = -1e-3;  checkRejected(bad, "manifoldReuseDistance");
    CHECK(defaults.manifoldReuseDistance == 0.0);
    bad = defaults; bad.bruteForceSupportLimit = -1;    checkRejected(bad, "bruteForceSupportLimit");
    bad = defaults; bad.coplanarTolerance = -1.0;       checkRejected(bad, "coplanarTolerance");
    bad = defaults; bad.normalMethod = 2;               checkRejected(bad, "normalMethod");
    bad = defaults; bad.contactOrder = 3;               checkRejected(bad, "contactOrder");
    bad = defaults; bad.contactOrder = GDC_ORDER_DEEPEST_FIRST_WHEN_LOADED;
    CHECK(gdcInstall(&bad) == GDC_OK);
    bad = defaults; bad.loadedDepthFraction = -1e-3;    checkRejected(bad, "loadedDepthFraction");
    bad = defaults; bad.loadedDepthFraction = NAN;      checkRejected(bad, "loadedDepthFraction");
    bad = defaults; bad.contactOrder = -1;              checkRejected(bad, "contactOrder");
    bad = defaults; bad.reductionHysteresis = 0.2;      checkRejected(bad, "reductionHysteresis");
    bad = defaults; bad.reductionHysteresis = NAN;      checkRejected(bad, "reductionHysteresis");
    bad = defaults; bad.maxBodyPairContacts = 17;       checkRejected(bad, "maxBodyPairContacts");
    bad = defaults; bad.bodyPairNormalTolerance = 0.6;  checkRejected(bad, "bodyPairNormalTolerance");
    CHECK(defaults.maxBodyPairContacts == 4);
    /* success clears the message */
    CHECK(gdcInstall(&defaults) == GDC_OK);
    CHECK(strcmp(gdcLastError(), "") == 0);
}

static void checkCreateErrors(dSpaceID space) {
    const dReal threePoints[3 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const dReal flat[4 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    dReal nanCube[8 * 3];
    memcpy(nanCube, cubePoints, sizeof nanCube);
    nanCube[4] = NAN;

    CHECK(gdcCreateConvexFromPoints(space, threePoints, 3) == 0);
    CHECK(strlen(gdcLastError()) > 0);
    CHECK(gdcCreateConvexFromPoints(space, flat, 4) == 0);
    CHECK(strlen(gdcLastError()) > 0);
    CHECK(gdcCreateConvexFromPoints(space, nanCube, 8) == 0);
    CHECK(strstr(gdcLastError(), "finite") != NULL);
    CHECK(gdcCreateConvexFromPoints(space, NULL, 8) == 0);
    CHECK(strstr(gdcLastError(), "NULL") != NULL);
    CHECK(gdcCreateConvex(space, cubePlanes, 6, cubePoints, 8, NULL) == 0);
    CHECK(strstr(gdcLastError(), "polygons") != NULL);
    CHECK(gdcCreateConvex(space, NULL, 6, cubePoints, 8, cubePolygons) == 0);
    CHECK(strstr(gdcLastError(), "planes") != NULL);
    CHECK(dSpaceGetNumGeoms(space) == 0); /* nothing half-made was left in the space */
}

/* Two unit cubes, the upper one sinking 0.01 into the lower: a face–face contact, four corners. */
static void checkContacts(dGeomID lower, dGeomID upper, int viaDCollide) {
    dContactGeom contacts[8];
    int n, i;
    dGeomSetPosition(lower, 0, 0, 0);
    dGeomSetPosition(upper, 0, 0, 0.99);
    n = viaDCollide ? dCollide(lower, upper, 8, contacts, sizeof(dContactGeom))
                    : gdcCollide(lower, upper, 8, contacts, sizeof(dContactGeom));
    CHECK(n == 4);
    for (i = 0; i < n && i < 8; ++i) {
        CHECK(fabs(contacts[i].normal[2] + 1.0) < TOLERANCE); /* from o2 (upper) into o1 (lower) */
        CHECK(fabs(contacts[i].depth - 0.01) < TOLERANCE);
        CHECK(fabs(fabs(contacts[i].pos[0]) - 0.5) < TOLERANCE && fabs(fabs(contacts[i].pos[1]) - 0.5) < TOLERANCE);
        CHECK(contacts[i].g1 == lower && contacts[i].g2 == upper);
        CHECK(contacts[i].side1 == -1 && contacts[i].side2 == -1);
    }
    /* at most flags & 0xffff contacts */
    n = viaDCollide ? dCollide(lower, upper, 1, contacts, sizeof(dContactGeom))
                    : gdcCollide(lower, upper, 1, contacts, sizeof(dContactGeom));
    CHECK(n == 1);
    /* apart: none */
    dGeomSetPosition(upper, 0, 0, 1.5);
    n = viaDCollide ? dCollide(lower, upper, 8, contacts, sizeof(dContactGeom))
                    : gdcCollide(lower, upper, 8, contacts, sizeof(dContactGeom));
    CHECK(n == 0);
}

/* gdcSpaceCollide: the lower and upper cubes of checkContacts' pose as its only touching pair. */
struct SpaceCollideRecord {
    int pairs;
    int contacts;
    int validNormals;
};

static void recordPair(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
    struct SpaceCollideRecord* record = (struct SpaceCollideRecord*)data;
    int i;
    (void)o1, (void)o2;
    ++record->pairs;
    record->contacts += count;
    for (i = 0; i < count; ++i)
        record->validNormals += fabs(contacts[i].normal[0] * contacts[i].normal[0] + contacts[i].normal[1] *
                                     contacts[i].normal[1] + contacts[i].normal[2] * contacts[i].normal[2] - 1.0) < TOLERANCE;
}

static void checkSpaceCollide(void) {
    dSpaceID space = dSimpleSpaceCreate(0);
    dGeomID lower = gdcCreateConvexFromPoints(space, cubePoints, 8);
    dGeomID upper = dCreateBox(space, 1, 1, 1);
    struct SpaceCollideRecord record = {0, 0, 0};
    int threads, cache;
    dGeomSetPosition(lower, 0, 0, 0);
    dGeomSetPosition(upper, 0, 0, 0.99);
    /* Static geoms: with the pair cache on, the second call onwards is answered from it. */
    for (cache = 0; cache <= 1; ++cache) {
        gdcSetPairCacheEnabled(cache);
        gdcClearPairCache();
        for (threads = 1; threads <= 2; ++threads) {
            CHECK(gdcSetThreadCount(threads) == GDC_OK);
            record.pairs = record.contacts = record.validNormals = 0;
            CHECK(gdcSpaceCollide(space, 8, &record, recordPair) == GDC_OK);
            CHECK(record.pairs == 1 && record.contacts == 4 && record.validNormals == 4);
        }
    }
    CHECK(gdcSetThreadCount(-1) == GDC_ERROR_INVALID_ARGUMENT);
    CHECK(strlen(gdcLastError()) > 0);
    CHECK(gdcSpaceCollide(space, 8, &record, NULL) == GDC_ERROR_INVALID_ARGUMENT);
    CHECK(gdcSpaceCollide(space, 0, &record, recordPair) == GDC_ERROR_INVALID_ARGUMENT);
    CHECK(gdcSetThreadCount(0) == GDC_OK);
    dSpaceDestroy(space);
}

/* gdcReduceBodyPair: a body of two unit cubes side by side (a 2 x 1 slab) sinking 0.01 into a
 * static ground box. Two geom pairs give 4 + 4 corners, two of them twice (the cubes' shared
 * edge); the budget of 4 keeps the slab's own four corners (x = +-1, y = +-0.5): the largest area. */
static int collectSlab(dGeomID ground, dGeomID left, dGeomID right, dContactGeom* contacts) {
    int n = dCollide(ground, left, 8, contacts, sizeof(dContactGeom));
    n += dCollide(right, ground, 8, contacts + n, sizeof(dContactGeom)); /* either geom order */
    return n;
}

static void checkReduceBodyPair(void) {
    dWorldID world = dWorldCreate();
    dBodyID slab = dBodyCreate(world), other = dBodyCreate(world);
    dGeomID ground = dCreateBox(0, 4, 4, 1);
    dGeomID left = dCreateBox(0, 1, 1, 1), right = dCreateBox(0, 1, 1, 1);
    dContactGeom contacts[16], copy[16];
    gdcSettings settings;
    int n, kept, keptMirrored, i, j, corners = 0;
    dWorldSetGravity(world, 0, 0, -9.81);
    dGeomSetPosition(ground, 0, 0, -0.5);
    dGeomSetBody(left, slab);
    dGeomSetBody(right, slab);
    dGeomSetOffsetPosition(left, -0.5, 0, 0);
    dGeomSetOffsetPosition(right, 0.5, 0, 0);
    dBodySetPosition(slab, 0, 0, 0.49);
    gdcDefaultSettings(&settings);
    CHECK(settings.maxBodyPairContacts == 4);

    n = collectSlab(ground, left, right, contacts);
    CHECK(n == 8);
    kept = gdcReduceBodyPair(0, slab, contacts, n, sizeof(dContactGeom), &settings);
    CHECK(kept == 4);
    CHECK(strcmp(gdcLastError(), "") == 0);
    for (i = 0; i < kept && i < 16; ++i) {
        corners += fabs(fabs(contacts[i].pos[0]) - 1.0) < TOLERANCE && fabs(fabs(contacts[i].pos[1]) - 0.5) < TOLERANCE;
        CHECK(fabs(contacts[i].depth - 0.01) < TOLERANCE);
        CHECK(contacts[i].g1 == ground || contacts[i].g2 == ground);
    }
    CHECK(corners == 4);
    /* The mirrored call (the bodies swapped) keeps the same contacts; NULL settings: the defaults. */
    n = collectSlab(ground, left, right, copy);
    keptMirrored = gdcReduceBodyPair(slab, 0, copy, n, sizeof(dContactGeom), NULL);
    CHECK(keptMirrored == kept);
    for (i = 0; i < kept && i < keptMirrored; ++i)
        for (j = 0; j < 3; ++j) CHECK(copy[i].pos[j] == contacts[i].pos[j]);
    /* Budget 0: every contact kept. */
    settings.maxBodyPairContacts = 0;
    n = collectSlab(ground, left, right, contacts);
    CHECK(gdcReduceBodyPair(0, slab, contacts, n, sizeof(dContactGeom), &settings) == n);
    settings.maxBodyPairContacts = 4;

    /* Bad input: a negative error code, a message, the array untouched. */
    n = collectSlab(ground, left, right, contacts);
    memcpy(copy, contacts, sizeof contacts);
#define CHECK_REFUSED(call, words)                                                            \
    do {                                                                                      \
        CHECK((call) == -GDC_ERROR_INVALID_ARGUMENT);                                         \
        CHECK(strstr(gdcLastError(), words) != NULL);                                         \
        CHECK(memcmp(copy, contacts, sizeof contacts) == 0);                                  \
    } while (0)
    CHECK_REFUSED(gdcReduceBodyPair(slab, slab, contacts, n, sizeof(dContactGeom), &settings), "same body");
    CHECK_REFUSED(gdcReduceBodyPair(0, 0, contacts, n, sizeof(dContactGeom), &settings), "static world");
    CHECK_REFUSED(gdcReduceBodyPair(0, slab, contacts, -1, sizeof(dContactGeom), &settings), "negative");
    CHECK_REFUSED(gdcReduceBodyPair(0, slab, NULL, n, sizeof(dContactGeom), &settings), "null");
    CHECK_REFUSED(gdcReduceBodyPair(0, slab, contacts, n, 8, &settings), "skip");
    CHECK_REFUSED(gdcReduceBodyPair(other, slab, contacts, n, sizeof(dContactGeom), &settings), "not between");
    settings.maxBodyPairContacts = 17;
    CHECK_REFUSED(gdcReduceBodyPair(0, slab, contacts, n, sizeof(dContactGeom), &settings), "maxBodyPairContacts");
    settings.maxBodyPairContacts = 4;
    contacts[2].normal[2] = 0.5; /* not unit length */
    memcpy(copy, contacts, sizeof contacts);
    CHECK_REFUSED(gdcReduceBodyPair(0, slab, contacts, n, sizeof(dContactGeom), &settings), "unit");
#undef CHECK_REFUSED
    /* Nothing to reduce: 0 contacts. */
    CHECK(gdcReduceBodyPair(0, slab, NULL, 0, sizeof(dContactGeom), &settings) == 0);
    CHECK(strcmp(gdcLastError(), "") == 0);

    dGeomDestroy(ground);
    dGeomDestroy(left);
    dGeomDestroy(right);
    dWorldDestroy(world);
}

int main(void) {
    dSpaceID space;
    dGeomID fromPoints, fromPlanes, box;
    gdcSettings two;

    dInitODE2(0);
    CHECK(strcmp(gdcLastError(), "") == 0);
    space = dSimpleSpaceCreate(0);

    checkSettings();
    checkCreateErrors(space);

    fromPoints = gdcCreateConvexFromPoints(space, cubePoints, 8);
    fromPlanes = gdcCreateConvex(space, cubePlanes, 6, cubePoints, 8, cubePolygons);
    box = dCreateBox(space, 1, 1, 1);
    CHECK(fromPoints != 0 && fromPlanes != 0);
    CHECK(strcmp(gdcLastError(), "") == 0);
    if (fromPoints && fromPlanes) {
        CHECK(dGeomGetClass(fromPoints) == dConvexClass && dGeomGetClass(fromPlanes) == dConvexClass);
        /* gdcCollide without gdcInstall, then ODE's own dCollide after it */
        checkContacts(fromPoints, fromPlanes, 0);
        checkContacts(box, fromPoints, 0);
        CHECK(gdcInstall(NULL) == GDC_OK);
        checkContacts(fromPlanes, fromPoints, 1);
        checkContacts(fromPoints, box, 1);
        /* maxContacts reaches the collider */
        gdcDefaultSettings(&two);
        two.maxContacts = 2;
        CHECK(gdcInstall(&two) == GDC_OK);
        {
            dContactGeom contacts[8];
            dGeomSetPosition(fromPlanes, 0, 0, 0.99);
            dGeomSetPosition(fromPoints, 0, 0, 0);
            CHECK(dCollide(fromPoints, fromPlanes, 8, contacts, sizeof(dContactGeom)) == 2);
        }
        CHECK(gdcInstall(NULL) == GDC_OK);
    }
    checkSpaceCollide();
    checkReduceBodyPair();
    dSpaceDestroy(space); /* destroys the geoms; gdcontact releases their hulls */
    dCloseODE();

    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("C API: all checks passed\n");
    return 0;
}

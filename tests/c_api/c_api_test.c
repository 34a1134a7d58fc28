/* The C API from C99: every function of <gdcontact/ode.h>, its errors and ODE's contact convention.
 * Exits non-zero naming each failed check. */
#include <gdcontact/ode.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

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
    CHECK(defaults.maxContacts == 8);
    CHECK(defaults.contactOrder == GDC_ORDER_DEEPEST_LAST);
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
    bad = defaults; bad.contactOrder = 2;               checkRejected(bad, "contactOrder");
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
        CHECK(fabs(contacts[i].normal[2] + 1.0) < 1e-9); /* from o2 (upper) into o1 (lower) */
        CHECK(fabs(contacts[i].depth - 0.01) < 1e-9);
        CHECK(fabs(fabs(contacts[i].pos[0]) - 0.5) < 1e-9 && fabs(fabs(contacts[i].pos[1]) - 0.5) < 1e-9);
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
                                     contacts[i].normal[1] + contacts[i].normal[2] * contacts[i].normal[2] - 1.0) < 1e-9;
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
    dSpaceDestroy(space); /* destroys the geoms; gdcontact releases their hulls */
    dCloseODE();

    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("C API: all checks passed\n");
    return 0;
}

/* gdcontact for C programs: the ODE drop-in collider (see <gdcontact/ode.hpp> for C++).
 *
 * C99, includes only <ode/ode.h>, usable from C and C++. Every function is extern "C" and never
 * lets an exception out: failures come back as an error code or a 0 geom, with a message in
 * gdcLastError(). Link with `pkg-config --libs gdcontact` (or CMake's gdcontact::gdcontact).
 *
 *     dInitODE2(0);
 *     gdcInstall(NULL);                                   after dInitODE2, NULL: default settings
 *     dGeomID rock = gdcCreateConvex(space, planes, planeCount, points, pointCount, polygons);
 *     if (!rock) fprintf(stderr, "%s\n", gdcLastError());
 *
 * dBox, dPlane, bodies, spaces, the near callback, dCollide and dWorldStep stay as they are.
 * Details: docs/install.md and docs/ode.md. */
#ifndef GDCONTACT_ODE_H
#define GDCONTACT_ODE_H

#include <ode/ode.h>

#if defined(__GNUC__) || defined(__clang__)
#define GDCONTACT_C_API __attribute__((visibility("default")))
#else
#define GDCONTACT_C_API
#endif

#ifdef __cplusplus
#define GDCONTACT_C_NOEXCEPT noexcept
extern "C" {
#else
#define GDCONTACT_C_NOEXCEPT
#endif

/* Error codes returned by gdcInstall (0 is success). gdcLastError() says what went wrong. */
#define GDC_OK 0
#define GDC_ERROR_INVALID_ARGUMENT 1 /* bad settings or shape data, a null pointer where data is needed */
#define GDC_ERROR_OUT_OF_MEMORY 2    /* an allocation failed; nothing was changed */
#define GDC_ERROR_INTERNAL 3         /* any other failure inside gdcontact (a bug: please report it) */
#define GDC_ERROR_ODE_NOT_INITIALIZED 4 /* gdcInstall before dInitODE2 (or after dCloseODE): call dInitODE2 first */

/* Values of gdcSettings.normalMethod (gdc::NormalMethod). */
#define GDC_NORMAL_GROWTH_DISTANCE 0 /* the paper's growth-distance normal (default) */
#define GDC_NORMAL_SEPARATING_AXIS 1 /* the exact minimum-translation normal (slower for big hulls) */

/* Values of gdcSettings.contactOrder (gdc::ContactOrder): the order in which dWorldQuickStep meets
 * one pair's contacts. */
#define GDC_ORDER_DEEPEST_LAST 0  /* the deepest point last: the least drift */
#define GDC_ORDER_DEEPEST_FIRST 1 /* the deepest point first: resting bodies sleep a little sooner */
#define GDC_ORDER_DEEPEST_FIRST_WHEN_LOADED 2 /* deepest first where the pair is deeper than
                                                * loadedDepthFraction of its size, else deepest last
                                                * (default): loaded columns hold */

/* The fields of gdc::Settings, in its order, with its units and the bounds gdcInstall checks
 * (settings.hpp says why each bound is there): rayCastTolerance (relative, 1e-15..1e-3),
 * maxRayCastIterations (1..10000), angularTolerance (radians, 0..0.5), margin (length unit, 0..1),
 * spanContactRegion (0 or not 0), maxContacts (1..16), bruteForceSupportLimit (0..65536),
 * coplanarTolerance (radians, 0..0.1), normalMethod (GDC_NORMAL_*), manifoldReuseDistance (length
 * unit, 0..1; 0: the pair cache is exact), contactOrder (GDC_ORDER_*), reductionHysteresis
 * (relative, 0..0.1).
 * Always start from gdcDefaultSettings(): fields are only ever added at the end. */
typedef struct gdcSettings {
    double rayCastTolerance;
    int maxRayCastIterations;
    double angularTolerance;
    double margin;
    int spanContactRegion;
    int maxContacts;
    int bruteForceSupportLimit;
    double coplanarTolerance;
    int normalMethod;
    double manifoldReuseDistance;
    /* The contact set the solver gets (its budget is maxContacts) */
    int contactOrder;
    double reductionHysteresis;
    /* ---- Per-body-pair contact budget (gdc::Settings, include/gdcontact/body_pair.hpp) ----
     * maxBodyPairContacts (0..16; 0: off): most contacts kept between two bodies touching through
     * several pairs of geoms, per contact direction; bodyPairNormalTolerance (radians, 0..0.5):
     * normals within it form one direction. gdcSpaceCollide applies them. */
    int maxBodyPairContacts;
    double bodyPairNormalTolerance;
    /* GDC_ORDER_DEEPEST_FIRST_WHEN_LOADED's threshold (relative to the pair's size, 0..1; gdc::Settings
     * places it after contactOrder, C adds fields at the end only) */
    double loadedDepthFraction;
    /* Points per whole turn of a cylinder's rim (4..64): gdc::Settings::rimPointsPerTurn */
    int rimPointsPerTurn;
} gdcSettings;

/* Fills *settings with gdcontact's defaults for the ODE it is built against (gdc::ode::defaultSettings:
 * those of gdc::Settings, maxContacts 8 against a single-precision ODE). Does nothing for NULL. */
GDCONTACT_C_API void gdcDefaultSettings(gdcSettings* settings) GDCONTACT_C_NOEXCEPT;

/* gdc::ode::install: routes ODE's box–box, box–convex, convex–convex, box–plane and convex–plane
 * pairs, and cylinder–box/convex/plane/cylinder, capsule–box/convex/cylinder and sphere–convex, to
 * gdcontact. Call after dInitODE2() (and again after a new dInitODE2: dCloseODE forgets
 * it; calling it again in one session replaces the settings). NULL: the defaults. Returns GDC_OK,
 * or an error code with ODE's colliders and the settings in use left as they were
 * (GDC_ERROR_INVALID_ARGUMENT: a field out of its range; GDC_ERROR_ODE_NOT_INITIALIZED: called
 * before dInitODE2 or after dCloseODE). */
GDCONTACT_C_API int gdcInstall(const gdcSettings* settings) GDCONTACT_C_NOEXCEPT;

/* gdc::ode::collide, a dColliderFn: usable in a near callback without gdcInstall. ODE's contact
 * convention (normal from o2 into o1, depth ≥ 0, at most flags & 0xffff contacts at stride skip);
 * uses the settings of the last gdcInstall. Returns the number of contacts; a failure inside
 * gdcontact is reported through dMessage and gives 0, misuse (a geom class it does not handle,
 * skip < sizeof(dContactGeom)) goes to dError. A dConvex gdcontact does not know (plain
 * dCreateConvex, or changed by dGeomSetConvex) is collided by ODE's own convex collider, with one
 * dMessage. */
GDCONTACT_C_API int gdcCollide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact,
                               int skip) GDCONTACT_C_NOEXCEPT;

/* gdc::ode::createConvex in dCreateConvex's layout: planes (a,b,c,d per face), points (x,y,z),
 * polygons (per face its vertex count, then its point indices). The arrays are copied. A real
 * dConvex in `space` (may be 0) whose hull gdcontact knows; freed by dGeomDestroy as usual.
 * Takes what dCreateConvex takes: data rounded to 6 digits passes; where the planes or polygons
 * disagree with the points (flipped, reordered, non-planar, missing) the geom is the hull of the
 * points, with one dMessage. Returns 0 only for data ODE cannot use either (NULL arrays, an index
 * out of range, NaN/Inf, points without interior; gdcLastError() names the problem). */
GDCONTACT_C_API dGeomID gdcCreateConvex(dSpaceID space, const dReal* planes, unsigned planeCount,
                                        const dReal* points, unsigned pointCount,
                                        const unsigned* polygons) GDCONTACT_C_NOEXCEPT;

/* gdc::ode::createConvex of a point cloud: a dConvex of the convex hull of `pointCount` points
 * (x,y,z triples, geom frame). Returns 0 on error: fewer than 4 points, NaN/Inf coordinates,
 * points without interior (gdcLastError() says which). */
GDCONTACT_C_API dGeomID gdcCreateConvexFromPoints(dSpaceID space, const dReal* points,
                                                  unsigned pointCount) GDCONTACT_C_NOEXCEPT;

/* As gdcCreateConvex, but planes and polygons that disagree with the points are an error
 * (0, gdcLastError() names the plane, polygon or point) instead of the hull of the points. */
GDCONTACT_C_API dGeomID gdcCreateConvexStrict(dSpaceID space, const dReal* planes, unsigned planeCount,
                                              const dReal* points, unsigned pointCount,
                                              const unsigned* polygons) GDCONTACT_C_NOEXCEPT;

/* Receives one touching pair's contacts from gdcSpaceCollide: `count` >= 1 contacts at `contacts`
 * (consecutive dContactGeoms, valid during the call), as dCollide(o1, o2, ...) would give them. */
typedef void (*gdcContactHandler)(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count);

/* gdc::ode::spaceCollide: one call per step in place of dSpaceCollide + near callback + dCollide.
 * ODE's broad phase finds the pairs (nested spaces included); gdcontact's pairs are collided on the
 * threads of gdcSetThreadCount, the others by ODE's own colliders; then `handler` runs on the
 * calling thread for each touching pair, in an order that does not depend on the thread count.
 * At most maxContactsPerPair (1..65535) contacts a pair. Returns GDC_OK or an error code
 * (GDC_ERROR_INVALID_ARGUMENT: a NULL or non-space `space`, a NULL handler, a count out of range). */
GDCONTACT_C_API int gdcSpaceCollide(dSpaceID space, int maxContactsPerPair, void* data,
                                    gdcContactHandler handler) GDCONTACT_C_NOEXCEPT;

/* gdc::ode::setThreadCount: threads gdcSpaceCollide uses, 0 (default) one per hardware thread,
 * 1 serial on the calling thread, at most 256. Returns GDC_OK or GDC_ERROR_INVALID_ARGUMENT. */
GDCONTACT_C_API int gdcSetThreadCount(int threads) GDCONTACT_C_NOEXCEPT;

/* gdc::ode::setPairCacheEnabled / clearPairCache: the adapter's pair cache (on by default; exact
 * unless gdcSettings::manifoldReuseDistance is set; docs/ode.md). */
GDCONTACT_C_API void gdcSetPairCacheEnabled(int enabled) GDCONTACT_C_NOEXCEPT;
GDCONTACT_C_API void gdcClearPairCache(void) GDCONTACT_C_NOEXCEPT;

/* gdc::ode::reduceBodyPair, the per-body-pair contact budget for a program with its own near
 * callback (what gdcSpaceCollide applies by itself). `contacts` (count of them at stride `skip`,
 * at least sizeof(dContactGeom)) are every contact one step's near callback got between the
 * geoms of body b1 and those of body b2 (several geom pairs: bodies made of several geoms), each
 * as dCollide gave it (g1, g2 name its pair's geoms, one on b1 and one on b2, in either order;
 * normal from g2 into g1). b1 or b2 may be 0 (the static world), not both. They are clustered by
 * normal (settings->bodyPairNormalTolerance), near-duplicates merged, and each cluster reduced to
 * settings->maxBodyPairContacts: the deepest kept, the widest support, the carried body's centre
 * of mass over it; ties within settings->reductionHysteresis go to a fixed identity, so the same
 * points are kept from step to step. The survivors are moved to the front of the array in their
 * order, each unchanged; returns their count. Contacts that all come from one geom pair, and
 * everything when maxBodyPairContacts is 0, are kept as they are. The mirrored call (b1 and b2
 * swapped) keeps the same contacts. settings NULL: gdcontact's defaults (gdcDefaultSettings).
 * Returns a negative number, -GDC_ERROR_INVALID_ARGUMENT (and the others as gdcInstall's), with
 * gdcLastError() saying why and the array left as it was, for: a setting out of range, count < 0,
 * contacts NULL with count > 0, skip < sizeof(dContactGeom), b1 == b2, a contact whose geoms are
 * not one on b1 and one on b2, a normal that is not unit length or a field that is not finite.
 *
 *     per pair of bodies, after dSpaceCollide collected their contacts into `pair[0..n)`:
 *     int kept = gdcReduceBodyPair(b1, b2, pair, n, sizeof(dContactGeom), &settings);
 *     if (kept < 0) { fprintf(stderr, "%s\n", gdcLastError()); kept = n; }
 *     for (i = 0; i < kept; ++i) { contact.geom = pair[i]; ... dJointCreateContact ... } */
GDCONTACT_C_API int gdcReduceBodyPair(dBodyID b1, dBodyID b2, dContactGeom* contacts, int count, int skip,
                                      const gdcSettings* settings) GDCONTACT_C_NOEXCEPT;

/* This thread's last error message, "" if none. gdcInstall, gdcCreateConvex*, gdcSpaceCollide,
 * gdcSetThreadCount and gdcReduceBodyPair set it when they fail and clear it when they succeed. The string stays valid
 * until this thread's next call of one of those functions. Never NULL. */
GDCONTACT_C_API const char* gdcLastError(void) GDCONTACT_C_NOEXCEPT;

#ifdef __cplusplus
}
#endif

#endif /* GDCONTACT_ODE_H */

// gdcontact as a drop-in collider for the Open Dynamics Engine (ODE 0.16.2).
//
// The only public header of gdcontact that includes ODE. Call install() once after dInitODE2()
// and dWorldStep / dWorldQuickStep consume gdcontact's contacts for every box–box, box–convex,
// convex–convex, box–plane and convex–plane pair; other pairs stay with ODE. See docs/ode.md.
#pragma once

#include <gdcontact/body_pair.hpp>
#include <gdcontact/collide.hpp>
#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>
#include <gdcontact/types.hpp>

#include <ode/ode.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace gdc::ode {

/// gdcontact's defaults for the ODE this library is built against: gdc::Settings' own, except
/// maxContacts 8 (a box–box octagon kept whole) against a single-precision ODE. There, with 6
/// points a face pair, dWorldStep's Dantzig LCP stopped on ties ("LCP internal error, s <= 0": a
/// row that carries no force, left exactly on its bound, asked to move) in stacks of turned plates
/// far more often than with dBox's points or 8 of gdcontact's, and the stacks tilted;
/// dWorldQuickStep fails no more seeds with 8 (docs/install.md, "Single precision: 8 points a
/// face"). install(), BodyPairContacts, spaceCollide before any install() and the C API's
/// gdcDefaultSettings start from these; a program that builds its own Settings should too.
GDCONTACT_API Settings defaultSettings();

/// Routes ODE's box–box, box–convex, convex–convex, box–plane and convex–plane pairs, and its
/// curved pairs that get one point where a region touches — cylinder–box, cylinder–convex,
/// cylinder–plane, cylinder–cylinder, capsule–box, capsule–convex, capsule–cylinder and
/// sphere–convex — to gdcontact (through dSetColliderOverride; docs/ode.md lists the pairs left
/// to ODE and why). Call after dInitODE2(); dCloseODE() resets ODE's
/// collider table and so forgets it (call it again after a new dInitODE2()). Calling it again in
/// the same session replaces the settings. `settings` are checked by gdc::validate (InvalidInput
/// naming the field and its bounds); called while ODE is not initialised it throws InvalidInput
/// saying to call dInitODE2() first. Contacts a dCollide call returns are at most
/// min(settings.maxContacts, flags & 0xffff).
GDCONTACT_API void install(const Settings& settings = defaultSettings());

/// Whether install() routes geoms of these two ODE classes (dBoxClass, dCylinderClass, …; either
/// order) to gdcontact — the pairs collide() takes. A program calling collide() itself from a near
/// callback asks this to leave the other pairs to dCollide.
GDCONTACT_API bool handles(int class1, int class2);

/// dColliderFn-compatible: usable directly, in a near-callback, without install(). Follows ODE's
/// contact convention (normal from o2 into o1, unit; depth ≥ 0; g1/g2 as received;
/// side1 = side2 = -1; at most flags & 0xffff contacts at stride `skip`). Handles the pairs
/// install() routes, in any order. A curved geom of a size ODE accepts and the core does not (a
/// zero radius, a zero-length cylinder) is collided as the thinnest shape the core takes. Uses the settings of the last install() (defaultSettings() before
/// any). A dConvex gdcontact does not know (made by plain dCreateConvex, or changed by
/// dGeomSetConvex) is collided by ODE's own convex collider, with one dMessage (docs/ode.md).
/// Never throws: a failure inside gdcontact is reported through dMessage and yields 0 contacts;
/// misuse (an unsupported class, skip < sizeof(dContactGeom)) is reported through dError.
GDCONTACT_API int collide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip);

/// As above with explicit settings (not validated per call; pass settings that install() would
/// accept). Needs no global state beyond the convex registry.
GDCONTACT_API int collide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip,
            const Settings& settings);

/// A real dConvex geom for the convex hull of `pointCount` points (x,y,z triples, geom-local
/// frame), placed in `space` (may be 0). ODE's own colliders (sphere, capsule, ray, ...) see the
/// same hull. gdcontact owns the hull data and releases it when ODE frees the geom
/// (dGeomDestroy, or dSpaceDestroy with cleanup). Throws InvalidInput for fewer than 4 points,
/// non-finite coordinates or points without interior.
GDCONTACT_API dGeomID createConvex(dSpaceID space, const dReal* points, unsigned pointCount);

/// dCreateConvex's layout: `planeCount` planes (a,b,c,d: unit outward normal, n·x = d on the
/// face), `pointCount` points, and per plane its polygon (vertex count, then that many point
/// indices, counter-clockwise seen from outside). Takes what dCreateConvex takes: the data is
/// checked to its own precision (1e-5 of the shape's size: data printed with 6 digits passes) and
/// copied (the caller may free its arrays). Where the planes and polygons disagree with the points
/// (flipped or reordered planes, non-planar or missing faces) the geom is the convex hull of the
/// points — the solid ODE's convex collider sees — ODE is given that hull's planes and polygons,
/// and one dMessage says so. Throws InvalidInput only for data ODE cannot use either: null arrays,
/// an index out of range, non-finite numbers, fewer than 4 points or points without interior.
GDCONTACT_API dGeomID createConvex(dSpaceID space, const dReal* planes, unsigned planeCount,
                     const dReal* points, unsigned pointCount, const unsigned* polygons);

/// As createConvex (dCreateConvex's layout), for data that must be right as given: where the
/// planes and polygons disagree with the points it throws InvalidInput naming the offending plane,
/// polygon or point instead of taking the hull.
GDCONTACT_API dGeomID createConvexStrict(dSpaceID space, const dReal* planes, unsigned planeCount,
                                         const dReal* points, unsigned pointCount, const unsigned* polygons);

/// The polytope gdcontact uses for a geom, in the geom's local frame: for a dBox, a box of its
/// current lengths; for a dConvex made by createConvex, its hull. nullptr for every other geom
/// (including a dConvex made with plain dCreateConvex).
GDCONTACT_API std::shared_ptr<const Polytope> polytopeOf(dGeomID geom);

/// World pose of a placeable geom (dGeomGetPosition / dGeomGetRotation, offsets included).
/// Throws InvalidInput for a non-placeable geom (a plane or a space).
GDCONTACT_API Pose poseOf(dGeomID geom);

/// Number of convex hulls gdcontact currently keeps for live createConvex geoms (diagnostics:
/// it returns to its previous value when those geoms are destroyed).
GDCONTACT_API std::size_t liveConvexCount();

}  // namespace gdc::ode

// ---- Whole-step collision for big worlds (src/ode/space_collide.cpp) ----------------------------
namespace gdc::ode {

/// Receives one touching pair's contacts from spaceCollide: `count` ≥ 1 contacts at `contacts`
/// (stride sizeof(dContactGeom); valid only during the call; the handler may modify them).
using ContactHandler = void (*)(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count);

/// One call per step in place of dSpaceCollide + near callback + dCollide. ODE's broad phase
/// (dSpaceCollide, nested spaces through dSpaceCollide2 as ODE's documentation describes) lists
/// the candidate pairs. gdcontact's pairs (box, createConvex convex and plane geoms, as collide()
/// handles them, with the installed settings) are collided on the threads setThreadCount chose;
/// every other pair goes to dCollide on the calling thread. Then `handler(data, o1, o2, contacts,
/// count)` runs on the calling thread for each pair with at least one contact, in the broad phase's
/// order, so its output never depends on the thread count. contacts[k] are what
/// dCollide(o1, o2, maxContactsPerPair, contacts, sizeof(dContactGeom)) gives after install()
/// (gdcontact's pairs return at most min(maxContactsPerPair, Settings::maxContacts) contacts) —
/// except where two bodies touch through more than one geom pair (composites) and the installed
/// Settings::maxBodyPairContacts is not 0: then the contacts of all those pairs are reduced
/// together by reduceBodyPair (in the broad phase's order of the pairs), and the handler is still
/// called once per geom pair, with that pair's surviving contacts (a pair none of whose contacts
/// survived is not reported), so a handler written per geom pair keeps working.
/// Throws InvalidInput for a null or non-space `space`, a null handler, or maxContactsPerPair
/// outside 1..65535; an exception from the handler propagates (the remaining pairs are dropped).
/// The geoms may not be moved or destroyed while it runs (the handler may create joints). Calls on
/// several threads at once (on different spaces) are allowed: one of them uses the pool, the
/// others run serially on their own thread, with the same results.
GDCONTACT_API void spaceCollide(dSpaceID space, int maxContactsPerPair, void* data, ContactHandler handler);

/// Threads spaceCollide uses for gdcontact's pairs: 0 (the default) one per hardware thread;
/// 1 serial, on the calling thread; n: the calling thread and n − 1 pool threads. Throws
/// InvalidInput outside 0..256. Takes effect at the next spaceCollide call.
GDCONTACT_API void setThreadCount(int threads);

}  // namespace gdc::ode

// ---- The per-body-pair contact budget (src/ode/body_pair.cpp, docs/ode.md) ---------------------
namespace gdc::ode {

/// Reduces the contacts between two bodies made of several geoms (composites) to the body-pair
/// budget: settings.maxBodyPairContacts per contact direction (gdc::reduceBodyPairContacts:
/// clustered by normal, touching points left out where others overlap, near-duplicates merged,
/// the deepest kept, the widest support, the carried body's centre of mass — dBodyGetPosition —
/// kept over it, ties within settings.reductionHysteresis to a fixed identity; the carried body is
/// the one the normal pushes against its world's gravity). The C twin is gdcReduceBodyPair. `contacts` (count of them at stride `skip`) are
/// those of every geom pair between b1 and b2 a near callback collected in one step, each as
/// dCollide gave it (g1, g2 name the pair's geoms; normal from g2 into g1; either geom order).
/// b1 or b2 may be 0 (the static world), not both. The survivors are moved to the front, in
/// their order, unchanged (each keeps its own geoms, normal and depth); returns their count.
/// Contacts that all come from one geom pair are returned as they are (that pair's own
/// reduction, settings.maxContacts, applies), as is everything with maxBodyPairContacts == 0.
/// The same contacts, mirrored (b1, b2 swapped, or each pair's geoms swapped), give the same
/// survivors. Throws InvalidInput for bad settings (gdc::validate), count < 0, a null array,
/// skip < sizeof(dContactGeom), b1 == b2, or a contact whose geoms are not one on b1 and one on
/// b2 (or whose normal is not unit, or a field not finite).
///
///     // near callback: collect; after dSpaceCollide, per pair of bodies:
///     int kept = gdc::ode::reduceBodyPair(b1, b2, pairContacts.data(), n, sizeof(dContactGeom), settings);
///     for (int i = 0; i < kept; ++i) { ... dJointCreateContact(world, group, &contact); ... }
GDCONTACT_API int reduceBodyPair(dBodyID b1, dBodyID b2, dContactGeom* contacts, int count, int skip,
                                 const Settings& settings);

/// Collects one step's contacts from a near callback, then hands them over with the body-pair
/// budget applied — what spaceCollide does, for a program that keeps its own near callback:
///
///     gdc::ode::BodyPairContacts collected(settings);     // kept across steps: reuses its memory
///     // near callback:  n = dCollide(o1, o2, 8, contacts, sizeof(dContactGeom));
///     //                 collected.add(o1, o2, contacts, n);
///     dSpaceCollide(space, &collected, &nearCallback);
///     collected.deliver(data, &handler);                    // handler as spaceCollide's; then cleared
///
/// deliver() reduces the contacts of each pair of bodies that touch through several geom pairs
/// (reduceBodyPair, in the order the pairs were added) and calls `handler(data, o1, o2, contacts,
/// count)` once per added geom pair with its surviving contacts (none survived, or none added: not
/// called), in the order of add(). So the output depends only on that order. Pairs of two static
/// geoms are handed over unchanged. Not thread-safe: one collector per thread.
class GDCONTACT_API BodyPairContacts {
public:
    /// Throws InvalidInput for settings gdc::validate refuses.
    explicit BodyPairContacts(const Settings& settings = defaultSettings());
    /// One geom pair's contacts (`count` at `contacts`, stride sizeof(dContactGeom)), as dCollide
    /// gave them for (o1, o2). Throws InvalidInput for count < 0 or null contacts with count > 0.
    void add(dGeomID o1, dGeomID o2, const dContactGeom* contacts, int count);
    /// Reduces, hands every pair over, and clears (also when the handler throws).
    void deliver(void* data, ContactHandler handler);
    /// Forgets what was added.
    void clear();

private:
    struct Pair {
        dGeomID o1, o2;
        std::size_t offset;
        int count;
    };
    Settings settings_;
    std::vector<Pair> pairs_;
    std::vector<dContactGeom> contacts_;
    std::vector<dContactGeom> gathered_;
    std::vector<int> done_;
};

}  // namespace gdc::ode

// ---- The pair cache (src/ode/pair_cache_table.cpp, docs/ode.md) --------------------------------
namespace gdc::ode {

/// What the adapter's pair cache holds and how its answers went since it was last cleared.
struct PairCacheStats {
    std::size_t entries;   ///< geom pairs cached now
    std::size_t capacity;  ///< most entries it keeps (setPairCacheCapacity)
    std::size_t bytes;     ///< memory it holds
    std::uint64_t hits;     ///< answers repeated without a query (nothing moved: exact, bit for bit)
    std::uint64_t carried;  ///< answers carried along (moved < Settings::manifoldReuseDistance)
    std::uint64_t misses;   ///< full queries
};

/// The adapter keeps one gdc::PairCache per geom pair it is asked about (collide() and
/// spaceCollide), on by default. With the default settings it is exact: a pair none of whose
/// inputs changed (poses, shapes, settings) gets its last answer again, bit for bit, without a
/// query. Only pairs whose geoms are static or belong to disabled bodies (ODE's auto-disable) can
/// stay unchanged, so only they are cached; a pair with an enabled body costs two ODE getters more
/// than without the cache. With
/// Settings::manifoldReuseDistance > 0 a pair that moved less than that gets its contacts carried
/// along instead (an approximation: see settings.hpp). Entries die with their geoms (ODE's free
/// hook), age out when their pair is no longer asked about, and never exceed the capacity. No
/// thread ever waits for it: a collide() call that finds it in use by another thread queries
/// without it (same answer). Off: every call a full query.
GDCONTACT_API void setPairCacheEnabled(bool enabled);
/// At most `entries` cached pairs (default 65536; about 0.9 KB each); shrinking drops the least
/// recently used. Not from inside a spaceCollide handler.
GDCONTACT_API void setPairCacheCapacity(std::size_t entries);
/// Drops every entry and zeroes the statistics. Not from inside a spaceCollide handler.
GDCONTACT_API void clearPairCache();
GDCONTACT_API PairCacheStats pairCacheStats();

}  // namespace gdc::ode

// gdc::ode::install / collide: ODE's geoms in, the core's manifold out as dContactGeoms.
#include <gdcontact/ode.hpp>

#include "pair_cache_table.hpp"
#include "resolved_pair.hpp"
#include "box_cache.hpp"
#include "convex_geoms.hpp"
#include "convex_registry.hpp"
#include "installed_settings.hpp"
#include "ode_internals.hpp"
#include "ode_real.hpp"
#include "round_geoms.hpp"
#include "geom_reading.hpp"
#include "thread_cache.hpp"
#include "trimesh_geoms.hpp"
#include "write_contacts.hpp"
#include "contact/pair_table.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <functional>
#include <optional>
#include <string>

namespace gdc::ode {
namespace {

using detail::className;
using detail::comesFirst;
using detail::readPoseInto;

// Misuse of the adapter is a programming error: ODE's error handler (which by default prints
// the message and exits) is the loud way ODE itself reports those.
[[noreturn]] void misuse(const std::string& what) {
    dError(d_ERR_UASSERT, "%s", ("gdcontact: " + what).c_str());
}

[[noreturn, gnu::cold, gnu::noinline]] void unsupportedClass(int geomClass) {
    misuse(std::string("gdc::ode::collide handles box, convex (gdc::ode::createConvex), plane, sphere, "
                       "capsule, cylinder and trimesh geoms in the pairs install() overrides; it got a ") +
           className(geomClass) + " (leave that pair to ODE: install() overrides only the supported pairs)");
}

// The polytope (geom frame) of a box or known convex geom; nullptr for an unknown convex; misuse
// for any other class.
// Inline: the box case is a getter and the thread cache's compare, less than the call around it.
[[gnu::always_inline]] inline const Polytope* polytopeFor(dGeomID geom, int geomClass, const Pose& pose,
                                                          const Settings& settings, detail::ThreadCache& cache,
                                                          bool& unregistered) {
    if (geomClass == dBoxClass) {
        dVector3 lengths;
        dGeomBoxGetLengths(geom, lengths);
        return &detail::borrowedBoxPolytope(cache, lengths);
    }
    if (geomClass != dConvexClass) unsupportedClass(geomClass);
    return detail::knownHull(geom, pose, settings, cache, unregistered);
}

const detail::ThreadCache::PlaneSlot& planeOf(dGeomID plane, detail::ThreadCache& cache) {
    dVector4 parameters;  // a·x + b·y + c·z ≤ d is the solid; (a,b,c) points out of it
    dGeomPlaneGetParams(plane, parameters);
    return detail::planeSlot(cache, parameters);
}

// Where a pair's cache comes from: handed over (spaceCollide found it while ODE's broad phase listed
// the pair), found through this call's own lease on the table, or none (the table is busy or off).
struct CacheSource {
    PairCache* given = nullptr;
    detail::PairCacheTable::Lease* lease = nullptr;
    PairCache* find(dGeomID o1, dGeomID o2) const {
        if (given) return given;
        return lease && *lease ? lease->find(o1, o2) : nullptr;
    }
    void count(const PairCache* cache) const {
        if (cache && !given && lease && *lease) lease->count(*cache);
    }
};

// The core query, through the pair's cache when there is one. The answer by reference — the
// cache's own manifold, or `storage` — so that a repeated answer is read where it lies (a
// Manifold's copies were a third of a repeated answer's cost, tests/ode/adapter_overhead.sh).
// A fresh answer goes to `storage`, one the pair cache carries along with the bodies to `carried`
// (gdc::collideInto writes only that there): every other answer is one the core computed, now or
// when it was cached.
template <class Query, class CachedQuery>
const Manifold& queryThrough(const CacheSource& source, dGeomID o1, dGeomID o2, Manifold& storage, Manifold& carried,
                             Query query, CachedQuery cachedQuery) {
    PairCache* cache = source.find(o1, o2);
    if (!cache) {
        query(storage);
        return storage;
    }
    const Manifold& manifold = cachedQuery(*cache, carried);
    source.count(cache);
    return manifold;
}

// AngularTolerance(radians), the thread's copy while `radians` is the same to the bit.
const gdc::detail::AngularTolerance& angularToleranceOf(detail::ThreadCache& cache, double radians) {
    std::uint64_t bits;
    std::memcpy(&bits, &radians, sizeof bits);
    if (cache.angularToleranceBits != bits) {
        cache.angularTolerance = gdc::detail::AngularTolerance(radians);
        cache.angularToleranceBits = bits;
    }
    return cache.angularTolerance;
}

// A fresh answer of the core, written into `out` by the pair table's cell (pair_table.hpp) — the
// one dispatch gdc::collide and the pair cache use too — in place: a Manifold returned by value is
// 0.6 KB zeroed and then copied. The answer goes to writeContacts alone, which orders the points by
// depth, keeping the order of equal depths, with the caller's limit as the core's budget
// (collideLimited): so the core's importance order is asked for only among equal depths
// (ImportanceOrder::AmongEqualDepths, half_space.hpp) and a face whose corners all have different
// depths (every tilted resting face) is not ranked — the same contacts, in the same order. A pair
// cache's query keeps the full order. The plane's normalisation is the thread's (planeSlot), made
// once per plane; a plane the core refuses is normalised here again, which throws its error.
void queryInto(const gdc::detail::Shape& a, const Pose& poseA, const gdc::detail::Shape& b, const Pose& poseB,
               const Settings& settings, detail::ThreadCache& cache, Manifold& out) {
    // Only a hull's or a curved kind's feature takes the angular tolerance's cosine and sine (a
    // box's are lazy, a plane has none).
    using gdc::detail::ShapeKind;
    const bool hull = (a.kind != ShapeKind::Box && a.kind != ShapeKind::HalfSpace) ||
                      (b.kind != ShapeKind::Box && b.kind != ShapeKind::HalfSpace);
    const gdc::detail::PairQuery query{settings, gdc::detail::ImportanceOrder::AmongEqualDepths,
                                       hull ? &angularToleranceOf(cache, settings.angularTolerance) : nullptr};
    gdc::detail::collidePair(a, poseA, b, poseB, query, out);
}

// A plane's pose in the core's call (it is ignored: a half-space lives in the world).
const Pose kWorld{};

gdc::detail::Shape planeShape(const detail::ThreadCache::PlaneSlot& plane) {
    if (!plane.normalised) gdc::detail::normaliseHalfSpace(plane.halfSpace);  // throws why
    return gdc::detail::Shape::of(plane.normalisedHalfSpace);
}

// The settings for one core call: `settings`, or a copy with the caller's smaller limit.
template <class Collide>
decltype(auto) collideLimited(const Settings& settings, int maxContacts, Collide collideWith) {
    if (settings.maxContacts == maxContacts) return collideWith(settings);  // the common case: no copy
    Settings pairSettings = settings;
    pairSettings.maxContacts = maxContacts;
    return collideWith(pairSettings);
}

// One geom of a pair with a curved kind: its kind and what goes with it (a curved size, a polytope,
// a plane, the pose). False for a plain convex (`unregistered`: ODE's collider).
bool resolveSide(dGeomID geom, int geomClass, const Settings& settings, detail::ThreadCache& cache, Pose& pose,
                 gdc::detail::ShapeKind& kind, gdc::detail::RoundShape& round, const Polytope*& polytope,
                 const detail::ThreadCache::PlaneSlot*& plane, bool& unregistered) {
    polytope = nullptr;  // a reused pair (spaceCollide's slots) may hold an earlier pair's
    if (geomClass == dPlaneClass) {
        kind = gdc::detail::ShapeKind::HalfSpace;
        plane = &planeOf(geom, cache);
        return true;
    }
    readPoseInto(geom, pose);
    if (detail::isRoundClass(geomClass)) {
        detail::readRound(geom, geomClass, kind, round);
        return true;
    }
    polytope = polytopeFor(geom, geomClass, pose, settings, cache, unregistered);
    if (polytope) kind = polytope->isBox() ? gdc::detail::ShapeKind::Box : gdc::detail::ShapeKind::Hull;
    return polytope != nullptr;
}

// A pair with a curved geom (kind Round), ordered as polytope pairs are (a plane always B).
bool resolveRound(const Settings& settings, detail::ThreadCache& cache, detail::ResolvedPair& out) {
    using Kind = detail::ResolvedPair::Kind;
    if (!detail::isGdcontactPair(out.class1, out.class2))
        unsupportedClass(detail::isRoundClass(out.class1) ? out.class2 : out.class1);
    bool unregistered = false;
    out.plane = nullptr;
    const bool usable =
        resolveSide(out.o1, out.class1, settings, cache, out.pose1(), out.kind1, out.round1, out.polytope1, out.plane,
                    unregistered) &&
        resolveSide(out.o2, out.class2, settings, cache, out.pose2(), out.kind2, out.round2, out.polytope2, out.plane,
                    unregistered);
    out.kind = usable ? Kind::Round : Kind::Ode;
    if (!usable) return !unregistered;
    if (out.class1 == dPlaneClass) out.flip = true;
    else if (out.class2 == dPlaneClass) out.flip = false;
    else out.flip = comesFirst(out.pose2().position, out.o2, out.pose1().position, out.o1);
    return true;
}

// One geom of a Round pair as the core takes it, with its bounding radius.
gdc::detail::Shape shapeOf(const detail::ResolvedPair& pair, bool second, double& radius) {
    const gdc::detail::ShapeKind kind = second ? pair.kind2 : pair.kind1;
    const Polytope* polytope = second ? pair.polytope2 : pair.polytope1;
    radius = 0;
    if (kind == gdc::detail::ShapeKind::HalfSpace) return planeShape(*pair.plane);
    if (kind == gdc::detail::ShapeKind::Box || kind == gdc::detail::ShapeKind::Hull) {
        radius = polytope->radius();
        return gdc::detail::Shape::of(*polytope);
    }
    const gdc::detail::RoundShape& round = second ? pair.round2 : pair.round1;
    radius = detail::roundRadius(kind, round);
    return gdc::detail::Shape::of(kind, round);
}

// A Round pair: the core's cell for the curved kinds (no pair cache: its entries hold polytopes).
int collideRound(const detail::ResolvedPair& pair, int maxContacts, dContactGeom* contact, int skip,
                 const Settings& settings, detail::ThreadCache& cache) {
    double radius1, radius2;
    const gdc::detail::Shape shape1 = shapeOf(pair, false, radius1);
    const gdc::detail::Shape shape2 = shapeOf(pair, true, radius2);
    const Pose& pose1 = shape1.hasPose() ? pair.pose1() : kWorld;
    const Pose& pose2 = shape2.hasPose() ? pair.pose2() : kWorld;
    Manifold& manifold = cache.scratch;
    collideLimited(settings, maxContacts, [&](const Settings& pairSettings) {
        pair.flip ? queryInto(shape2, pose2, shape1, pose1, pairSettings, cache, manifold)
                  : queryInto(shape1, pose1, shape2, pose2, pairSettings, cache, manifold);
    });
    if (manifold.empty()) return 0;
    return detail::writeContacts(manifold, pair.flip, radius1 + radius2, maxContacts, settings.contactOrder,
                                 detail::loadedDepthOf(settings, radius1, radius2), pair.o1, pair.o2, contact, skip,
                                 true);
}

// detail::resolvePair, inlined into gdc::ode::collide's path.
[[gnu::always_inline]] inline bool resolve(dGeomID o1, int class1, dGeomID o2, int class2, const Settings& settings,
                                           detail::ThreadCache& cache, detail::ResolvedPair& out) {
    using Kind = detail::ResolvedPair::Kind;
    out.o1 = o1;
    out.o2 = o2;
    out.class1 = class1;
    out.class2 = class2;
    if (class1 == dTriMeshClass || class2 == dTriMeshClass) return detail::resolveMeshPair(settings, cache, out);
    if (detail::isRoundClass(class1) || detail::isRoundClass(class2)) return resolveRound(settings, cache, out);
    if (class1 == dPlaneClass || class2 == dPlaneClass) {
        // The plane is always the core's B; the core's A is o2 when o1 is the plane.
        const bool planeFirst = class1 == dPlaneClass;
        if (planeFirst && class2 == dPlaneClass) misuse("gdc::ode::collide: plane–plane is not a supported pair");
        out.flip = planeFirst;
        dGeomID body = planeFirst ? o2 : o1;
        readPoseInto(body, out.pose1());
        bool unregistered = false;
        out.polytope1 = polytopeFor(body, planeFirst ? class2 : class1, out.pose1(), settings, cache, unregistered);
        if (!out.polytope1) {
            out.kind = Kind::Ode;
            return !unregistered;
        }
        out.plane = &planeOf(planeFirst ? o1 : o2, cache);
        out.kind = Kind::PolytopePlane;
        return true;
    }
    readPoseInto(o1, out.pose1());
    readPoseInto(o2, out.pose2());
    bool unregistered = false;
    out.polytope1 = polytopeFor(o1, class1, out.pose1(), settings, cache, unregistered);
    out.polytope2 = polytopeFor(o2, class2, out.pose2(), settings, cache, unregistered);
    if (!out.polytope1 || !out.polytope2) {
        out.kind = Kind::Ode;
        return !unregistered;
    }
    out.flip = comesFirst(out.pose2().position, o2, out.pose1().position, o1);
    out.kind = Kind::Polytopes;
    return true;
}

[[gnu::always_inline]] inline int collidePolytopeWithPlane(const detail::ResolvedPair& pair, int maxContacts, dContactGeom* contact, int skip,
                             const Settings& settings, detail::ThreadCache& cache, const CacheSource& pairCache) {
    const bool planeFirst = pair.flip;
    dGeomID o1 = pair.o1, o2 = pair.o2;
    const Polytope& polytope = *pair.polytope1;
    const Pose& pose = pair.pose1();
    const detail::ThreadCache::PlaneSlot& plane = *pair.plane;
    const Manifold& manifold = collideLimited(settings, maxContacts, [&](const Settings& pairSettings) -> const Manifold& {
        return queryThrough(
            pairCache, o1, o2, cache.scratch, cache.carried,
            [&](Manifold& out) {
                queryInto(gdc::detail::Shape::of(polytope), pose, planeShape(plane), kWorld, pairSettings, cache, out);
            },
            [&](PairCache& entry, Manifold& carried) -> const Manifold& {
                return gdc::collideInto(polytope, pose, plane.halfSpace, pairSettings, entry, carried);
            });
    });
    if (manifold.empty()) return 0;
    // The core's own answer is checked finite; a carried one (in cache.carried) is not.
    return detail::writeContacts(manifold, planeFirst, polytope.radius(), maxContacts, settings.contactOrder,
                                 detail::loadedDepthOf(settings, polytope.radius(), 0.0), o1, o2, contact, skip,
                                 &manifold != &cache.carried);
}

[[gnu::always_inline]] inline int collidePolytopes(const detail::ResolvedPair& pair, int maxContacts, dContactGeom* contact, int skip,
                     const Settings& settings, detail::ThreadCache& cache, const CacheSource& pairCache) {
    dGeomID o1 = pair.o1, o2 = pair.o2;
    const Polytope& polytope1 = *pair.polytope1;
    const Polytope& polytope2 = *pair.polytope2;
    const Pose& pose1 = pair.pose1();
    const Pose& pose2 = pair.pose2();
    const bool swapped = pair.flip;
    const Manifold& manifold = collideLimited(settings, maxContacts, [&](const Settings& pairSettings) -> const Manifold& {
        return queryThrough(
            pairCache, o1, o2, cache.scratch, cache.carried,
            [&](Manifold& out) {
                const gdc::detail::Shape shape1 = gdc::detail::Shape::of(polytope1), shape2 = gdc::detail::Shape::of(polytope2);
                swapped ? queryInto(shape2, pose2, shape1, pose1, pairSettings, cache, out)
                        : queryInto(shape1, pose1, shape2, pose2, pairSettings, cache, out);
            },
            [&](PairCache& entry, Manifold& carried) -> const Manifold& {
                return swapped ? gdc::collideInto(polytope2, pose2, polytope1, pose1, pairSettings, entry, carried)
                               : gdc::collideInto(polytope1, pose1, polytope2, pose2, pairSettings, entry, carried);
            });
    });
    if (manifold.empty()) return 0;
    // The core's own answer (box–box or general) is checked finite, as the half-space one.
    return detail::writeContacts(manifold, swapped, polytope1.radius() + polytope2.radius(), maxContacts,
                                 settings.contactOrder,
                                 detail::loadedDepthOf(settings, polytope1.radius(), polytope2.radius()), o1, o2,
                                 contact, skip, &manifold != &cache.carried);
}

[[gnu::always_inline]] inline int collideResolvedPair(const detail::ResolvedPair& pair, int maxContacts, dContactGeom* contact, int skip,
                        const Settings& settings, detail::ThreadCache& cache, const CacheSource& pairCache) {
    switch (pair.kind) {
        case detail::ResolvedPair::Kind::Polytopes:
            return collidePolytopes(pair, maxContacts, contact, skip, settings, cache, pairCache);
        case detail::ResolvedPair::Kind::PolytopePlane:
            return collidePolytopeWithPlane(pair, maxContacts, contact, skip, settings, cache, pairCache);
        case detail::ResolvedPair::Kind::Round: return collideRound(pair, maxContacts, contact, skip, settings, cache);
        case detail::ResolvedPair::Kind::Mesh: return detail::collideMeshPair(pair, maxContacts, contact, skip, settings);
        case detail::ResolvedPair::Kind::Ode: break;
    }
    return detail::collideWithOde(pair.o1, pair.class1, pair.o2, pair.class2, maxContacts, contact, skip);
}

int maxContactsOf(int flags, const Settings& settings) {
    return std::min({flags & 0xffff, settings.maxContacts, kMaxManifoldPoints});
}

// Inline, as the guard around it and its one caller's lambda (collideGuarded): one frame for the
// whole call, where a call with eight arguments (two on the stack) would cost every pair; GCC
// left the lambda a function of its own once this was inlined into it, hence the attributes
// there too.
[[gnu::always_inline]] inline int collideChecked(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip,
                                                 const Settings& settings, detail::ThreadCache& cache,
                                                 const CacheSource& pairCache) {
    const int maxContacts = maxContactsOf(flags, settings);
    if (maxContacts <= 0 || o1 == o2) return 0;
    if (!o1 || !o2) misuse("gdc::ode::collide got a null geom");
    if (!contact) misuse("gdc::ode::collide got a null contact array");
    if (skip < static_cast<int>(sizeof(dContactGeom)))
        misuse("gdc::ode::collide: skip (" + std::to_string(skip) +
               ") is smaller than sizeof(dContactGeom)");

    detail::ResolvedPair pair;
    if (!resolve(o1, dGeomGetClass(o1), o2, dGeomGetClass(o2), settings, cache, pair))
        detail::reportPlainConvex();  // then collided by ODE's convex collider (kind Ode)
    return collideResolvedPair(pair, maxContacts, contact, skip, settings, cache, pairCache);
}

// What no exception may cross: ODE is C. A failure becomes a dMessage and no contacts.
template <class Body>
[[gnu::always_inline]] inline int guarded(Body body) noexcept {
    try {
        return body();
    } catch (const InvalidInput& error) {  // its message already starts with "gdcontact: "
        dMessage(d_ERR_UNKNOWN, "%s (pair skipped)", error.what());
    } catch (const std::exception& error) {
        dMessage(d_ERR_UNKNOWN, "gdcontact: %s (pair skipped)", error.what());
    } catch (...) {
        dMessage(d_ERR_UNKNOWN, "gdcontact: unknown failure (pair skipped)");
    }
    return 0;
}

// The installed settings (`settings` null) or the caller's; the pair's cache `given`, or else one
// from the table when this call can take its lease. ODE is C: no exception may cross back into it.
int collideGuarded(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip, const Settings* settings,
                   PairCache* given = nullptr) {
    detail::ThreadCache& cache = detail::threadCache();
    if (!settings) {
        static const Settings defaults;
        settings = &defaults;
        try {
            settings = &detail::installedSettings(cache);
        } catch (...) {  // a lock failure; the defaults are always valid
        }
    }
    return guarded([&]() __attribute__((always_inline)) {
        // One call of collideChecked (inlined here, see there), with the table's lease when one is
        // taken: an optional, alive until the call is over.
        std::optional<detail::PairCacheTable::Lease> lease;
        CacheSource source{given, nullptr};
        // The table's switch first: with the cache off, not even the ODE getters of the rule.
        if (!given && detail::pairCacheTable().enabled() && detail::pairCacheWorthIt(o1, o2, *settings))
            source.lease = &lease.emplace(detail::pairCacheTable());
        return collideChecked(o1, o2, flags, contact, skip, *settings, cache, source);
    });
}

int collideInstalled(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip) noexcept {
    return collideGuarded(o1, o2, flags, contact, skip, nullptr);
}

}  // namespace

bool detail::resolvePair(dGeomID o1, int class1, dGeomID o2, int class2, const Settings& settings, ThreadCache& cache,
                         ResolvedPair& out) {
    return resolve(o1, class1, o2, class2, settings, cache, out);
}

int detail::collideResolved(const ResolvedPair& pair, int flags, dContactGeom* contact, int skip,
                            const Settings& settings, ThreadCache& cache, PairCache* pairCache) noexcept {
    const int maxContacts = maxContactsOf(flags, settings);
    if (maxContacts <= 0) return 0;
    return guarded([&] {
        return collideResolvedPair(pair, maxContacts, contact, skip, settings, cache, CacheSource{pairCache, nullptr});
    });
}

int detail::collideWithPairCache(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip,
                                 PairCache* cache) noexcept {
    return collideGuarded(o1, o2, flags, contact, skip, nullptr, cache);
}

void install(const Settings& settings) {
    if (!detail::odeIsInitialized())
        throw InvalidInput("gdc::ode::install() was called while ODE is not initialised: call dInitODE2(0) "
                           "first (and again after dCloseODE()), then install()");
    if (const std::string problem = detail::odeConfigurationProblem(); !problem.empty())
        throw InvalidInput("gdc::ode::install(): " + problem);
    gdc::validate(settings);
    detail::captureOdeColliders();  // before the overrides below replace ODE's colliders
    // A new session (or new settings) says its one-time messages again.
    detail::resetConvexMessages();
    detail::setInstalledSettings(settings);
    for (int class1 = 0; class1 < dGeomNumClasses; ++class1)
        for (int class2 = class1; class2 < dGeomNumClasses; ++class2)
            if (detail::isGdcontactPair(class1, class2)) dSetColliderOverride(class1, class2, &collideInstalled);
}

int collide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip,
            const Settings& settings) {
    return collideGuarded(o1, o2, flags, contact, skip, &settings);
}

int collide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip) {
    return collideGuarded(o1, o2, flags, contact, skip, nullptr);
}

}  // namespace gdc::ode

#include "convex_registry.hpp"
#include "ode_real.hpp"

#include "free_hook.hpp"

#include <gdcontact/ode.hpp>

#include <cmath>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <utility>

namespace gdc::ode::detail {
namespace {

struct ConvexEntry {
    std::shared_ptr<ConvexRecord> record;
    // False when ODE's free handler was replaced behind our back while this entry existed: the
    // geom may have been freed unseen and its address reused, so the entry is checked against the
    // geom's own AABB before use.
    bool trusted = true;
};

struct Registry {
    std::shared_mutex mutex;
    std::unordered_map<const void*, ConvexEntry> convexes;
    // convexes.size(), readable without the lock: the free hook skips the lock for every freed
    // block while no hull is registered.
    std::atomic<std::size_t> count{0};
};

// Intentionally never destroyed: ODE may free geoms from static destructors that run after ours
// would have, and the free hook must still find the registry then.
Registry& registry() {
    static Registry* const instance = new Registry;
    return *instance;
}

// Whether the geom at a distrusted entry's address is still the convex that entry describes:
// its ODE AABB (computed by ODE from the points it was given) must match the hull's at its pose.
bool matchesGeom(const Polytope& hull, dGeomID geom) {
    if (dGeomGetClass(geom) != dConvexClass) return false;
    return matchesAabb(hull, poseOf(geom), geom, 32, 3);
}

}  // namespace

std::atomic<std::uint64_t> convexesForgotten{0};

void forgetConvex(const void* address) noexcept {
    Registry& r = registry();
    if (r.count.load(std::memory_order_relaxed) == 0) return;
    std::shared_ptr<ConvexRecord> released;  // destroyed after the lock is dropped
    try {
        {  // most freed blocks are no convex geom: those take the lock shared only
            std::shared_lock lock(r.mutex);
            if (r.convexes.count(address) == 0) return;
        }
        std::unique_lock lock(r.mutex);
        auto found = r.convexes.find(address);
        if (found == r.convexes.end()) return;
        released = std::move(found->second.record);
        r.convexes.erase(found);
        r.count.fetch_sub(1, std::memory_order_relaxed);
        convexesForgotten.fetch_add(1, std::memory_order_release);  // every thread's AABB memo is void
    } catch (...) {  // a lock failure: the entry stays, distrusted by the AABB check
    }
}

void distrustRegisteredConvexes() {
    Registry& r = registry();
    std::unique_lock lock(r.mutex);
    for (auto& entry : r.convexes) entry.second.trusted = false;
    convexesForgotten.fetch_add(1, std::memory_order_release);  // no memo may answer for them now
}

dGeomID createRegisteredConvex(dSpaceID space, std::shared_ptr<ConvexRecord> record) {
    ensureFreeHook();
    dGeomID geom = dCreateConvex(space, record->planes.data(),
                                 static_cast<unsigned>(record->planes.size() / 4),
                                 record->points.data(),
                                 static_cast<unsigned>(record->points.size() / 3),
                                 record->polygons.data());
    Registry& r = registry();
    std::shared_ptr<ConvexRecord> replaced;  // a stale entry at a reused address (hook was away)
    try {
        std::unique_lock lock(r.mutex);
        ConvexEntry& entry = r.convexes[geom];
        if (entry.record)
            replaced = std::move(entry.record);
        else
            r.count.fetch_add(1, std::memory_order_relaxed);
        entry.record = std::move(record);
        entry.trusted = true;
    } catch (...) {
        dGeomDestroy(geom);  // ODE must not keep pointers into the record's arrays
        throw;
    }
    return geom;
}

std::shared_ptr<const Polytope> registeredConvex(dGeomID geom) {
    Registry& r = registry();
    if (r.count.load(std::memory_order_relaxed) == 0) return nullptr;
    std::shared_ptr<ConvexRecord> record;
    bool trusted;
    {
        std::shared_lock lock(r.mutex);
        auto found = r.convexes.find(geom);
        if (found == r.convexes.end()) return nullptr;
        record = found->second.record;
        trusted = found->second.trusted;
    }
    // Our hook may have been replaced since the geom was registered: then nothing told us about
    // frees in between, and the address may now hold a different geom.
    // A mismatch is reported as "not ours" but the entry is kept: should the check ever be wrong
    // about a live geom, ODE still points into the entry's arrays. A stale entry is replaced when
    // createConvex reuses its address.
    if (!trusted || !freeHookActive()) {
        if (!matchesGeom(*record->polytope, geom)) return nullptr;
    }
    return record->polytope;
}

const Polytope* borrowedConvex(ThreadCache::GeomMemo& memo, dGeomID geom) {
    // With another free handler in front of ours, frees go unseen and an address may now hold
    // another geom: every lookup then takes registeredConvex's checked path.
    // (The registry keeps holding the hull after the temporary shared_ptr is gone.)
    if (!freeHookActive()) return registeredConvex(geom).get();
    // The memo: a trusted hull found for this address while no convex was forgotten since. The
    // geom is alive (it is being collided), and the registered geom at this address could only
    // have been replaced after a free the hook saw, which advances the generation.
    const std::uint64_t generation = convexesForgotten.load(std::memory_order_acquire);
    if (memo.hull && memo.hullGeneration == generation) return memo.hull;
    Registry& r = registry();
    if (r.count.load(std::memory_order_relaxed) == 0) return nullptr;
    const Polytope* hull;
    bool trusted;
    {
        std::shared_lock lock(r.mutex);
        auto found = r.convexes.find(geom);
        if (found == r.convexes.end()) return nullptr;
        hull = found->second.record->polytope.get();
        trusted = found->second.trusted;
    }
    if (!trusted) return matchesGeom(*hull, geom) ? hull : nullptr;  // checked each time
    memo.hull = hull;
    memo.hullGeneration = generation;  // the generation read before the lookup
    return hull;
}

std::size_t registeredConvexCount() { return registry().count.load(); }

bool matchesAabb(const Polytope& hull, const Pose& pose, dGeomID geom, int bruteForceLimit, int axes) {
    // The world AABB of the hull: along each world axis, the support of the hull in the local
    // direction the axis has (a row of the rotation).
    Vec3 lower, upper;
    for (int axis = 0; axis < axes; ++axis) {
        const Vec3 direction = pose.rotation.row(axis).transpose();
        const Vec3& top = hull.vertices()[hull.supportVertex(direction, bruteForceLimit)];
        const Vec3& bottom = hull.vertices()[hull.supportVertex(-direction, bruteForceLimit)];
        upper[axis] = direction.dot(top) + pose.position[axis];
        lower[axis] = direction.dot(bottom) + pose.position[axis];
    }
    dReal box[6];
    dGeomGetAABB(geom, box);
    // ODE computed the box in dReal: a single-precision one is off by float rounding (ode_real.hpp).
    const double tolerance = inputRelativeTolerance(1e-9) * (hull.radius() + pose.position.norm()) + 1e-300;
    for (int axis = 0; axis < axes; ++axis) {
        if (!(std::abs(static_cast<double>(box[2 * axis]) - lower[axis]) <= tolerance)) return false;
        if (!(std::abs(static_cast<double>(box[2 * axis + 1]) - upper[axis]) <= tolerance)) return false;
    }
    return true;
}

}  // namespace gdc::ode::detail

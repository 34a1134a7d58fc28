// The hulls of createConvex geoms, by geom address. ODE 0.16.2 has no getter for a dConvex's data,
// so the hull of a createConvex geom is found by the geom's address; and no geom-destroy callback,
// so the registry learns of a destroyed geom through ODE's free handler (free_hook).
//
// A std::unordered_map under a std::shared_mutex, with a per-thread memo in front for collide():
// the lock and the map's probe are a measurable part of a spaceCollide step (docs/ode.md, "The
// hull registry"); the memo answers
// a geom seen before in ~10, with no lock and no shared write, while no hull has been forgotten
// since. It replaced a lock-free index with hazard pointers (~250 lines).
#pragma once

#include "thread_cache.hpp"

#include <gdcontact/polytope.hpp>

#include <ode/ode.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace gdc::ode::detail {

/// What gdcontact keeps for one createConvex geom.
struct ConvexRecord {
    std::shared_ptr<const Polytope> polytope;
    // The arrays handed to dCreateConvex. ODE keeps only pointers to them, so they must live
    // exactly as long as the geom: the record is dropped when ODE frees the geom's memory.
    std::vector<dReal> planes;
    std::vector<dReal> points;
    std::vector<unsigned> polygons;
};

/// Creates the dConvex for `record` (whose arrays must be filled) in `space` and registers it.
dGeomID createRegisteredConvex(dSpaceID space, std::shared_ptr<ConvexRecord> record);

/// The hull of a createConvex geom; nullptr for a geom gdcontact did not create.
std::shared_ptr<const Polytope> registeredConvex(dGeomID geom);

/// The hull of a createConvex geom for collide(): borrowed, not shared. It stays valid while the
/// geom lives, since a hull is released only when ODE frees its geom, and a geom may not be
/// destroyed while it is being collided. nullptr for a geom gdcontact did not create.
/// Answered from the thread's memo of the geom (`memo`, geomMemo(cache, geom)) when it can be,
/// else from the registry.
const Polytope* borrowedConvex(ThreadCache::GeomMemo& memo, dGeomID geom);

/// Number of live registered convex geoms.
std::size_t registeredConvexCount();

/// For the free hook: forgets the hull of the geom at `address` if it has one (its memory is
/// being freed). Never throws.
void forgetConvex(const void* address) noexcept;

/// For the free hook, when it is put back in front of another handler: frees may have gone unseen
/// meanwhile, so every hull registered until now is checked against its geom's AABB before use.
void distrustRegisteredConvexes();

/// Advanced whenever a registered convex is forgotten (its geom was freed) or the registered
/// convexes are distrusted: the per-thread memos (ThreadCache::GeomMemo) taken before
/// are void.
extern std::atomic<std::uint64_t> convexesForgotten;

/// Whether the geom's AABB (which ODE computes from the points it holds) is that of `hull` at
/// `pose` (within rounding), along the first `axes` world axes (1: x only, two support queries;
/// 3: the whole box). False after dGeomSetConvex gave the geom other points.
bool matchesAabb(const Polytope& hull, const Pose& pose, dGeomID geom, int bruteForceLimit, int axes);

}  // namespace gdc::ode::detail

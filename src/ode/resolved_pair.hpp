// One geom pair as the core takes it: everything collide() reads from ODE and from the adapter's
// caches before the query (classes, the polytopes, poses, the plane, which geom is the core's A).
// gdc::ode::collide resolves its pair and collides it at once; spaceCollide resolves each of its
// pairs once, on the thread running ODE's broad phase (which needs the classes and the hull lookup
// anyway to tell gdcontact's pairs from ODE's), and hands the resolved pair to whichever thread
// collides it.
#pragma once

#include "thread_cache.hpp"
#include "contact/pair_table.hpp"

#include <gdcontact/pair_cache.hpp>

#include <ode/ode.h>

namespace gdc::ode::detail {

struct ResolvedPair {
    enum class Kind : unsigned char {
        Polytopes,      // box or known convex, both
        PolytopePlane,  // box or known convex against a plane
        Round,          // a sphere, capsule or cylinder against a body or a plane (round_geoms.hpp)
        Mesh,           // a box, known convex, capsule or cylinder against a trimesh (trimesh_geoms.hpp)
        Ode,            // a convex geom whose hull gdcontact does not know: ODE's collider
    };
    dGeomID o1 = nullptr, o2 = nullptr;
    int class1 = 0, class2 = 0;
    Kind kind = Kind::Ode;
    // Polytopes and Round: the core's A is o2 (the pair is ordered by position; a plane is always
    // the core's B). PolytopePlane: o1 is the plane. Mesh: o1 is the trimesh (the other geom in
    // polytope1, or kind1 and round1, and pose1; the trimesh's pose in pose2).
    bool flip = false;
    const Polytope* polytope1 = nullptr;  // o1's (PolytopePlane: the non-plane geom's), geom frame
    const Polytope* polytope2 = nullptr;  // o2's (Polytopes only)
    // Round: each geom's kind (a plane's HalfSpace), a curved one's size, a polytope's in
    // polytope1/polytope2 by geom; the poses by geom (a plane's unused).
    gdc::detail::ShapeKind kind1 = gdc::detail::ShapeKind::HalfSpace, kind2 = gdc::detail::ShapeKind::HalfSpace;
    gdc::detail::RoundShape round1, round2;
    // Likewise, written by resolvePair (pose2 only for Polytopes). Not default-initialised: a
    // default Pose is 12 stores, twice on every gdc::ode::collide call.
    Pose& pose1() { return poses[0].pose; }
    Pose& pose2() { return poses[1].pose; }
    const Pose& pose1() const { return poses[0].pose; }
    const Pose& pose2() const { return poses[1].pose; }
    // PolytopePlane: the plane. The resolving thread's cache slot, valid until that thread looks up
    // kPlaneSlots other planes: a pair handed to another thread points to a copy.
    const ThreadCache::PlaneSlot* plane = nullptr;

private:
    union UninitialisedPose {
        UninitialisedPose() {}
        Pose pose;
    };
    UninitialisedPose poses[2];
};

/// Resolves (o1, o2), a pair of classes gdcontact collides (isGdcontactPair). The box polytopes are borrowed from the thread's cache (see ThreadCache::pinnedBoxes
/// for keeping them beyond kBorrowedBoxSizes lookups). False (kind Ode) when a convex geom is not
/// one gdcontact created (a plain dCreateConvex geom). Throws on a failed allocation.
bool resolvePair(dGeomID o1, int class1, dGeomID o2, int class2, const Settings& settings, ThreadCache& cache,
                 ResolvedPair& out);

/// gdc::ode::collide of a resolved pair with `settings` and the pair's cache `pairCache` (which
/// the caller holds through its lease; nullptr: none). Never throws (a failure is a dMessage and
/// no contacts).
int collideResolved(const ResolvedPair& pair, int flags, dContactGeom* contact, int skip, const Settings& settings,
                    ThreadCache& cache, PairCache* pairCache) noexcept;

}  // namespace gdc::ode::detail

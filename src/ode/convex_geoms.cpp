// dConvex geoms after install(): which ones gdcontact knows (knownHull), and ODE's own collider for
// the others (collideWithOde), with one message per kind (convex_geoms.hpp).
#include "convex_geoms.hpp"

#include "convex_registry.hpp"
#include "ode_internals.hpp"
#include "ode_real.hpp"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace gdc::ode::detail {
namespace {

// One message per kind and process: a scene full of plain convexes must not flood the log.
void sayOnce(std::atomic<bool>& said, const char* message) {
    if (!said.exchange(true, std::memory_order_relaxed)) dMessage(d_ERR_UNKNOWN, "%s", message);
}
std::atomic<bool> saidPlainConvex{false}, saidSetConvex{false}, saidNoOdeCollider{false};

[[gnu::cold, gnu::noinline]] void reportSetConvex() {
    sayOnce(saidSetConvex,
            "gdcontact: a gdc::ode::createConvex geom was given other data with dGeomSetConvex (its bounding "
            "box no longer matches its hull); gdcontact no longer knows its shape and leaves its pairs to "
            "ODE's own convex collider. Create a new geom with gdc::ode::createConvex instead of calling "
            "dGeomSetConvex. (Said once.)");
}

// Whether the geom's AABB along world x — ODE computes it from the points it holds — is the
// hull's at `pose`: two support queries, warm-started where this thread found them last for this
// geom. Only x: the whole box is a measurable part of a hull–hull call, and
// other data almost never has the same x extent at every pose a geom takes, so a change is seen
// at the latest when the geom turns. (matchesAabb checks the whole box where trust is lost.)
// `hint`: the thread's memo of the geom (geomMemo).
bool matchesXExtent(const Polytope& hull, const Pose& pose, dGeomID geom, int bruteForceLimit,
                    detail::ThreadCache::GeomMemo& hint) {
    dReal box[6];
    dGeomGetAABB(geom, box);
    // Everything the check below reads besides the hull: compared by their bytes with the inputs of
    // this geom's last check that passed (a geom in several pairs of one step: checked once).
    const double inputs[8] = {pose.rotation(0, 0), pose.rotation(0, 1), pose.rotation(0, 2), pose.position.x(),
                              pose.position.y(),   pose.position.z(),   box[0],              box[1]};
    static_assert(sizeof(inputs) == sizeof(hint.verifiedInputs), "the memo holds every input");
    const std::uint64_t generation = detail::convexesForgotten.load(std::memory_order_acquire);
    if (hint.verifiedHull == &hull && hint.verifiedGeneration == generation &&
        std::memcmp(inputs, hint.verifiedInputs, sizeof inputs) == 0)
        return true;
    hint.verifiedHull = nullptr;
    const Vec3 direction = pose.rotation.row(0).transpose();
    // With a hint, climb from it (a few neighbours) even where a cold query would scan every vertex.
    hint.upper = hull.supportVertex(direction, hint.upper >= 0 ? 0 : bruteForceLimit, hint.upper);
    hint.lower = hull.supportVertex(-direction, hint.lower >= 0 ? 0 : bruteForceLimit, hint.lower);
    const double upper = direction.dot(hull.vertices()[hint.upper]) + pose.position.x();
    const double lower = direction.dot(hull.vertices()[hint.lower]) + pose.position.x();
    // ODE computed the box in dReal: a single-precision one is off by float rounding (ode_real.hpp).
    const double tolerance = detail::inputRelativeTolerance(1e-9) * (hull.radius() + pose.position.norm()) + 1e-300;
    const bool matches = std::abs(static_cast<double>(box[0]) - lower) <= tolerance &&
                         std::abs(static_cast<double>(box[1]) - upper) <= tolerance;
    if (matches) {
        hint.verifiedHull = &hull;
        hint.verifiedGeneration = generation;
        std::memcpy(hint.verifiedInputs, inputs, sizeof inputs);
    }
    return matches;
}

}  // namespace

[[gnu::cold, gnu::noinline]] void reportPlainConvex() {
    sayOnce(saidPlainConvex,
            "gdcontact: a dConvex made with plain dCreateConvex is collided by ODE's own convex collider "
            "where this ODE lets it be reached (docs/ode.md). ODE gives no access to a dConvex's data, so gdcontact "
            "cannot collide it; for gdcontact's contacts create it with gdc::ode::createConvex(space, planes, "
            "planeCount, points, pointCount, polygons) — the same arguments as dCreateConvex. (Said once.)");
}


// The pair (o1, o2), one of them a dConvex gdcontact does not know, collided by ODE's collider
// for it, as dCollide would (mirrored when ODE's table has the pair the other way round). Only
// valid contacts are kept: libccd gives a zero normal for exactly touching shapes, which would
// make ODE abort.
int collideWithOde(dGeomID o1, int class1, dGeomID o2, int class2, int maxContacts, dContactGeom* contact,
                   int skip) {
    const detail::OdeColliders& ode = detail::odeColliders();
    // ODE's function takes the convex first (or, convexSecond, the other geom first): `reverse`
    // when o1, o2 come the other way round.
    const bool convexFirst = class1 == dConvexClass;
    const detail::OdeCollider* collider = ode.against(convexFirst ? class2 : class1);
    bool reverse = !convexFirst;
    if (collider && collider->convexSecond) reverse = !reverse;
    // ODE's own collider answers nothing for this pair kind (ODE without libccd): neither does this.
    if (collider && collider->fallback == detail::OdeFallback::OdeGivesNone) return 0;
    dColliderFn* function = collider ? collider->function : nullptr;
    if (!function) {
        sayOnce(saidNoOdeCollider,
                "gdcontact: this ODE does not export its own convex colliders (a static libode, or one built "
                "with hidden symbols), so after install() the pairs it takes over with a plain dCreateConvex "
                "geom get no contacts; create such geoms with gdc::ode::createConvex (docs/ode.md). (Said once.)");
        return 0;
    }
    const int count = reverse ? function(o2, o1, maxContacts, contact, skip)
                              : function(o1, o2, maxContacts, contact, skip);
    int kept = 0;
    char* bytes = reinterpret_cast<char*>(contact);
    for (int i = 0; i < std::min(count, maxContacts); ++i) {
        dContactGeom current = *reinterpret_cast<dContactGeom*>(bytes + static_cast<std::ptrdiff_t>(i) * skip);
        Vec3 normal(current.normal[0], current.normal[1], current.normal[2]);
        const double length = normal.norm();
        const bool valid = std::isfinite(length) && std::abs(length - 1.0) < 1e-3 &&
                           std::isfinite(current.depth) && std::isfinite(current.pos[0]) &&
                           std::isfinite(current.pos[1]) && std::isfinite(current.pos[2]);
        if (!valid) continue;
        if (reverse) normal = -normal;
        normal /= length;
        for (int axis = 0; axis < 3; ++axis) current.normal[axis] = normal[axis];
        current.depth = std::max<dReal>(current.depth, 0);
        current.g1 = o1;
        current.g2 = o2;
        current.side1 = -1;
        current.side2 = -1;
        *reinterpret_cast<dContactGeom*>(bytes + static_cast<std::ptrdiff_t>(kept) * skip) = current;
        ++kept;
    }
    return kept;
}


// The hull of a convex geom at `pose`, or nullptr when gdcontact does not know the geom's shape:
// a plain dCreateConvex geom (`unregistered` set), or a createConvex geom given other data by
// dGeomSetConvex (its AABB, which ODE computes from the points it holds, no longer matches the hull).
const Polytope* knownHull(dGeomID geom, const Pose& pose, const Settings& settings,
                                            detail::ThreadCache& cache, bool& unregistered) {
    detail::ThreadCache::GeomMemo& memo = detail::geomMemo(cache, geom);  // one search for both memos
    const Polytope* hull = detail::borrowedConvex(memo, geom);
    if (!hull) {
        unregistered = true;
        return nullptr;
    }
    if (!matchesXExtent(*hull, pose, geom, settings.bruteForceSupportLimit, memo)) {
        // A non-finite pose makes every AABB differ: the core reports it ("not finite").
        if (!pose.isFinite()) return hull;
        reportSetConvex();
        return nullptr;
    }
    return hull;
}


void resetConvexMessages() {
    saidPlainConvex.store(false, std::memory_order_relaxed);
    saidSetConvex.store(false, std::memory_order_relaxed);
    saidNoOdeCollider.store(false, std::memory_order_relaxed);
}

}  // namespace gdc::ode::detail

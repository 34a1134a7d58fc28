// The public queries of the adapter that read a geom or the pair cache's table, outside the
// collision path (gdc::ode::polytopeOf, poseOf, liveConvexCount and the pair cache's controls).
#include <gdcontact/ode.hpp>

#include "box_cache.hpp"
#include "convex_registry.hpp"
#include "geom_reading.hpp"
#include "pair_cache_table.hpp"
#include "round_geoms.hpp"

namespace gdc::ode {
namespace {

std::shared_ptr<const Polytope> boxPolytopeOf(dGeomID box) {
    dVector3 lengths;
    dGeomBoxGetLengths(box, lengths);
    return detail::boxPolytope(0.5 * lengths[0], 0.5 * lengths[1], 0.5 * lengths[2]);
}

Pose readPose(dGeomID geom) {
    Pose pose;
    detail::readPoseInto(geom, pose);
    return pose;
}

}  // namespace

std::shared_ptr<const Polytope> polytopeOf(dGeomID geom) {
    if (!geom) throw InvalidInput("gdc::ode::polytopeOf: null geom");
    switch (dGeomGetClass(geom)) {
        case dBoxClass: return boxPolytopeOf(geom);
        case dConvexClass: return detail::registeredConvex(geom);
        default: return nullptr;
    }
}

Pose poseOf(dGeomID geom) {
    if (!geom) throw InvalidInput("gdc::ode::poseOf: null geom");
    if (dGeomIsSpace(geom) || dGeomGetClass(geom) == dPlaneClass)
        throw InvalidInput("gdc::ode::poseOf: a plane or space has no pose");
    return readPose(geom);
}

bool handles(int class1, int class2) { return detail::isGdcontactPair(class1, class2); }

std::size_t liveConvexCount() { return detail::registeredConvexCount(); }

void setPairCacheEnabled(bool enabled) { detail::pairCacheTable().setEnabled(enabled); }

void setPairCacheCapacity(std::size_t entries) { detail::pairCacheTable().setCapacity(entries); }

void clearPairCache() { detail::pairCacheTable().clear(); }

PairCacheStats pairCacheStats() {
    const detail::PairCacheTable::Stats stats = detail::pairCacheTable().stats();
    return PairCacheStats{stats.entries, stats.capacity, stats.bytes, stats.repeated, stats.carried, stats.computed};
}

}  // namespace gdc::ode

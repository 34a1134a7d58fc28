// The manifold written out (collide_general.hpp: emitManifold, emitInLiftOrder): the lifted points
// of A's frame, ranked and reduced (reduction.hpp), mapped to the world.
#include "contact/collide_general.hpp"
#include "contact/reduction.hpp"

#include <algorithm>

namespace gdc::detail {

namespace {

// The manifold written out in world coordinates: the normal, and points[pick(i)] for i < count.
// Finite input can still overflow (a plane offset of 1e308, found by the fuzzer): refuse it rather
// than hand out an infinite or NaN contact. x·0 is 0 for every finite x and NaN otherwise: one
// test for all the coordinates written. emitManifold (ranked) and emitInLiftOrder (in lift order)
// share it, so both write the same bits.
template <class Pick>
[[gnu::always_inline]] inline void writeWorldManifold(const LiftedPoints& points, int count, Pick pick,
                                                      const Vec3& normal, const Pose& commonToWorld,
                                                      Manifold& manifold) {
    manifold.normal = commonToWorld.rotation * normal;
    manifold.pointCount = count;
    double nonFinite = 0;
    for (int i = 0; i < count; ++i) {
        const LiftedPoint& point = points[pick(i)];
        manifold.points[i] = {commonToWorld.apply(point.position), point.depth};
        nonFinite += (manifold.points[i].position * 0.0).sum() + point.depth * 0.0;
    }
    if (!(nonFinite == 0))
        throw InvalidInput("the contact overflows double precision (coordinates or offsets near 1e308)");
}

}  // namespace

void emitManifold(const LiftedPoints& points, const Vec3& normal, const Pose& commonToWorld, const Settings& settings,
                  double tolerance, const Vec3* centroids, int centroidCount, Manifold& manifold) {
    int chosen[kMaxManifoldPoints];
    const int maxCount = std::max(1, std::min(settings.maxContacts, kMaxManifoldPoints));
    const int total = static_cast<int>(points.size());
    // The bodies' centroids on the contact plane, for the centroid rule: needed only where points
    // are dropped.
    Vec2 planarCentroids[2];
    RankingRule rule{maxCount, settings.reductionHysteresis, tolerance,
                     commonToWorld.rotation.transpose() * identityDirection()};
    if (total > maxCount && maxCount >= 3 && centroidCount > 0) {
        Vec3 u, v;
        planeBasis(normal, u, v);
        for (int c = 0; c < std::min(centroidCount, 2); ++c)
            planarCentroids[c] = Vec2(centroids[c].dot(u), centroids[c].dot(v));
        rule.centroids = planarCentroids;
        rule.centroidCount = std::min(centroidCount, 2);
    }
    const int count = rankContacts(points, rule, chosen);
    writeWorldManifold(points, count, [&](int i) { return chosen[i]; }, normal, commonToWorld, manifold);
}

bool emitInLiftOrder(const LiftedPoints& points, const Vec3& normal, const Pose& commonToWorld, const Settings& settings,
                     Manifold& manifold) {
    // emitManifold's ranking keeps every point where there are at most maxCount (rankContacts);
    // then it only orders them.
    const int maxCount = std::max(1, std::min(settings.maxContacts, kMaxManifoldPoints));
    const int total = static_cast<int>(points.size());
    if (total > maxCount) return false;
    for (int i = 0; i < total; ++i)
        for (int j = i + 1; j < total; ++j)
            if (points[i].depth == points[j].depth) return false;
    writeWorldManifold(points, total, [](int i) { return i; }, normal, commonToWorld, manifold);
    return true;
}

}  // namespace gdc::detail

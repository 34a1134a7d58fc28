// collide() / collideInto() with a pair's cache: repeat the cached answer when nothing changed (exact), carry the
// cached contacts along when the pair moved less than Settings::manifoldReuseDistance (opt-in),
// query otherwise. The query itself is the pair table's (pair_table.hpp), as collide()'s; this file
// only decides whether to run it.
#include <gdcontact/collide.hpp>

#include "contact/pair_table.hpp"

#include <cstring>

namespace gdc {
namespace {

static_assert(sizeof(Pose) == 12 * sizeof(double), "a Pose is compared by its bits: it must have no padding");

bool sameBits(const Pose& x, const Pose& y) { return std::memcmp(&x, &y, sizeof(Pose)) == 0; }
bool sameBits(double x, double y) { return std::memcmp(&x, &y, sizeof(double)) == 0; }
bool sameBits(const Vec3& x, const Vec3& y) { return std::memcmp(x.data(), y.data(), 3 * sizeof(double)) == 0; }

// Largest distance of a vertex from the polytope's own origin: how far a turn of its frame by a
// rotation difference ΔR can move one of its points, at most ‖ΔR‖·reach.
double reach(const Polytope& polytope) { return polytope.centroid().norm() + polytope.radius(); }

// A bound on how far any point of a body moved between the frames `before` and `now` it is
// placed by: the point x (its own frame) moved by ΔR·x + Δt, at most ‖ΔR‖_F·reach + |Δt|.
double motion(const Pose& before, const Pose& now, double reachOfMoved) {
    return (now.position - before.position).norm() + (now.rotation - before.rotation).norm() * reachOfMoved;
}

// The cached contacts carried along with the bodies (Jolt's manifold reuse): each contact's point
// on A rides with A and its point on B with B; the normal turns with A; the depth is re-measured
// between the two carried points along it. Points that left the contact (depth below −margin) are
// dropped; false when none is left, so that the caller queries.
bool carry(const PairCache& cache, const Pose& poseA, const Pose& poseB, double margin, Manifold& out) {
    const Manifold& before = cache.manifold;
    out.featureA = before.featureA;
    out.featureB = before.featureB;
    const Vec3 normalInA = cache.poseA.rotation.transpose() * before.normal;
    out.normal = (poseA.rotation * normalInA).normalized();
    out.pointCount = 0;
    for (int i = 0; i < before.pointCount; ++i) {
        const ContactPoint& point = before.points[i];
        const Vec3 onA = poseA.apply(cache.poseA.applyInverse(point.position + 0.5 * point.depth * before.normal));
        const Vec3 onB = poseB.apply(cache.poseB.applyInverse(point.position - 0.5 * point.depth * before.normal));
        const double depth = (onA - onB).dot(out.normal);
        if (!(depth >= -margin)) continue;
        out.points[out.pointCount++] = {0.5 * (onA + onB), depth};
    }
    return out.pointCount > 0;
}

// The answer for a pair whose cache holds the same shapes and settings: the cache's own manifold
// (repeated), `carried`, or none (nullptr: query).
template <class Moved>
const Manifold* answerFromCache(PairCache& cache, const Pose& poseA, const Pose& poseB, const Settings& settings,
                                Moved moved, Manifold& carried) {
    if (sameBits(poseA, cache.poseA) && sameBits(poseB, cache.poseB)) {
        cache.answer = CacheAnswer::Repeated;
        return &cache.manifold;
    }
    // An empty cached answer is never carried: it says nothing of how near the pair came.
    if (!(settings.manifoldReuseDistance > 0) || cache.manifold.empty()) return nullptr;
    if (!(moved() <= settings.manifoldReuseDistance)) return nullptr;
    if (!carry(cache, poseA, poseB, settings.margin, carried)) return nullptr;
    cache.answer = CacheAnswer::Carried;
    return &carried;
}

// A full query (the pair table's cell) into the cache, which then describes it. Emptied first: it
// stays empty if the query throws.
const Manifold& queryInto(PairCache& cache, PairCache::Kind kind, const detail::Shape& a, const Pose& poseA,
                          const detail::Shape& b, const Pose& poseB, const Settings& settings) {
    cache.kind = PairCache::Kind::Empty;
    cache.answer = CacheAnswer::Computed;
    detail::collidePair(a, poseA, b, poseB, detail::PairQuery{settings}, cache.manifold);
    cache.kind = kind;
    return cache.manifold;
}

}  // namespace

const Manifold& collideInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                            const Settings& settings, PairCache& cache, Manifold& carried) {
    if (cache.kind == PairCache::Kind::Polytopes && cache.shapeA == a.fingerprint() &&
        cache.shapeB == b.fingerprint() && cache.settings == settings) {
        const Manifold* answer = answerFromCache(cache, poseA, poseB, settings, [&] {
            // B relative to A: its points in A's frame, before and now.
            return motion(cache.poseA.relative(cache.poseB), poseA.relative(poseB), reach(b));
        }, carried);
        if (answer) return *answer;
    }
    const Manifold& answer = queryInto(cache, PairCache::Kind::Polytopes, detail::Shape::of(a), poseA,
                                       detail::Shape::of(b), poseB, settings);
    cache.shapeA = a.fingerprint();
    cache.shapeB = b.fingerprint();
    cache.poseA = poseA;
    cache.poseB = poseB;
    cache.settings = settings;
    return answer;
}

const Manifold& collideInto(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings,
                            PairCache& cache, Manifold& carried) {
    static const Pose world;  // the half-space's frame: B does not move
    if (cache.kind == PairCache::Kind::HalfSpace && cache.shapeA == a.fingerprint() &&
        sameBits(cache.halfSpaceNormal, b.normal) && sameBits(cache.halfSpaceOffset, b.offset) &&
        cache.settings == settings) {
        const Manifold* answer = answerFromCache(cache, poseA, world, settings,
                                                 [&] { return motion(cache.poseA, poseA, reach(a)); }, carried);
        if (answer) return *answer;
    }
    cache.kind = PairCache::Kind::Empty;  // a bad pose or plane throws here: the cache is emptied too
    const detail::UnitHalfSpace plane = detail::enterHalfSpace(poseA, b);
    const Manifold& answer =
        queryInto(cache, PairCache::Kind::HalfSpace, detail::Shape::of(a), poseA, detail::Shape::of(plane), world, settings);
    cache.shapeA = a.fingerprint();
    cache.shapeB = 0;
    cache.poseA = poseA;
    cache.poseB = world;
    cache.halfSpaceNormal = b.normal;
    cache.halfSpaceOffset = b.offset;
    cache.settings = settings;
    return answer;
}

Manifold collide(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                 const Settings& settings, PairCache& cache) {
    Manifold carried;
    return collideInto(a, poseA, b, poseB, settings, cache, carried);
}

Manifold collide(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings,
                 PairCache& cache) {
    Manifold carried;
    return collideInto(a, poseA, b, settings, cache, carried);
}

}  // namespace gdc

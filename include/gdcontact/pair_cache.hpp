// The pair cache: what the last query of one pair learned, kept by the caller for that pair's next
// query. Box2D's b2SimplexCache is the model — the core stays pure and re-entrant, the caller owns
// one cache per pair and passes it in (the ODE adapter keeps one per geom pair, docs/ode.md).
#pragma once

#include <gdcontact/manifold.hpp>
#include <gdcontact/settings.hpp>
#include <gdcontact/types.hpp>

#include <cstdint>

namespace gdc {

/// How collide(..., PairCache&) answered.
enum class CacheAnswer : std::uint8_t {
    Computed,  ///< a full query (the cache was empty, for other shapes or settings, or the pair moved)
    Repeated,  ///< nothing moved: the cached answer, which is the query's bit for bit
    Carried,   ///< moved less than Settings::manifoldReuseDistance: the cached contacts carried along
};

/// One pair's cache. Default-constructed it is empty; a query fills it. It recognises the shapes by
/// Polytope::fingerprint(), the poses and half-space by their bits and the settings by every field,
/// so passing it with another pair is never wrong, only a full query. Copyable; not to be shared
/// by two threads at once (like the pair it belongs to).
struct PairCache {
    void clear() { kind = Kind::Empty; }
    bool empty() const { return kind == Kind::Empty; }
    CacheAnswer lastAnswer() const { return answer; }

    // ---- what the last full query saw and answered (read and written by collide() only) ----
    enum class Kind : std::uint8_t { Empty, Polytopes, HalfSpace };
    Kind kind = Kind::Empty;
    CacheAnswer answer = CacheAnswer::Computed;
    std::uint64_t shapeA = 0, shapeB = 0;  // fingerprints (shapeB: 0 for a half-space)
    Pose poseA, poseB;                     // poseB: identity for a half-space (B is the world)
    Vec3 halfSpaceNormal = Vec3::Zero();   // as given to collide(), bit for bit
    double halfSpaceOffset = 0;
    Settings settings;
    Manifold manifold;  // world frame, as returned
};

}  // namespace gdc

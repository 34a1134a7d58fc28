// The contact query of gdcontact: shapes and poses in, a value manifold out. Pure and re-entrant.
#pragma once

#include <gdcontact/manifold.hpp>
#include <gdcontact/pair_cache.hpp>
#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>
#include <gdcontact/shapes.hpp>

namespace gdc {

/// Contact manifold between two convex polytopes by the paper's three stages: growth-distance
/// normal, one Gauss-map feature per body, feature intersection in the contact plane.
/// Returns an empty manifold when the pair is separated by more than settings.margin.
/// Throws InvalidInput for non-finite poses.
GDCONTACT_API Manifold collide(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                 const Settings& settings = {});

/// Contact manifold between a convex polytope (A) and a solid half-space (B). The normal is
/// −halfSpace.normal (from A into B's solid, as above).
GDCONTACT_API Manifold collide(const Polytope& a, const Pose& poseA, const HalfSpace& b,
                 const Settings& settings = {});

/// Contact manifold between any two shapes (shapes.hpp: polytopes, spheres, capsules, cylinders, a
/// half-space), by the same three stages: the curved kinds bring their exact Gauss-map features (a
/// cylinder's cap is a disc, its side a segment; a capsule's side a segment with its radius; a
/// sphere a point with its radius), intersected exactly in the contact plane. Throws InvalidInput for
/// non-finite poses, sizes a shape refuses (shapes.hpp) and two half-spaces.
GDCONTACT_API Manifold collide(const ShapeRef& a, const Pose& poseA, const ShapeRef& b, const Pose& poseB,
                               const Settings& settings = {});

/// The same queries with the pair's cache (pair_cache.hpp): when neither pose, shape nor setting
/// changed since the query that filled it, its answer is returned without a query — the same
/// manifold bit for bit. With Settings::manifoldReuseDistance > 0, a pair that moved less than that
/// (every point of B relative to A) gets the cached contacts carried along with the bodies, their
/// depths re-measured. Otherwise a full query, which then fills the cache. cache.lastAnswer() says
/// which. Throws as the queries above (the cache is then emptied).
GDCONTACT_API Manifold collide(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                               const Settings& settings, PairCache& cache);
GDCONTACT_API Manifold collide(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings,
                               PairCache& cache);

/// As the two above, answering by reference instead of by value: the cache's own manifold (a full
/// query or a repeat) or `carried` (a carried answer). Valid until the cache or `carried` changes.
/// For callers that read the answer once (the ODE adapter): a Manifold is 0.6 KB, and its copies
/// were a third of a repeated answer's cost.
GDCONTACT_API const Manifold& collideInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                                          const Settings& settings, PairCache& cache, Manifold& carried);
GDCONTACT_API const Manifold& collideInto(const Polytope& a, const Pose& poseA, const HalfSpace& b,
                                          const Settings& settings, PairCache& cache, Manifold& carried);

}  // namespace gdc

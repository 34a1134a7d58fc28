// The cells of the pair table for the curved kinds (round_pair.cpp): a sphere, a capsule or a
// cylinder against any body or a half-space, by the paper's stages on support functions.
#pragma once

#include "contact/pair_table.hpp"
#include "contact/pipeline.hpp"

namespace gdc::detail {

/// The pair's contacts written into `out`, A or B (or both) a curved kind, neither a half-space.
/// The points are ranked in full unless the query's order lets them be in lift order (emitRound).
/// Poses finite (collidePair checks).
void collideRoundInto(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, const PairQuery& query,
                      Manifold& out);
/// A curved kind A on the half-space B (the table mirrors the other order): A's feature for the
/// plane's normal lifted onto the plane (liftOntoPlane). `poseB` is unused: a half-space is placed
/// in the world.
void collideRoundOnPlaneInto(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB,
                             const PairQuery& query, Manifold& out);

}  // namespace gdc::detail

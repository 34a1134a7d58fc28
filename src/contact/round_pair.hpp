// The cells of the pair table for the curved kinds (round_pair.cpp): a sphere, a capsule or a
// cylinder against any body or a half-space, by the paper's stages on support functions.
#pragma once

#include "contact/pair_table.hpp"
#include "contact/pipeline.hpp"

namespace gdc::detail {

/// The pair's contacts written into `out`, A or B (or both) a curved kind; B may be a half-space
/// (A may not: the table mirrors that pair). The points are ranked in full whatever the query's
/// order (a permission the table's callers give, not a demand). Poses finite (collidePair checks).
void collideRoundInto(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, const PairQuery& query,
                      Manifold& out);

}  // namespace gdc::detail

// The hull's stage-1 hook: the growth distance of two small polytopes as the gauge of their
// Minkowski difference, by enumerating its facet normals (docs/algorithm.md, "The gauge"), where the
// general pipeline would run the GJK ray cast (growth_distance.hpp). Large hulls keep the ray cast:
// the enumeration's cost grows with the product of the edge counts.
#pragma once

#include "geometry/growth_distance.hpp"
#include "geometry/minkowski.hpp"

namespace gdc::detail {

/// Largest edge count of each polytope for which the enumeration runs (its tables are fixed arrays,
/// B's faces a 64-bit set), and largest product of the two edge counts: the edge pairs dominate the
/// enumeration's cost where the walk from the best face (hull_gauge.cpp) does not settle it. The
/// product is the measured crossover (bench/hull_gauge_crossover.cpp, instructions per growth
/// distance for two Fibonacci-sphere hulls, enumeration against ray cast): 324 pairs (8 vertices)
/// 3 831 against 7 094, 900 (12) 6 508 against 8 532, 1 296 (14) 8 675 against 9 441, 1 764 (16)
/// 10 883 against 10 002. Both give the same σ and facet (the enumeration exactly, the cast within
/// its tolerance), so this is a speed crossover, not a trade-off of the answer (hence no Setting).
constexpr int kHullGaugeMaxEdges = 64;
constexpr int kHullGaugeMaxEdgePairs = 1296;

/// Whether hullGrowth serves the pair: both polytopes small (above), and not both boxes (their closed
/// form, boxGrowth, is cheaper still). Inline: for a large hull it is all the hook costs.
inline bool hullGaugeApplies(const Polytope& a, const Polytope& b) {
    const auto edgesA = a.edges().size(), edgesB = b.edges().size();
    return edgesA <= kHullGaugeMaxEdges && edgesB <= kHullGaugeMaxEdges && edgesA * edgesB <= kHullGaugeMaxEdgePairs &&
           !(a.isBox() && b.isBox());
}

/// growthDistance(pair, settings, /*needWitnesses=*/false) by enumeration: the maximum of (m·d)/h_K(m)
/// over the facet normals m of K = (A − c_A) − (B − c_B) — A's face normals, B's face normals negated
/// and the cross products of the edge pairs whose arcs cross on the Gauss maps of A and −B — at
/// d = c_B − c_A. Valid, the normal (unit, A towards B; the normalised sum of the facets tied within
/// 1e-12, the middle of the cone a ray through an edge of K leaves by, as boxGrowth) and the growth;
/// no witnesses, no face-overlap bound (as the ray cast's answer).
GrowthDistance hullGrowth(const MinkowskiDifference& pair);

}  // namespace gdc::detail

// The hull's stage-1 hook: the growth distance of two small polytopes as the gauge of their
// Minkowski difference, by enumerating its facet normals (docs/algorithm.md, "The gauge"), where the
// general pipeline would run the GJK ray cast (growth_distance.hpp). Large hulls keep the ray cast:
// the enumeration's cost grows with the product of the edge counts.
#pragma once

#include "growth_distance.hpp"
#include "minkowski.hpp"

namespace gdc::detail {

/// Largest edge count of each polytope for which the enumeration runs, and largest product of the
/// two edge counts (the edge-pair tests dominate its cost). Measured with bench/callgrind_counts.py
/// (hull_hull/8, /16, /64 and box–hull, docs/algorithm.md): the enumeration costs less than the ray
/// cast up to the product stated here and more above it. Both give the same σ and facet (the
/// enumeration exactly, the cast within its tolerance), so this is a speed crossover, not a
/// trade-off of the answer.
constexpr int kHullGaugeMaxEdges = 64;
constexpr int kHullGaugeMaxEdgePairs = 2048;

/// Whether hullGrowth serves the pair: both polytopes small (above), and not both boxes (their closed
/// form, boxGrowth, is cheaper still).
bool hullGaugeApplies(const Polytope& a, const Polytope& b);

/// growthDistance(pair, settings, /*needWitnesses=*/false) by enumeration: the maximum of (m·d)/h_K(m)
/// over the facet normals m of K = (A − c_A) − (B − c_B) — A's face normals, B's face normals negated
/// and the cross products of the edge pairs whose arcs cross on the Gauss maps of A and −B — at
/// d = c_B − c_A. Valid, the normal (unit, A towards B; the normalised sum of the facets tied within
/// 1e-12, the middle of the cone a ray through an edge of K leaves by, as boxGrowth) and the growth;
/// no witnesses, no face-overlap bound (as the ray cast's answer).
GrowthDistance hullGrowth(const MinkowskiDifference& pair);

}  // namespace gdc::detail

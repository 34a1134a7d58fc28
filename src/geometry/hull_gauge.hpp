// The hull's stage-1 hook: the growth distance of two small polytopes as the gauge of their
// Minkowski difference, by enumerating its facet normals (docs/algorithm.md, "The gauge"), where the
// general pipeline would run the GJK ray cast (growth_distance.hpp). Large hulls keep the ray cast:
// the enumeration's cost grows with the product of the edge counts.
#pragma once

#include "geometry/growth_distance.hpp"
#include "geometry/minkowski.hpp"

#include <array>
#include <cmath>
#include <cstdint>

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

/// What hullGrowth found on its way that the later stages of the same query would search for again
/// (collide.cpp, GeneralPairHooks): the pair's overlap along each face normal it evaluated (A's face
/// normals n, B's turned into A's frame and negated, −R·n_B, both pointing from A towards B), and the
/// exit facet of K — a plane of A − B whose overlap bounds the penetration along any direction, the
/// depth certificate's candidate. An overlap is max m·A − min m·B from the same support values the
/// enumeration compared (a face's plane offset for its own body): equal to the support searches'
/// within rounding, not bit for bit.
struct HullGaugeCarry {
    static constexpr int kMaxFaces = 64;  // 2E/3 + 2 for E ≤ kHullGaugeMaxEdges
    std::uint64_t knownA = 0, knownB = 0;  // bit f: overlapA[f] / overlapB[f] was written
    std::array<double, kMaxFaces> overlapA, overlapB;
    bool exitKnown = false;
    Vec3 exitDirection = Vec3::Zero();  // the exit facet's normal, A towards B, not normalised
    double exitOverlap = 0;             // the pair's overlap along exitDirection (in its length's units)
    /// Each body's face whose facet of K had the largest ratio (m·d)/h_K(m) among that body's faces
    /// evaluated (−1: none): the face stage 2 proposes for that body's feature (faceIsSelected,
    /// gauss_map.hpp, proves it or the search runs) — on a resting pair the exit facet's face on its
    /// side and the nearly parallel face on the other.
    int faceA = -1, faceB = -1;
    /// A lower bound of the pair's overlap along every face normal of A and of −B (their searched
    /// overlaps, rounding included): stage 1's faceOverlapLowerBound, which spares the overhang check
    /// where it clears half the normal's overlap. −∞ where the enumeration did not reach the faces.
    double faceOverlapBound = -INFINITY;
    /// B's vertices in A's frame (pair.vertexB(i), bit for bit), as the enumeration placed them.
    std::array<Vec3, kMaxFaces> verticesB;
};

/// growthDistance(pair, settings, /*needWitnesses=*/false) by enumeration: the maximum of (m·d)/h_K(m)
/// over the facet normals m of K = (A − c_A) − (B − c_B) — A's face normals, B's face normals negated
/// and the cross products of the edge pairs whose arcs cross on the Gauss maps of A and −B — at
/// d = c_B − c_A. Valid, the normal (unit, A towards B; the normalised sum of the facets tied within
/// 1e-12, the middle of the cone a ray through an edge of K leaves by, as boxGrowth) and the growth;
/// no witnesses, no face-overlap bound (as the ray cast's answer).
/// With `carry`, also what the enumeration found on the way (HullGaugeCarry); the answer is the same.
GrowthDistance hullGrowth(const MinkowskiDifference& pair, HullGaugeCarry* carry = nullptr);

}  // namespace gdc::detail

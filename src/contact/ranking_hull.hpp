// The planar hull arithmetic of the ranking (reduction.cpp) and its centroid rule
// (ranking_hull.cpp): convex hulls and insertions of a few points, areas, containment, and the
// leader of a stream of values. Internal to the reduction.
#pragma once

#include "contact/reduction.hpp"

#include <array>
#include <cmath>
#include <cstdint>

namespace gdc::detail {

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

constexpr int kMaxHull = 2 * kMaxManifoldPoints + 4;
static_assert(kMaxHull <= 64, "the edges a point sees are bits of a 64-bit mask");

// Convex hull (counter-clockwise, monotone chain) of a few planar points, in place; returns its
// size (collinear points dropped; a single point or a segment gives 1 or 2).
int convexHull(Vec2* points, int n, Vec2* hull);

// Inserts `p`, a point outside the convex polygon `hull` (CCW, size ≥ 3), into it in place: the
// vertices between the edges p sees are dropped and p takes their place. Returns the new size.
int insertIntoHull(Vec2* hull, int size, const Vec2& p);

// The same insertion when the caller already knows which edges `p` sees (bit i: edge i, from vertex
// i, has p strictly on its outer side — the sign insertIntoHull tests): the same output, no cross
// product.
int insertIntoHullSeeing(Vec2* hull, int size, const Vec2& p, std::uint64_t sees);

// Removes list[position] from the list of `count`, keeping the others' order (ties of identity
// go to the lower index); returns the new count. Kept a loop: GCC turns the shift into a call of
// memmove, which for the few entries of a contact set costs more than the shift.
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("no-tree-loop-distribute-patterns")))
#endif
inline int removeAt(int* list, int position, int count) {
    for (int k = position + 1; k < count; ++k) list[k - 1] = list[k];
    return count - 1;
}

inline double hullArea(const Vec2* hull, int size) {
    double twice = 0;
    for (int i = 0; i < size; ++i) twice += cross2(hull[i], hull[i + 1 == size ? 0 : i + 1]);
    return 0.5 * twice;
}

// Whether `p` lies inside the convex polygon `hull` (CCW), within `slack` (a length).
inline bool contains(const Vec2* hull, int size, const Vec2& p, double slack) {
    if (size < 3) return false;
    for (int i = 0; i < size; ++i) {
        const Vec2& a = hull[i];
        const Vec2 edge = hull[i + 1 == size ? 0 : i + 1] - a;
        const double side = cross2(edge, p - a);
        // With slack ≥ 0 a point on the inner side passes whatever the edge's length: no root taken.
        if (side >= 0 && slack >= 0) continue;
        if (side < -slack * edge.norm()) return false;
    }
    return true;
}

// Whether the centroid rule leaves the kept points as they are for the common reason: with a
// tolerance ≥ 0, one or two centroids each on the inner side of every kept edge pass each of
// applyCentroidRule's tests (every edge `continue`s). One pass over the edges makes the same
// cross products, each edge's difference once for both centroids; false: the full tests decide.
// Each caller makes this test before applyCentroidRule (before the rule's frame,
// and before the convex-cycle ranking lists its free points), so the rule does not repeat it.
bool centroidsInsideKeptHull(const RankingRule& rule, const Vec2* hull, int keptSize);

// The centroid rule: a body whose centroid projects inside the whole contact polygon rests on
// it; if the kept points leave the centroid outside, that body would tip over an edge the polygon
// does not have. Then one kept point (never the first) is swapped for the point that brings every
// such centroid back inside, the swap of largest area. `hull`: the kept hull (CCW, keptSize
// vertices; overwritten), `free`: the points not kept, ascending. Returns wanted. Called where
// centroidsInsideKeptHull did not settle it.
int applyCentroidRule(const RankPoint* points, int count, const RankingRule& rule, int wanted, int* chosen,
                      std::array<Vec2, kMaxHull>& hull, int keptSize, const int* free, int freeCount);

// Where one value alone reaches a pick's band, that value is the largest and every other is
// below the band: the pick is that point, without a pass over the candidates' identities.
// `Leader` follows the largest value and the largest of the others as the values are made
// (NaN, which reaches no band, is passed over); the band is the one pickAtLeast is given. On a
// tilted face (one deepest point, one farthest) the first two picks become one test each.
struct Leader {
    double top = -INFINITY, runnerUp = -INFINITY;
    int index = -1;
    void see(int k, double v) {
        if (v > top) runnerUp = top, top = v, index = k;
        else if (v > runnerUp) runnerUp = v;
    }
    bool alone(double band) const { return index >= 0 && top >= band && !(runnerUp >= band); }
};


}  // namespace gdc::detail

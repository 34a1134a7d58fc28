#include "contact/reduction.hpp"
#include "contact/rank_few.hpp"
#include "contact/ranking_hull.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace gdc::detail {
namespace {

// The greedy ranking of rankContacts for points certified a strictly convex cycle
// (isStrictlyConvexCycle: the clip of two faces) with no given prefix and at least one slot that
// reads the kept hull's gains. Each point is a vertex of the polygon, so it sees exactly one edge
// of the kept hull — the one between its two hull neighbours — and the area it adds is that one
// triangle: the very expression the general path sums (b − a, then the cross product, the sign
// certified), so every value, comparison and choice is the general path's. The kept hull is links
// between indices, the free points a bit set (ascending, as the general path's list). Returns -1
// where a slot finds no area to gain (a sliver: the spread rule), and the general path ranks.
// `deepestLeader`: the depths' leader, seen in index order (the entries take it in a pass they
// make anyway). Inlined into both entries: a call and frame per ranked query otherwise.
[[gnu::always_inline]] inline int rankConvexCycle(const RankPoint* points, int count, const RankingRule& rule, int wanted,
                                                  const Leader& deepestLeader, int* chosen) {
    const double keep = 1 - rule.hysteresis;
    std::uint32_t freeMask = (std::uint32_t{1} << count) - 1;
    double value[kMaxManifoldPoints];
    auto pickAtLeast = [&](double threshold) {  // the free point of largest identity whose value reaches it
        int best = -1;
        double bestIdentity = -INFINITY;
        for (std::uint32_t m = freeMask; m != 0; m &= m - 1) {
            const int k = __builtin_ctz(m);
            if (value[k] >= threshold && (best < 0 || points[k].identity > bestIdentity))
                best = k, bestIdentity = points[k].identity;
        }
        return best;
    };
    auto pickLeaderOrAtLeast = [&](const Leader& leader, double band) {
        return leader.alone(band) ? leader.index : pickAtLeast(band);
    };
    const double deepest = deepestLeader.top;  // std::max over the depths: NaN passed over, ties kept
    // A non-finite depth finds no first point: the general path answers as it always did. Every
    // later pick finds one: the certificate held, so the points are finite, and the band
    // (keep = 1 − hysteresis, within [0.9, 1] by Settings) admits at least the best value.
    const double band = deepest - rule.tolerance;
    int first = deepestLeader.index;
    if (!deepestLeader.alone(band)) {
        for (int k = 0; k < count; ++k) value[k] = points[k].depth;
        first = pickAtLeast(band);
    }
    if (first < 0) return -1;
    chosen[0] = first, freeMask &= ~(std::uint32_t{1} << first);
    const Vec2 p0 = points[first].planar;
    Leader farthestLeader;
    for (std::uint32_t m = freeMask; m != 0; m &= m - 1) {
        const int k = __builtin_ctz(m);
        farthestLeader.see(k, value[k] = (points[k].planar - p0).squaredNorm());
    }
    // The std::max of 0 and the squared distances (finite, ≥ +0 where the certificate held): the
    // leader's top, or 0 if that is below.
    const double farthest = std::max(0.0, farthestLeader.top);
    const int second = pickLeaderOrAtLeast(farthestLeader, keep * keep * farthest);
    chosen[1] = second, freeMask &= ~(std::uint32_t{1} << second);
    const double areaTolerance = rule.tolerance * std::sqrt(farthest);
    // The third point: the largest triangle on the segment.
    const Vec2 segment = points[second].planar - p0;
    double bestGain = 0;
    for (std::uint32_t m = freeMask; m != 0; m &= m - 1) {
        const int k = __builtin_ctz(m);
        bestGain = std::max(bestGain, value[k] = 0.5 * std::abs(cross2(segment, points[k].planar - p0)));
    }
    if (!(bestGain > areaTolerance)) return -1;
    const int third = pickAtLeast(keep * bestGain);
    chosen[2] = third, freeMask &= ~(std::uint32_t{1} << third);
    // A free point's gain: the triangle on the kept edge between its hull neighbours. It changes
    // only when a neighbour does (the arcs on either side of the point taken), so each slot
    // recomputes those alone — the same expression of the same neighbours, so the same bits — and
    // the best gain is the maximum of the values kept, in the same order; the last slot updates
    // nothing. Two boxes' octagon to a budget of 6: 12 gains a ranking, now the first slot's 5
    // and those beside the fourth point.
    int before[kMaxManifoldPoints], after[kMaxManifoldPoints], next[kMaxManifoldPoints];
    auto gainOf = [&](int k) {
        const Vec2& a = points[before[k]].planar;
        const double twiceArea = cross2(points[after[k]].planar - a, points[k].planar - a);
        return -(0.5 * twiceArea);  // twiceArea < 0: 0 − ½·twiceArea
    };
    // The triangle counter-clockwise is its corners in cyclic order; each free point's hull
    // neighbours are the corners around its arc: between the first two, the last two, or (round
    // the end of the cycle) the last and the first.
    int c0 = first, c1 = second, c2 = third;
    if (c0 > c1) std::swap(c0, c1);
    if (c1 > c2) std::swap(c1, c2);
    if (c0 > c1) std::swap(c0, c1);
    next[c0] = c1, next[c1] = c2, next[c2] = c0;
    // The first slot's gains are made here, and with them their leader: its top is the slot's
    // best gain (the maximum of finite positive values — the certificate makes each twiceArea
    // < 0 — in any order), and a gain alone in the band is the pick (no max pass, and where one
    // gain leads no pick pass, of the first slot's own).
    Leader firstSlot;
    auto arc = [&](int from, int begin, int end, int to) {  // the points begin..end-1 lie between from and to
        for (int k = begin; k < end; ++k) {
            before[k] = from, after[k] = to;
            firstSlot.see(k, value[k] = gainOf(k));
        }
    };
    arc(c0, c0 + 1, c1, c1);
    arc(c1, c1 + 1, c2, c2);
    arc(c2, c2 + 1, count, c0);
    arc(c2, 0, c0, c0);
    int hullSize = 3;
    for (int slot = 3; slot < wanted; ++slot) {
        if (slot + 1 == count) {  // every point kept: no centroid rule
            chosen[slot] = __builtin_ctz(freeMask);
            return wanted;
        }
        if (slot == 3) {
            bestGain = std::max(0.0, firstSlot.top);
        } else {
            bestGain = 0;
            for (std::uint32_t m = freeMask; m != 0; m &= m - 1) bestGain = std::max(bestGain, value[__builtin_ctz(m)]);
        }
        if (!(bestGain > areaTolerance)) return -1;
        const int q = slot == 3 ? pickLeaderOrAtLeast(firstSlot, keep * bestGain) : pickAtLeast(keep * bestGain);
        chosen[slot] = q, freeMask &= ~(std::uint32_t{1} << q);
        // q joins the hull between its neighbours: the points of the arc on either side now see q
        // (read by a later slot only: the last one links q in alone, for the centroid rule).
        const int a = before[q], b = after[q];
        next[a] = q, next[q] = b;
        ++hullSize;
        if (slot + 1 == wanted) break;
        for (int j = a + 1 == count ? 0 : a + 1; j != q; j = j + 1 == count ? 0 : j + 1) after[j] = q, value[j] = gainOf(j);
        for (int j = q + 1 == count ? 0 : q + 1; j != b; j = j + 1 == count ? 0 : j + 1) before[j] = q, value[j] = gainOf(j);
    }
    if (wanted == count || rule.centroidCount == 0 || count > kMaxHull - 2) return wanted;
    // The kept hull as the general path's insertions leave it: from the first point (never
    // dropped), counter-clockwise; the free points ascending.
    std::array<Vec2, kMaxHull> hull;
    for (int e = 0, vertex = first; e < hullSize; ++e, vertex = next[vertex]) hull[e] = points[vertex].planar;
    if (centroidsInsideKeptHull(rule, hull.data(), hullSize)) return wanted;
    int free[kMaxManifoldPoints];
    int freeCount = 0;
    for (std::uint32_t m = freeMask; m != 0; m &= m - 1) free[freeCount++] = __builtin_ctz(m);
    return applyCentroidRule(points, count, rule, wanted, chosen, hull, hullSize, free, freeCount);
}

// isStrictlyConvexCycle's certificate taken vertex by vertex, so that the pass that gathers the
// points (rankContacts of lifted points) takes it too: the least turn (the cross product of
// consecutive edges), the sums of the edges' |x| and |y| and the times the edges' direction
// turns through +x (the times the boundary winds: each turn is less than π where every turn is
// left). The sums add the edges in the cycle's order (p0→p1 first, the closing edge last); the
// turns at the first and the last vertex, which need the closing edge, are taken at the end (a
// least value and a count do not depend on the order).
class CycleCertificate {
public:
    CycleCertificate(const Vec2& p0, const Vec2& p1) : first_(p0), last_(p1), out_(p1 - p0), in_(out_), sum_(out_.cwiseAbs()) {}
    void add(const Vec2& q) {  // the next vertex: the turn at the previous one
        const Vec2 edge = q - last_;
        turn(in_, edge);
        sum_ += edge.cwiseAbs();  // x and y each summed as two scalars would be (IEEE, lane by lane)
        in_ = edge, last_ = q;
    }
    bool certified() {
        const Vec2 closing = first_ - last_;
        turn(in_, closing);
        sum_ += closing.cwiseAbs();
        turn(closing, out_);
        // Every difference of two of the points is at most (sumX, sumY)/2 in each coordinate (a
        // closed polygon's extent is at most half its edges' total), so a computed cross product
        // of two differences is off by at most ~2 ε·sumX·sumY (ε = 2^-53, three roundings of
        // each of two products of at most sumX/2·sumY/2, and the result's): the margin
        // 1e-13·sumX·sumY is over 400 times that. Every turn certain and left, the boundary
        // winding once: a strictly convex polygon, and (its smallest triangle of vertices is one
        // of three consecutive ones) every cross product of differences of three of the points
        // has its true sign. The area stays far from underflow and overflow so that the bound
        // holds (else: not certified).
        const double box = sum_.x() * sum_.y();
        return upward_ == 1 && box >= 1e-250 && box <= 1e250 && leastTurn_ > 1e-13 * box;
    }

private:
    void turn(const Vec2& e, const Vec2& f) {  // e into a vertex, f out of it
        leastTurn_ = std::min(leastTurn_, e.x() * f.y() - e.y() * f.x());
        upward_ += e.y() < 0 && f.y() >= 0;  // exact signs: a rounded difference keeps its sign
    }
    Vec2 first_, last_;
    Vec2 out_;  // the edge out of the first vertex
    Vec2 in_;   // the edge into the last vertex added
    Vec2 sum_;  // the edges' |x| and |y| summed
    double leastTurn_ = INFINITY;
    int upward_ = 0;
};

// Whether the ranking of a certified convex cycle can save anything: no given prefix, the
// points in one buffer, and a slot that reads the kept hull's gains (else there is nothing for
// the certificate, a pass over the points, to save).
bool cycleRankingPays(int count, const RankingRule& rule) {
    const int wanted = std::min(count, rule.maxCount);
    return rule.fixedCount == 0 && count >= 5 && count <= kMaxManifoldPoints && wanted - 3 - (wanted == count ? 1 : 0) >= 1;
}

int rankGrowingHull(const RankPoint* points, int count, const RankingRule& rule, int* chosen);

}  // namespace

bool isStrictlyConvexCycle(const RankPoint* points, int count) {
    if (count < 3) return false;
    CycleCertificate certificate(points[0].planar, points[1].planar);
    for (int i = 2; i < count; ++i) certificate.add(points[i].planar);
    return certificate.certified();
}

int rankContacts(const RankPoint* points, int count, const RankingRule& rule, int* chosen) {
    if (rule.fixedCount == 0 && count <= 4 && count <= rule.maxCount) return rankAllOfFew(points, count, rule, chosen);
    // A convex polygon's vertices in cyclic order (the clip of two faces), where a slot reads the
    // kept hull's gains.
    if (cycleRankingPays(count, rule) && isStrictlyConvexCycle(points, count)) {
        Leader deepest;
        for (int k = 0; k < count; ++k) deepest.see(k, points[k].depth);
        const int ranked = rankConvexCycle(points, count, rule, std::min(count, rule.maxCount), deepest, chosen);
        if (ranked >= 0) return ranked;
    }
    return rankGrowingHull(points, count, rule, chosen);
}

namespace {

// The general ranking: the kept hull grown slot by slot (rankContacts without its shortcuts).
int rankGrowingHull(const RankPoint* points, int count, const RankingRule& rule, int* chosen) {
    const int fixed = rule.fixedCount;
    const int wanted = std::min(count, rule.maxCount);
    if (fixed > 0 && fixed >= wanted) return fixed;
    if (wanted <= 0) return 0;
    const double keep = 1 - rule.hysteresis;
    // The free points (indices, ascending: a tie of identities goes to the lower index), and the
    // value each would add in the current slot (value[k] belongs to free[k]). Walking this list
    // instead of flags over every point, precomputing the kept hull's edges and skipping hull
    // updates no later step reads make the ranking cheaper; the arithmetic of every value and
    // comparison is the one the ranking always did, so it chooses the same points in the same
    // order (tests/reduction_test.cpp compares it with the former code on 200000 polygons).
    int freeStorage[kMaxManifoldPoints];
    double valueStorage[kMaxManifoldPoints];
    std::uint64_t seesStorage[kMaxManifoldPoints];  // the kept hull's edges each free point sees
    std::vector<int> freeHeap;
    std::vector<double> valueHeap;
    std::vector<std::uint64_t> seesHeap;
    if (count > kMaxManifoldPoints) freeHeap.resize(count), valueHeap.resize(count), seesHeap.resize(count);
    std::uint64_t* sees = count > kMaxManifoldPoints ? seesHeap.data() : seesStorage;
    int* free = count > kMaxManifoldPoints ? freeHeap.data() : freeStorage;
    double* value = count > kMaxManifoldPoints ? valueHeap.data() : valueStorage;
    int freeCount = 0;
    if (fixed == 0) {  // every point free (the search below cost a box face pair 1 % of its query)
        for (int k = 0; k < count; ++k) free[k] = k;
        freeCount = count;
    } else {
        for (int k = 0; k < count; ++k)
            if (std::find(chosen, chosen + fixed, k) == chosen + fixed) free[freeCount++] = k;
    }
    // Among the free points whose value reaches `threshold`, the one of largest identity (its
    // position in `free`).
    auto pickAtLeast = [&](double threshold) {
        int best = -1;
        double bestIdentity = -INFINITY;
        for (int k = 0; k < freeCount; ++k)
            if (value[k] >= threshold && (best < 0 || points[free[k]].identity > bestIdentity))
                best = k, bestIdentity = points[free[k]].identity;
        return best;
    };
    auto take = [&](int position, int slot) {
        chosen[slot] = free[position];
        freeCount = removeAt(free, position, freeCount);
    };

    double farthest = 0;
    if (fixed == 0) {
        // The deepest point; depths within rounding of it are equal (an exactly resting face's
        // corners). No wider band: the first point carries the pair's whole penetration (ODE's
        // contract), and a dropped deeper corner tilted dWorldStep's stacks by micrometres.
        double deepest = -INFINITY;
        for (int k = 0; k < count; ++k) deepest = std::max(deepest, value[k] = points[k].depth);
        take(pickAtLeast(deepest - rule.tolerance), 0);
        if (wanted == 1) return 1;
        if (count == 2) return take(0, 1), 2;

        // The farthest from it: the longest segment through the first point (at least half the
        // polygon's diameter).
        const Vec2 p0 = points[chosen[0]].planar;
        for (int k = 0; k < freeCount; ++k) farthest = std::max(farthest, value[k] = (points[free[k]].planar - p0).squaredNorm());
        take(pickAtLeast(keep * keep * farthest), 1);
        if (wanted == 2) return 2;
    }
    const Vec2 p0 = points[chosen[0]].planar;

    // The centroid rule (below) reads the kept hull only if it can act at all.
    const bool centroidRuleMayAct =
        !(fixed > 0 || wanted == count || wanted < 3 || rule.centroidCount == 0 || count > kMaxHull - 2);

    // Then, slot by slot, the largest area added to the kept points' hull (for the third point the
    // triangle on the segment), the hull grown by each point taken. Collinear sets gain no area and
    // spread along their line.
    const double areaTolerance = fixed > 0 ? rule.areaTolerance : rule.tolerance * std::sqrt(farthest);
    std::array<Vec2, kMaxHull> hull, edges;  // edges[e] = hull[e + 1] - hull[e] (cyclically)
    int hullSize = 0;  // 0 until the kept points span a triangle
    auto updateEdges = [&] {
        for (int e = 0; e < hullSize; ++e) edges[e] = hull[e + 1 == hullSize ? 0 : e + 1] - hull[e];
    };
    // From a given prefix the kept hull is rebuilt from the kept points before each slot (the
    // monotone chain's vertex order; a segment when they are collinear): a few slots of a rare
    // path, where the grown hull's bookkeeping would save nothing.
    std::array<Vec2, kMaxHull> keptPoints;
    auto rebuildHull = [&](int kept) {
        for (int s = 0; s < kept; ++s) keptPoints[s] = points[chosen[s]].planar;
        hullSize = convexHull(keptPoints.data(), kept, hull.data());  // 1 or 2 points: themselves, sorted
        updateEdges();
    };
    for (int slot = fixed > 0 ? fixed : 2; slot < wanted; ++slot) {
        if (slot + 1 == count) return take(0, slot), wanted;  // every point kept: no centroid rule
        if (fixed > 0) rebuildHull(slot);
        double bestGain = 0;
        if (fixed > 0 && hullSize < 3) {  // a segment (or a point: no area)
            for (int k = 0; k < freeCount; ++k)
                bestGain = std::max(bestGain, value[k] = hullSize < 2 ? 0.0 : 0.5 * std::abs(cross2(edges[0], points[free[k]].planar - hull[0])));
        } else if (hullSize < 3) {
            const Vec2 segment = points[chosen[1]].planar - p0;
            for (int k = 0; k < freeCount; ++k)
                bestGain = std::max(bestGain, value[k] = 0.5 * std::abs(cross2(segment, points[free[k]].planar - p0)));
        } else {
            // The area the hull gains when the point joins it: the triangles it forms with the
            // edges it sees from outside (areaGain, with the edges computed once per hull).
            for (int k = 0; k < freeCount; ++k) {
                const Vec2& p = points[free[k]].planar;
                double gain = 0;
                std::uint64_t seen = 0;
                for (int e = 0; e < hullSize; ++e) {
                    const double twiceArea = cross2(edges[e], p - hull[e]);
                    if (twiceArea < 0) gain -= 0.5 * twiceArea, seen |= std::uint64_t{1} << e;
                }
                bestGain = std::max(bestGain, value[k] = gain);
                sees[k] = seen;
            }
        }
        if (!(bestGain > areaTolerance)) {
            // Spread: the free point farthest from its nearest kept point.
            double spread = 0;
            for (int k = 0; k < freeCount; ++k) {
                double nearest = INFINITY;
                for (int s = 0; s < slot; ++s)
                    nearest = std::min(nearest, (points[free[k]].planar - points[chosen[s]].planar).squaredNorm());
                spread = std::max(spread, value[k] = nearest);
            }
            take(pickAtLeast(keep * keep * spread), slot);
            continue;  // still collinear: no hull yet
        }
        const int position = pickAtLeast(keep * bestGain);
        const int index = free[position];
        const std::uint64_t seen = sees[position];
        take(position, slot);
        // A later slot reads the hull unless the next one takes the last point or there is none.
        const bool hullRead = (slot + 1 < wanted && slot + 2 != count) || centroidRuleMayAct;
        if (!hullRead || fixed > 0) continue;
        const Vec2& q = points[index].planar;
        if (hullSize >= 3) {
            hullSize = insertIntoHullSeeing(hull.data(), hullSize, q, seen);
        } else {  // the first point off the line: the triangle, counter-clockwise
            Vec2 b = points[chosen[1]].planar, c = q;
            if (cross2(b - p0, c - p0) < 0) std::swap(b, c);
            hull[0] = p0, hull[1] = b, hull[2] = c;
            hullSize = 3;
        }
        updateEdges();
    }
    // (A polygon of more points than the hull buffers hold — only caps of many faces make one —
    // keeps the greedy set.)
    if (!centroidRuleMayAct || centroidsInsideKeptHull(rule, hull.data(), hullSize)) return wanted;
    return applyCentroidRule(points, count, rule, wanted, chosen, hull, hullSize, free, freeCount);
}

}  // namespace

int rankContacts(const LiftedPoints& points, const RankingRule& rule, int* chosen) {
    const int count = static_cast<int>(points.size());
    RankPoint storage[kMaxManifoldPoints];
    std::vector<RankPoint> heap;
    if (count > kMaxManifoldPoints) heap.resize(count);
    RankPoint* ranked = count > kMaxManifoldPoints ? heap.data() : storage;
    auto gather = [&](int i) {
        ranked[i] = {points[i].planar, points[i].depth, points[i].position.dot(rule.identity)};
        return ranked[i].planar;
    };
    if (!cycleRankingPays(count, rule)) {
        for (int i = 0; i < count; ++i) gather(i);
        return rankContacts(ranked, count, rule, chosen);
    }
    // The certificate taken in the pass that gathers the points (rankContacts(RankPoint*)'s
    // dispatch otherwise): one pass over the points instead of two.
    Leader deepest;  // the deepest point's leader too
    const Vec2 p0 = gather(0);
    deepest.see(0, ranked[0].depth);
    CycleCertificate certificate(p0, gather(1));
    deepest.see(1, ranked[1].depth);
    for (int i = 2; i < count; ++i) certificate.add(gather(i)), deepest.see(i, ranked[i].depth);
    if (certificate.certified()) {
        const int ranking = rankConvexCycle(ranked, count, rule, std::min(count, rule.maxCount), deepest, chosen);
        if (ranking >= 0) return ranking;
    }
    return rankGrowingHull(ranked, count, rule, chosen);
}

}  // namespace gdc::detail

// The ranking of reduction.cpp as it was before its general path was made cheaper (commit
// 36c3de3), kept verbatim as the reference that tests/reduction_test.cpp compares the library's
// ranking with: the same indices in the same order on random polygons and resting poses.
#pragma once

#include "contact/reduction.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

// GCC's -Wstringop-overflow misreads the inlined flag writes of this copy (a false positive the
// library's own translation unit never showed).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-overflow"

namespace gdc::reference {
using namespace gdc::detail;

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

constexpr int kMaxHull = 2 * kMaxManifoldPoints + 4;

// Convex hull (counter-clockwise, monotone chain) of a few planar points, in place; returns its
// size (collinear points dropped; a single point or a segment gives 1 or 2).
int convexHull(Vec2* points, int n, Vec2* hull) {
    std::sort(points, points + n,
              [](const Vec2& p, const Vec2& q) { return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y()); });
    int k = 0;
    for (int i = 0; i < n; ++i) {
        while (k >= 2 && cross2(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0) --k;
        hull[k++] = points[i];
    }
    for (int i = n - 2, lower = k + 1; i >= 0; --i) {
        while (k >= lower && cross2(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0) --k;
        hull[k++] = points[i];
    }
    return std::max(1, k - 1);
}

// Area the convex polygon `hull` (CCW) gains when `p` joins it: the triangles p forms with the
// edges it sees from outside.
double areaGain(const Vec2* hull, int size, const Vec2& p) {
    double gain = 0;
    for (int i = 0; i < size; ++i) {
        const Vec2& a = hull[i];
        const Vec2& b = hull[i + 1 == size ? 0 : i + 1];
        const double twiceArea = cross2(b - a, p - a);
        if (twiceArea < 0) gain -= 0.5 * twiceArea;
    }
    return gain;
}

// Inserts `p`, a point outside the convex polygon `hull` (CCW, size ≥ 3), into it in place: the
// vertices between the edges p sees are dropped and p takes their place. Returns the new size.
int insertIntoHull(Vec2* hull, int size, const Vec2& p) {
    bool sees[kMaxHull];
    int seen = 0;
    for (int i = 0; i < size; ++i) {
        const Vec2& a = hull[i];
        sees[i] = cross2(hull[i + 1 == size ? 0 : i + 1] - a, p - a) < 0;  // edge i runs from vertex i
        seen += sees[i];
    }
    if (seen == 0 || seen == size) return size;  // inside (or a degenerate hull): nothing to insert
    Vec2 out[kMaxHull];
    int count = 0;
    for (int i = 0; i < size; ++i) {
        const bool before = sees[i == 0 ? size - 1 : i - 1], after = sees[i];
        if (before && after) continue;  // between two visible edges: now inside
        out[count++] = hull[i];
        if (!before && after) out[count++] = p;  // the visible chain starts here
    }
    std::copy(out, out + count, hull);
    return count;
}

double hullArea(const Vec2* hull, int size) {
    double twice = 0;
    for (int i = 0; i < size; ++i) twice += cross2(hull[i], hull[i + 1 == size ? 0 : i + 1]);
    return 0.5 * twice;
}

// Whether `p` lies inside the convex polygon `hull` (CCW), within `slack` (a length).
bool contains(const Vec2* hull, int size, const Vec2& p, double slack) {
    if (size < 3) return false;
    for (int i = 0; i < size; ++i) {
        const Vec2& a = hull[i];
        const Vec2 edge = hull[i + 1 == size ? 0 : i + 1] - a;
        if (cross2(edge, p - a) < -slack * edge.norm()) return false;
    }
    return true;
}

}  // namespace


// rankContacts for at most 4 points, all kept (a box face on a plane, two aligned boxes): the same
// choices, slot by slot, without the general bookkeeping — the most common case by far.
inline int rankAllOfFew(const RankPoint* points, int count, const RankingRule& rule, int* chosen) {
    const double keep = 1 - rule.hysteresis;
    int order[4] = {0, 1, 2, 3};
    // Moves the point of largest identity among order[from..count) whose value reaches the
    // threshold to position `from`.
    auto pick = [&](int from, const double* value, double threshold) {
        int best = from;
        for (int k = from; k < count; ++k)
            if (value[k] >= threshold && (value[best] < threshold || points[order[k]].identity > points[order[best]].identity))
                best = k;
        std::swap(order[from], order[best]);
    };
    double value[4];
    double deepest = -INFINITY;
    for (int k = 0; k < count; ++k) deepest = std::max(deepest, value[k] = points[k].depth);
    pick(0, value, deepest - rule.tolerance);
    if (count > 2) {
        const Vec2 p0 = points[order[0]].planar;
        double farthest = 0;
        for (int k = 1; k < count; ++k) farthest = std::max(farthest, value[k] = (points[order[k]].planar - p0).squaredNorm());
        pick(1, value, keep * keep * farthest);
        if (count == 4) {
            const Vec2 segment = points[order[1]].planar - p0;
            double bestGain = 0;
            for (int k = 2; k < 4; ++k)
                bestGain = std::max(bestGain, value[k] = 0.5 * std::abs(cross2(segment, points[order[k]].planar - p0)));
            if (bestGain > rule.tolerance * std::sqrt(farthest)) {
                pick(2, value, keep * bestGain);
            } else {  // collinear: the point farther from its nearest kept point
                for (int k = 2; k < 4; ++k) {
                    const Vec2& q = points[order[k]].planar;
                    value[k] = std::min((q - p0).squaredNorm(), (q - points[order[1]].planar).squaredNorm());
                }
                pick(2, value, keep * keep * std::max(value[2], value[3]));
            }
        }
    }
    std::copy(order, order + count, chosen);
    return count;
}

inline int rankContacts(const RankPoint* points, int count, const RankingRule& rule, int* chosen) {
    if (count <= 4 && count <= rule.maxCount) return rankAllOfFew(points, count, rule, chosen);
    const int wanted = std::min(count, rule.maxCount);
    if (wanted <= 0) return 0;
    const double keep = 1 - rule.hysteresis;
    // Which points are kept, and the value each free point would add in the current slot.
    char takenStorage[kMaxManifoldPoints];
    double valueStorage[kMaxManifoldPoints];
    std::vector<char> takenHeap;
    std::vector<double> valueHeap;
    if (count > kMaxManifoldPoints) takenHeap.resize(count), valueHeap.resize(count);
    char* taken = count > kMaxManifoldPoints ? takenHeap.data() : takenStorage;
    double* value = count > kMaxManifoldPoints ? valueHeap.data() : valueStorage;
    std::fill(taken, taken + count, 0);
    // Among the free points whose value reaches `threshold`, the one of largest identity.
    auto pickAtLeast = [&](double threshold) {
        int best = -1;
        double bestIdentity = -INFINITY;
        for (int i = 0; i < count; ++i)
            if (!taken[i] && value[i] >= threshold && (best < 0 || points[i].identity > bestIdentity))
                best = i, bestIdentity = points[i].identity;
        return best;
    };
    auto take = [&](int index, int slot) { chosen[slot] = index, taken[index] = 1; };
    auto takeLast = [&](int slot) {  // one point left: no choice to make
        for (int i = 0; i < count; ++i)
            if (!taken[i]) return take(i, slot);
    };

    // The deepest point; depths within rounding of it are equal (an exactly resting face's corners).
    // No wider band: the first point carries the pair's whole penetration (ODE's contract), and a
    // dropped deeper corner tilted dWorldStep's stacks by micrometres.
    double deepest = -INFINITY;
    for (int i = 0; i < count; ++i) deepest = std::max(deepest, value[i] = points[i].depth);
    take(pickAtLeast(deepest - rule.tolerance), 0);
    if (wanted == 1) return 1;
    if (count == 2) return takeLast(1), 2;

    // The farthest from it: the longest segment through the first point (at least half the
    // polygon's diameter).
    const Vec2 p0 = points[chosen[0]].planar;
    double farthest = 0;
    for (int i = 0; i < count; ++i)
        if (!taken[i]) farthest = std::max(farthest, value[i] = (points[i].planar - p0).squaredNorm());
    take(pickAtLeast(keep * keep * farthest), 1);
    if (wanted == 2) return 2;

    // Then, slot by slot, the largest area added to the kept points' hull (for the third point the
    // triangle on the segment), the hull grown by each point taken. Collinear sets gain no area and
    // spread along their line.
    const double areaTolerance = rule.tolerance * std::sqrt(farthest);
    std::array<Vec2, kMaxHull> hull;
    int hullSize = 0;  // 0 until the kept points span a triangle
    for (int slot = 2; slot < wanted; ++slot) {
        if (slot + 1 == count) return takeLast(slot), wanted;  // every point kept: no centroid rule
        double bestGain = 0;
        if (hullSize < 3) {
            const Vec2 segment = points[chosen[1]].planar - p0;
            for (int i = 0; i < count; ++i)
                if (!taken[i])
                    bestGain = std::max(bestGain, value[i] = 0.5 * std::abs(cross2(segment, points[i].planar - p0)));
        } else {
            for (int i = 0; i < count; ++i)
                if (!taken[i]) bestGain = std::max(bestGain, value[i] = areaGain(hull.data(), hullSize, points[i].planar));
        }
        if (!(bestGain > areaTolerance)) {
            // Spread: the free point farthest from its nearest kept point.
            double spread = 0;
            for (int i = 0; i < count; ++i) {
                if (taken[i]) continue;
                double nearest = INFINITY;
                for (int s = 0; s < slot; ++s)
                    nearest = std::min(nearest, (points[i].planar - points[chosen[s]].planar).squaredNorm());
                spread = std::max(spread, value[i] = nearest);
            }
            take(pickAtLeast(keep * keep * spread), slot);
            continue;  // still collinear: no hull yet
        }
        const int index = pickAtLeast(keep * bestGain);
        take(index, slot);
        const Vec2& q = points[index].planar;
        if (hullSize >= 3) {
            hullSize = insertIntoHull(hull.data(), hullSize, q);
        } else {  // the first point off the line: the triangle, counter-clockwise
            Vec2 b = points[chosen[1]].planar, c = q;
            if (cross2(b - p0, c - p0) < 0) std::swap(b, c);
            hull[0] = p0, hull[1] = b, hull[2] = c;
            hullSize = 3;
        }
    }
    // (A polygon of more points than the hull buffers hold — only caps of many faces make one —
    // keeps the greedy set.)
    if (wanted == count || wanted < 3 || rule.centroidCount == 0 || count > kMaxHull - 2) return wanted;

    // The centroid rule: a body whose centroid projects inside the whole contact polygon rests on
    // it; if the kept points leave the centroid outside, that body would tip over an edge the
    // polygon does not have. Then one kept point (never the first) is swapped for the point that
    // brings every such centroid back inside, the swap of largest area.
    const int centroids = std::min(rule.centroidCount, 4);
    const int keptSize = hullSize;
    std::array<Vec2, kMaxHull> scratch;
    // A centroid needs the rule only if it is outside the kept hull and a free point lies beyond a
    // kept edge it is outside of (else that edge's line separates it from every point: it is
    // outside the whole polygon too) — two cheap tests before the whole polygon is built.
    bool restore = false;
    for (int c = 0; c < centroids && !restore; ++c) {
        const Vec2& centroid = rule.centroids[c];
        if (keptSize < 3) {
            restore = true;
            break;
        }
        for (int e = 0; e < keptSize && !restore; ++e) {
            const Vec2& a = hull[e];
            const Vec2 edge = hull[e + 1 == keptSize ? 0 : e + 1] - a;
            if (!(cross2(edge, centroid - a) < -rule.tolerance * edge.norm())) continue;  // inside this edge
            for (int i = 0; i < count && !restore; ++i)
                restore = !taken[i] && cross2(edge, points[i].planar - a) < 0;
            if (!restore) break;  // separated from every point by this edge's line
        }
    }
    if (!restore) return wanted;
    // The whole polygon: the kept hull grown by every free point (no sort).
    std::array<Vec2, kMaxHull> whole;
    int wholeSize = keptSize;
    std::copy(hull.begin(), hull.begin() + keptSize, whole.begin());
    if (wholeSize >= 3) {
        for (int i = 0; i < count; ++i)
            if (!taken[i]) wholeSize = insertIntoHull(whole.data(), wholeSize, points[i].planar);
    } else {
        for (int i = 0; i < count; ++i) scratch[i] = points[i].planar;
        wholeSize = convexHull(scratch.data(), count, whole.data());
    }
    // Every centroid inside the whole polygon (by more than rounding) must be inside the kept set.
    bool required[4] = {false, false, false, false};
    bool any = false;
    for (int c = 0; c < centroids; ++c) {
        required[c] = contains(whole.data(), wholeSize, rule.centroids[c], -rule.tolerance);
        any |= required[c] && !contains(hull.data(), keptSize, rule.centroids[c], rule.tolerance);
    }
    if (!any) return wanted;
    int bestSlot = -1, bestPoint = -1;
    double bestArea = -1;
    for (int slot = 1; slot < wanted; ++slot)
        for (int i = 0; i < count; ++i) {
            if (taken[i]) continue;
            for (int s = 0; s < wanted; ++s) scratch[s] = s == slot ? points[i].planar : points[chosen[s]].planar;
            const int size = convexHull(scratch.data(), wanted, hull.data());
            bool holds = true;
            for (int c = 0; c < centroids && holds; ++c)
                holds = !required[c] || contains(hull.data(), size, rule.centroids[c], rule.tolerance);
            if (!holds) continue;
            const double area = hullArea(hull.data(), size);
            if (area > bestArea) bestArea = area, bestSlot = slot, bestPoint = i;
        }
    if (bestSlot >= 0) chosen[bestSlot] = bestPoint;
    return wanted;
}


// The body-pair reduction's fill by area from a given triangle (src/body_pair_reduction.cpp's
// fillByArea before commit "rankContacts from a given prefix"), verbatim with its helpers: the
// reference that tests/reduction_test.cpp compares detail::rankContacts with a prefix against.
// The certificate of a strictly convex cycle as reduction.cpp had it at ac53fc8 (one loop over
// the edges), verbatim: the library's CycleCertificate, taken vertex by vertex, must agree.
inline bool isStrictlyConvexCycle(const RankPoint* points, int count) {
    if (count < 3) return false;
    double leastTurn = INFINITY, sumX = 0, sumY = 0;
    int upward = 0;
    double px = points[0].planar.x(), py = points[0].planar.y();
    double ex = px - points[count - 1].planar.x(), ey = py - points[count - 1].planar.y();  // the edge into point i
    for (int i = 0; i < count; ++i) {
        const int j = i + 1 == count ? 0 : i + 1;
        const double qx = points[j].planar.x(), qy = points[j].planar.y();
        const double fx = qx - px, fy = qy - py;  // the edge out of point i
        leastTurn = std::min(leastTurn, ex * fy - ey * fx);
        sumX += std::abs(fx), sumY += std::abs(fy);
        upward += ey < 0 && fy >= 0;  // exact signs: a rounded difference keeps its sign
        ex = fx, ey = fy, px = qx, py = qy;
    }
    const double box = sumX * sumY;
    return upward == 1 && box >= 1e-250 && box <= 1e250 && leastTurn > 1e-13 * box;
}

namespace fill {
namespace {
// Convex hull (counter-clockwise, monotone chain) of the points `indices[0, n)` of `points`, as
// indices into `hull` (room for 2n); returns its size. Collinear points are left out; one or two
// points give themselves. `indices` is sorted in place.
int hullOf(const std::vector<Vec2>& points, int* indices, int n, int* hull) {
    std::sort(indices, indices + n, [&](int a, int b) {
        const Vec2& p = points[a];
        const Vec2& q = points[b];
        return p.x() < q.x() || (p.x() == q.x() && (p.y() < q.y() || (p.y() == q.y() && a < b)));
    });
    if (n < 3) {
        std::copy(indices, indices + n, hull);
        return n;
    }
    int k = 0;
    for (int i = 0; i < n; ++i) {
        while (k >= 2 && cross2(points[hull[k - 1]] - points[hull[k - 2]], points[indices[i]] - points[hull[k - 2]]) <= 0) --k;
        hull[k++] = indices[i];
    }
    for (int i = n - 2, lower = k + 1; i >= 0; --i) {
        while (k >= lower && cross2(points[hull[k - 1]] - points[hull[k - 2]], points[indices[i]] - points[hull[k - 2]]) <= 0)
            --k;
        hull[k++] = indices[i];
    }
    return std::max(1, k - 1);
}

// Hull of a few chosen points (≤ kMaxManifoldPoints + 1), into a fixed array.
struct SmallHull {
    std::array<int, 2 * (kMaxManifoldPoints + 2)> vertices;
    int size = 0;
    SmallHull(const std::vector<Vec2>& points, const int* chosen, int n) {
        std::array<int, kMaxManifoldPoints + 2> copy;
        std::copy(chosen, chosen + n, copy.begin());
        size = hullOf(points, copy.data(), n, vertices.data());
    }
};

// Area the counter-clockwise polygon `hull` gains when `p` joins it.
double areaGain(const std::vector<Vec2>& points, const SmallHull& hull, const Vec2& p) {
    if (hull.size == 2)  // a segment: the triangle it makes with p
        return 0.5 * std::abs(cross2(points[hull.vertices[1]] - points[hull.vertices[0]], p - points[hull.vertices[0]]));
    double gain = 0;
    for (int i = 0; i < hull.size; ++i) {
        const Vec2& a = points[hull.vertices[i]];
        const Vec2& b = points[hull.vertices[i + 1 == hull.size ? 0 : i + 1]];
        const double twiceArea = cross2(b - a, p - a);
        if (twiceArea < 0) gain -= 0.5 * twiceArea;
    }
    return gain;
}

// Adds points of `candidates[0, n)` to `chosen` (the kept ones; `size` of them) until `budget`:
// each time the one adding the most area — with the per-geom-pair reduction's hysteresis: gains
// within `keep` (1 − Settings::reductionHysteresis) of the best count as equal and go to the
// largest identity (a point's position along detail::identityDirection), so a perturbation
// within the band keeps the same points. Collinear sets (no area above `areaTolerance`) spread:
// the point farthest from every kept one, by the same band. `nearest` (per point, indexed like
// `points`) is scratch. Returns the new size.
int fillByArea(const std::vector<Vec2>& points, const std::vector<double>& identity, const int* candidates, int n,
               int budget, double keep, double areaTolerance, int* chosen, int size, std::vector<double>& nearest,
               std::vector<double>& gain) {
    auto isChosen = [&](int i) { return std::find(chosen, chosen + size, i) != chosen + size; };
    for (int c = 0; c < n; ++c) {
        const int i = candidates[c];
        nearest[i] = 1e300;
        for (int k = 0; k < size; ++k) nearest[i] = std::min(nearest[i], (points[i] - points[chosen[k]]).squaredNorm());
    }
    while (size < budget) {
        const SmallHull hull(points, chosen, size);
        double bestGain = 0, bestSpread = 0;
        int free = 0;
        for (int c = 0; c < n; ++c) {
            const int i = candidates[c];
            if (isChosen(i)) continue;
            ++free;
            gain[i] = hull.size >= 2 ? areaGain(points, hull, points[i]) : 0.0;
            bestGain = std::max(bestGain, gain[i]);
            bestSpread = std::max(bestSpread, nearest[i]);
        }
        if (free == 0) break;
        const bool byArea = bestGain > areaTolerance;
        const double threshold = byArea ? keep * bestGain : keep * keep * bestSpread;
        int best = -1;
        for (int c = 0; c < n; ++c) {
            const int i = candidates[c];
            if (isChosen(i) || (byArea ? gain[i] : nearest[i]) < threshold) continue;
            if (best < 0 || identity[i] > identity[best]) best = i;
        }
        chosen[size++] = best;
        for (int c = 0; c < n; ++c) {
            const int i = candidates[c];
            nearest[i] = std::min(nearest[i], (points[i] - points[best]).squaredNorm());
        }
    }
    return size;
}

}  // namespace
}  // namespace fill

}  // namespace gdc::reference

#pragma GCC diagnostic pop

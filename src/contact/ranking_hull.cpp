// The ranking's hull arithmetic and centroid rule (ranking_hull.hpp).
#include "contact/ranking_hull.hpp"

#include <algorithm>

namespace gdc::detail {

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

int insertIntoHullSeeing(Vec2* hull, int size, const Vec2& p, std::uint64_t sees) {
    if (sees == 0 || sees == (std::uint64_t{1} << size) - 1) return size;  // inside, or a degenerate hull
    Vec2 out[kMaxHull];
    int count = 0;
    for (int i = 0; i < size; ++i) {
        const bool before = (sees >> (i == 0 ? size - 1 : i - 1)) & 1, after = (sees >> i) & 1;
        if (before && after) continue;
        out[count++] = hull[i];
        if (!before && after) out[count++] = p;
    }
    for (int i = 0; i < count; ++i) hull[i] = out[i];
    return count;
}

bool centroidsInsideKeptHull(const RankingRule& rule, const Vec2* hull, int keptSize) {
    const int centroids = std::min(rule.centroidCount, 4);
    if (centroids < 1 || centroids > 2 || keptSize < 3 || !(rule.tolerance >= 0)) return false;
    // The two centroids' x and y side by side: each lane computes cross2(edge, centroid − a) as
    // edge.x·(centroid − a).y − edge.y·(centroid − a).x, the same IEEE operations in the same order.
    const Eigen::Array2d x(rule.centroids[0].x(), rule.centroids[centroids - 1].x());
    const Eigen::Array2d y(rule.centroids[0].y(), rule.centroids[centroids - 1].y());
    Vec2 a = hull[keptSize - 1];
    bool inside = true;
    for (int e = 0; e < keptSize; ++e) {  // the kept edge from vertex e − 1 to vertex e
        const Vec2 b = hull[e];
        const Vec2 edge = b - a;
        const Eigen::Array2d side = edge.x() * (y - a.y()) - edge.y() * (x - a.x());
        inside &= (side >= 0).all();
        a = b;
    }
    return inside;
}

int applyCentroidRule(const RankPoint* points, int count, const RankingRule& rule, int wanted, int* chosen,
                      std::array<Vec2, kMaxHull>& hull, int keptSize, const int* free, int freeCount) {
    const int centroids = std::min(rule.centroidCount, 4);
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
            // Inside this edge: on its inner side (no root needed where the tolerance is ≥ 0), or
            // outside by no more than the tolerance.
            const double side = cross2(edge, centroid - a);
            if ((side >= 0 && rule.tolerance >= 0) || !(side < -rule.tolerance * edge.norm())) continue;
            for (int k = 0; k < freeCount && !restore; ++k) restore = cross2(edge, points[free[k]].planar - a) < 0;
            if (!restore) break;  // separated from every point by this edge's line
        }
    }
    if (!restore) return wanted;
    // The whole polygon: the kept hull grown by every free point (no sort).
    std::array<Vec2, kMaxHull> whole;
    int wholeSize = keptSize;
    std::copy(hull.begin(), hull.begin() + keptSize, whole.begin());
    if (wholeSize >= 3) {
        for (int k = 0; k < freeCount; ++k) wholeSize = insertIntoHull(whole.data(), wholeSize, points[free[k]].planar);
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
        for (int k = 0; k < freeCount; ++k) {
            const int i = free[k];
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

}  // namespace gdc::detail

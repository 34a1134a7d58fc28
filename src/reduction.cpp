#include "reduction.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Convex hull (counter-clockwise, monotone chain) of a few planar points, in place; returns its size.
int convexHull(SmallVector<Vec2, 17>& points, std::array<Vec2, 36>& hull) {
    const int n = static_cast<int>(points.size());
    std::sort(points.data(), points.data() + n,
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
double areaGain(const std::array<Vec2, 36>& hull, int size, const Vec2& p) {
    double gain = 0;
    for (int i = 0; i < size; ++i) {
        const Vec2& a = hull[i];
        const Vec2& b = hull[i + 1 == size ? 0 : i + 1];
        double twiceArea = cross2(b - a, p - a);
        if (twiceArea < 0) gain -= 0.5 * twiceArea;
    }
    return gain;
}

}  // namespace

int reduceContacts(const LiftedPoints& points, int maxCount, int* chosen) {
    const int count = static_cast<int>(points.size());
    if (count <= maxCount) {
        for (int i = 0; i < count; ++i) chosen[i] = i;
        return count;
    }
    if (maxCount <= 0) return 0;
    // Per point: whether it is kept, and its largest squared distance to the points kept so far
    // (updated as each is taken, instead of rescanning every kept point for every candidate).
    struct Candidate {
        bool taken;
        double farthestKept;
    };
    SmallVector<Candidate, 16> candidates;
    for (int i = 0; i < count; ++i) candidates.push_back({false, 0.0});
    auto take = [&](int index, int slot) { chosen[slot] = index, candidates[index].taken = true; };

    int deepest = 0;
    for (int i = 1; i < count; ++i)
        if (points[i].depth > points[deepest].depth) deepest = i;
    take(deepest, 0);
    if (maxCount == 1) return 1;

    int farthest = -1;
    double farthestDistance = -1;
    for (int i = 0; i < count; ++i)
        if (!candidates[i].taken) {
            double d = (points[i].planar - points[deepest].planar).squaredNorm();
            if (d > farthestDistance) farthestDistance = d, farthest = i;
        }
    take(farthest, 1);

    auto keepDistancesTo = [&](int index) {
        for (int i = 0; i < count; ++i)
            candidates[i].farthestKept =
                std::max(candidates[i].farthestKept, (points[i].planar - points[index].planar).squaredNorm());
    };
    if (maxCount > 2) keepDistancesTo(chosen[0]), keepDistancesTo(chosen[1]);

    std::array<Vec2, 36> hull;
    for (int slot = 2; slot < maxCount; ++slot) {
        // Two kept points make at most a 2-point hull, whose gain is the triangle formula below:
        // the hull is built only from the third slot on.
        int hullSize = 2;
        if (slot >= 3) {
            SmallVector<Vec2, 17> kept;
            for (int s = 0; s < slot; ++s) kept.push_back(points[chosen[s]].planar);
            hullSize = convexHull(kept, hull);
        }
        int best = -1;
        double bestGain = -1, bestDistance = -1;
        for (int i = 0; i < count; ++i) {
            if (candidates[i].taken) continue;
            // Both orientations of a 2-point hull count, so a segment's gain is its triangle.
            double gain = hullSize >= 3 ? areaGain(hull, hullSize, points[i].planar)
                                        : 0.5 * std::abs(cross2(points[chosen[1]].planar - points[chosen[0]].planar,
                                                                points[i].planar - points[chosen[0]].planar));
            // Collinear sets (an edge contact) gain no area: spread along the line instead.
            const double distance = candidates[i].farthestKept;
            if (gain > bestGain || (gain == bestGain && distance > bestDistance))
                bestGain = gain, bestDistance = distance, best = i;
        }
        take(best, slot);
        if (slot + 1 < maxCount) keepDistancesTo(best);
    }
    return maxCount;
}

}  // namespace gdc::detail

#include "reduction.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Area of the convex hull of a few planar points (monotone chain).
double hullArea(SmallVector<Vec2, 17>& points) {
    const int n = static_cast<int>(points.size());
    if (n < 3) return 0;
    std::sort(points.data(), points.data() + n,
              [](const Vec2& p, const Vec2& q) { return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y()); });
    std::array<Vec2, 36> hull;
    int k = 0;
    for (int i = 0; i < n; ++i) {
        while (k >= 2 && cross2(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0) --k;
        hull[k++] = points[i];
    }
    for (int i = n - 2, lower = k + 1; i >= 0; --i) {
        while (k >= lower && cross2(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0) --k;
        hull[k++] = points[i];
    }
    double area = 0;
    for (int i = 0; i + 1 < k; ++i) area += cross2(hull[i], hull[i + 1]);
    return 0.5 * area;
}

}  // namespace

int reduceContacts(const LiftedPoints& points, int maxCount, int* chosen) {
    const int count = static_cast<int>(points.size());
    if (count <= maxCount) {
        for (int i = 0; i < count; ++i) chosen[i] = i;
        return count;
    }
    if (maxCount <= 0) return 0;
    SmallVector<char, 32> taken;
    for (int i = 0; i < count; ++i) taken.push_back(0);
    auto take = [&](int index, int slot) { chosen[slot] = index, taken[index] = 1; };

    int deepest = 0;
    for (int i = 1; i < count; ++i)
        if (points[i].depth > points[deepest].depth) deepest = i;
    take(deepest, 0);
    if (maxCount == 1) return 1;

    int farthest = -1;
    double farthestDistance = -1;
    for (int i = 0; i < count; ++i)
        if (!taken[i]) {
            double d = (points[i].planar - points[deepest].planar).squaredNorm();
            if (d > farthestDistance) farthestDistance = d, farthest = i;
        }
    take(farthest, 1);

    for (int slot = 2; slot < maxCount; ++slot) {
        int best = -1;
        double bestArea = -1, bestDistance = -1;
        for (int i = 0; i < count; ++i) {
            if (taken[i]) continue;
            SmallVector<Vec2, 17> candidate;
            for (int s = 0; s < slot; ++s) candidate.push_back(points[chosen[s]].planar);
            candidate.push_back(points[i].planar);
            double area = hullArea(candidate);
            // Collinear sets (an edge contact) have no area: spread along the line instead.
            double distance = 0;
            for (int s = 0; s < slot; ++s)
                distance = std::max(distance, (points[i].planar - points[chosen[s]].planar).squaredNorm());
            if (area > bestArea || (area == bestArea && distance > bestDistance))
                bestArea = area, bestDistance = distance, best = i;
        }
        take(best, slot);
    }
    return maxCount;
}

}  // namespace gdc::detail

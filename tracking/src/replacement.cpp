// Which stored point a full manifold gives up for the new one: Bullet's "keep the deepest, maximise
// the area" rule. Bullet scores each choice by the squared cross product of two point differences
// of its fixed 4-point layout, an area proxy that depends on the order the points were stored in;
// here the score is the exact area of the convex hull of the points that remain, for any count.
#include <gdcontact/tracking.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace gdc::tracking {
namespace {

struct HullMeasure {
    double area = 0.0;
    double perimeter = 0.0;  // of the hull polygon; twice the length for collinear points
};

double cross(const Vec2& origin, const Vec2& a, const Vec2& b) {
    return (a - origin).x() * (b - origin).y() - (a - origin).y() * (b - origin).x();
}

// Andrew's monotone chain on at most kMaxManifoldPoints + 1 points (no allocation).
HullMeasure measureHull(const Vec2* points, int count) {
    std::array<Vec2, kMaxManifoldPoints + 1> sorted;
    std::copy(points, points + count, sorted.begin());
    std::sort(sorted.begin(), sorted.begin() + count, [](const Vec2& p, const Vec2& q) {
        return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
    });
    std::array<Vec2, 2 * (kMaxManifoldPoints + 1)> hull;
    int size = 0;
    for (int i = 0; i < count; ++i) {  // lower chain
        while (size >= 2 && cross(hull[size - 2], hull[size - 1], sorted[i]) <= 0.0) --size;
        hull[size++] = sorted[i];
    }
    for (int i = count - 2, lower = size + 1; i >= 0; --i) {  // upper chain
        while (size >= lower && cross(hull[size - 2], hull[size - 1], sorted[i]) <= 0.0) --size;
        hull[size++] = sorted[i];
    }
    if (size > 1) --size;  // the last point repeats the first
    HullMeasure measure;
    for (int i = 0; i < size; ++i) {
        const Vec2& p = hull[i];
        const Vec2& q = hull[(i + 1) % size];
        measure.area += p.x() * q.y() - p.y() * q.x();
        measure.perimeter += (q - p).norm();
    }
    measure.area = 0.5 * std::abs(measure.area);
    return measure;
}

void require(bool ok, const std::string& what) {
    if (!ok) throw InvalidInput("tracking: " + what);
}

}  // namespace

double convexHullArea(const Vec2* points, int count) {
    require(points != nullptr || count == 0, "convexHullArea: null points");
    require(count >= 0 && count <= kMaxManifoldPoints + 1,
            "convexHullArea: count must be in 0.." + std::to_string(kMaxManifoldPoints + 1));
    for (int i = 0; i < count; ++i) require(points[i].allFinite(), "convexHullArea: non-finite point");
    return measureHull(points, count).area;
}

int choosePointToReplace(const Vec2* stored, const double* depths, int count, const Vec2& candidate,
                         double candidateDepth) {
    require(stored != nullptr && depths != nullptr, "choosePointToReplace: null input");
    require(count >= 1 && count <= kMaxManifoldPoints,
            "choosePointToReplace: count must be in 1.." + std::to_string(kMaxManifoldPoints));
    require(candidate.allFinite() && std::isfinite(candidateDepth),
            "choosePointToReplace: non-finite candidate");

    // The deepest stored point is protected unless the candidate is at least as deep (Bullet's
    // strict comparison: then the candidate is the deepest and every stored point is fair game).
    int deepest = -1;
    double deepestDepth = candidateDepth;
    double extent = 0.0;  // squared size of the point set, for a relative tie tolerance
    for (int i = 0; i < count; ++i) {
        require(stored[i].allFinite() && std::isfinite(depths[i]),
                "choosePointToReplace: non-finite stored point");
        if (depths[i] > deepestDepth) {
            deepest = i;
            deepestDepth = depths[i];
        }
        extent = std::max(extent, (stored[i] - candidate).squaredNorm());
    }
    // Areas that differ by less than this (relative to the set's size) are ties, decided by the
    // perimeter — so collinear sets (all areas 0) still keep their longest spread.
    const double areaTie = 1e-12 * extent;
    const double lengthTie = 1e-12 * std::sqrt(extent);

    int best = -1;
    HullMeasure bestMeasure;
    std::array<Vec2, kMaxManifoldPoints> remaining;
    for (int removed = 0; removed < count; ++removed) {
        if (removed == deepest) continue;
        int size = 0;
        for (int i = 0; i < count; ++i)
            if (i != removed) remaining[size++] = stored[i];
        remaining[size++] = candidate;
        const HullMeasure measure = measureHull(remaining.data(), size);
        const bool better = best < 0 || measure.area > bestMeasure.area + areaTie ||
                            (measure.area > bestMeasure.area - areaTie &&
                             measure.perimeter > bestMeasure.perimeter + lengthTie);
        if (better) {
            best = removed;
            bestMeasure = measure;
        }
    }
    return best;
}

}  // namespace gdc::tracking

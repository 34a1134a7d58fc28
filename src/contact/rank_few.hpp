// rankContacts for at most 4 points, all kept (a box face on a plane, two aligned boxes), in a
// header so that the half-space path, which ranks a box face's four points on every call, has it
// inlined (a call through rankContacts' dispatch was 12 % of a box–plane call). reduction.cpp's
// rankContacts dispatches to the same function.
#pragma once

#include "contact/reduction.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gdc::detail {

/// rankContacts for at most 4 points (count ≤ rule.maxCount, no given prefix), all kept: the same
/// choices, slot by slot, without the general bookkeeping — the most common case by far.
[[gnu::always_inline]] inline int rankAllOfFew(const RankPoint* points, int count, const RankingRule& rule, int* chosen) {
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
            for (int k = 2; k < 4; ++k) {
                const Vec2 offset = points[order[k]].planar - p0;  // the triangle's area: half |segment × offset|
                bestGain = std::max(bestGain, value[k] = 0.5 * std::abs(segment.x() * offset.y() - segment.y() * offset.x()));
            }
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

}  // namespace gdc::detail

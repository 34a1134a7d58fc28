// gdc::reduceBodyPairContacts: the per-body-pair contact budget (include/gdcontact/body_pair.hpp).
//
// Why: a body of several parts resting on another gets the whole support polygon of every pair of
// parts — the composites scene had 35–39 coplanar contacts between two bodies, and ODE's Dantzig
// LCP (dWorldStep) met degenerate pivots on those nearly dependent rows ("LCP internal error") and
// spent most of the step on them. A resting body needs a stable support region, not every vertex
// of it: a few points spanning the region, the deepest among them, the centre of mass above them.
//
// Mirror symmetry: the swapped call sees every normal negated. Clustering compares |dot| values
// that negation leaves bit for bit; the reduction works in a plane basis built from the cluster's
// normal turned to a canonical sign, and in coordinates relative to the cluster's first point, so
// both calls compute with the same numbers and choose the same points.
#include <gdcontact/body_pair.hpp>

#include <gdcontact/manifold.hpp>

#include "contact/feature_intersection.hpp"  // detail::planeBasis: the contact plane's basis, chosen from the normal alone
#include "contact/reduction.hpp"             // detail::rankContacts: the per-geom-pair ranking and its hysteresis

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace gdc {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The normal turned so that its largest component (the first of equal ones) is positive: the same
// vector for n and −n.
Vec3 canonicalSign(const Vec3& n) {
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(n[k]) > std::abs(n[axis])) axis = k;
    return n[axis] < 0 ? Vec3(-n) : n;
}

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

// Whether `p` lies inside the counter-clockwise polygon `hull[0, size)` (≥ 3 vertices), by more
// than `slack` from every edge (slack in length units: with slack ≥ 0 a centre on the boundary
// counts as outside; a negative slack admits the boundary).
bool strictlyInside(const std::vector<Vec2>& points, const int* hull, int size, const Vec2& p, double slack) {
    if (size < 3) return false;
    for (int i = 0; i < size; ++i) {
        const Vec2& a = points[hull[i]];
        const Vec2& b = points[hull[i + 1 == size ? 0 : i + 1]];
        const Vec2 edge = b - a;
        if (!(cross2(edge, p - a) > slack * edge.norm())) return false;
    }
    return true;
}

void requireValid(const BodyPairContact& c, int index) {
    const bool finite = c.position.allFinite() && c.normal.allFinite() && std::isfinite(c.depth);
    if (!finite || std::abs(c.normal.norm() - 1.0) > 1e-6)
        throw InvalidInput("reduceBodyPairContacts: contact " + std::to_string(index) +
                           (finite ? " has a normal that is not unit length" : " has a non-finite position, normal or depth"));
}

}  // namespace

int reduceBodyPairContacts(const BodyPairContact* contacts, int count, const BodyPairFrame& frame,
                           const Settings& settings, std::vector<int>& kept) {
    kept.clear();
    if (count < 0) throw InvalidInput("reduceBodyPairContacts: negative contact count " + std::to_string(count));
    if (count > 0 && !contacts) throw InvalidInput("reduceBodyPairContacts: null contacts");
    for (int i = 0; i < count; ++i) requireValid(contacts[i], i);
    const int budget = std::min(settings.maxBodyPairContacts, kMaxManifoldPoints);
    kept.reserve(static_cast<std::size_t>(count));
    if (budget <= 0) {
        for (int i = 0; i < count; ++i) kept.push_back(i);
        return count;
    }

    // Scratch, in two allocations: per contact its cluster, and five index lists.
    std::vector<int> indices(6 * static_cast<std::size_t>(count));
    int* clusterOf = indices.data();
    int* firstOfCluster = clusterOf + count;
    int* members = firstOfCluster + count;
    int* distinct = members + count;
    int* hull = distinct + count;  // room for 2 · count
    std::vector<Vec2> planar(static_cast<std::size_t>(count));
    std::vector<double> identity(static_cast<std::size_t>(count));
    std::vector<detail::RankPoint> ranked;

    // 1. Clusters by normal, in the order of the contacts.
    const double cosTolerance = std::cos(settings.bodyPairNormalTolerance);
    int clusters = 0;
    for (int i = 0; i < count; ++i) {
        int cluster = -1;
        for (int c = 0; c < clusters && cluster < 0; ++c)
            if (contacts[i].normal.dot(contacts[firstOfCluster[c]].normal) >= cosTolerance) cluster = c;
        if (cluster < 0) firstOfCluster[cluster = clusters++] = i;
        clusterOf[i] = cluster;
    }

    const double gravityLength = frame.gravity.norm();
    const Vec3 up = gravityLength > 0 ? Vec3(-frame.gravity / gravityLength) : Vec3::Zero();
    for (int cluster = 0; cluster < clusters; ++cluster) {
        const BodyPairContact& first = contacts[firstOfCluster[cluster]];
        const Vec3 axis = canonicalSign(first.normal);
        Vec3 u, v;
        detail::planeBasis(axis, u, v);
        int n = 0;
        Vec2 low = Vec2::Constant(1e300), high = Vec2::Constant(-1e300);
        double coordinateScale = 0;  // the largest world coordinate: the scale of its rounding
        for (int i = firstOfCluster[cluster]; i < count; ++i) {
            if (clusterOf[i] != cluster) continue;
            const Vec3 relative = contacts[i].position - first.position;
            planar[i] = Vec2(relative.dot(u), relative.dot(v));
            low = low.cwiseMin(planar[i]);
            high = high.cwiseMax(planar[i]);
            coordinateScale = std::max(coordinateScale, contacts[i].position.cwiseAbs().maxCoeff());
            members[n++] = i;
        }
        const double extent = (high - low).norm();

        // Touching points (depth exactly 0: the adapter reports a rounding-level overlap or gap
        // as 0) go where the cluster has overlapping ones. Such a row has a right-hand side of
        // exactly 0 (ERP · 0 / dt), and between two bodies moving together (resting, woken from
        // sleep, or falling side by side) an exactly zero relative velocity too: its residual w
        // starts at exactly 0, a tie ODE's Dantzig pivoting cannot break — it stops with "LCP
        // internal error, s <= 0 (s=0)" and zeroes the remaining forces, and the island falls
        // through the floor, every step again (docs/benchmarks.md, "Touching points in the
        // composites heap"). The overlapping points carry the support; the touching one adds no
        // force ODE would not get a step later, when it overlaps.
        bool overlapping = false;
        for (int k = 0; k < n && !overlapping; ++k) overlapping = contacts[members[k]].depth > 0;
        if (overlapping) {
            int m = 0;
            for (int k = 0; k < n; ++k)
                if (contacts[members[k]].depth > 0) members[m++] = members[k];
            n = m;
        }

        // The pair's rounding scale, as the per-geom-pair reduction's (1e-9 of its size): depths
        // within it are equal (an exactly resting face's corners), and so are area gains within
        // it times the extent.
        double deepestDepth = 0;
        for (int k = 0; k < n; ++k) deepestDepth = std::max(deepestDepth, contacts[members[k]].depth);
        const double tolerance = 1e-9 * (extent + deepestDepth);
        // Identity for ties: the position along the fixed generic direction, relative to the
        // cluster's first point (the same numbers in the swapped call).
        for (int k = 0; k < n; ++k)
            identity[members[k]] = (contacts[members[k]].position - first.position).dot(detail::identityDirection());
        // Deeper, with hysteresis: depths within the tolerance are equal, the tie to the larger
        // identity — so a perturbation within rounding keeps the same representative.
        auto deeper = [&](int a, int b) {
            if (std::abs(contacts[a].depth - contacts[b].depth) > tolerance) return contacts[a].depth > contacts[b].depth;
            return identity[a] > identity[b] || (identity[a] == identity[b] && a < b);
        };

        // 2. Near-duplicates: deepest first, each kept unless a kept one is within the merge
        //    distance. Candidates are found by a sweep along the first axis (the distance is
        //    tiny, so there are few): no quadratic scan of the cluster.
        //    The distance is relative to the cluster's extent, with a floor at the rounding of
        //    the points' world coordinates (1e-9 of the largest): a cluster whose only points are
        //    one point reported twice (two parts of one body on the same edge of the other) has an
        //    extent of rounding alone, and both copies are one row — duplicate rows make Dantzig's
        //    matrix singular ("LCP internal error, s <= 0" in the composites under dWorldStep).
        const double mergeDistance = std::max(kBodyPairMergeFraction * extent, 1e-9 * coordinateScale);
        std::copy(members, members + n, distinct);
        std::sort(distinct, distinct + n, [&](int a, int b) { return planar[a].x() < planar[b].x() || (planar[a].x() == planar[b].x() && a < b); });
        // Pairs closer than the merge distance: each as (loser, winner by `deeper`).
        std::vector<std::pair<int, int>> close;
        for (int a = 0; a < n; ++a)
            for (int b = a + 1; b < n && planar[distinct[b]].x() - planar[distinct[a]].x() <= mergeDistance; ++b) {
                const int p = distinct[a], q = distinct[b];
                if ((planar[p] - planar[q]).squaredNorm() <= mergeDistance * mergeDistance)
                    close.push_back(deeper(p, q) ? std::make_pair(q, p) : std::make_pair(p, q));
            }
        std::copy(members, members + n, distinct);
        std::sort(distinct, distinct + n, [&](int a, int b) {
            return contacts[a].depth > contacts[b].depth || (contacts[a].depth == contacts[b].depth && a < b);
        });
        int distinctCount = n;
        if (!close.empty()) {
            // Walk deepest first; a point goes when a close one that wins by `deeper` has not gone
            // (`deeper` is not transitive, so one pass in a fixed order decides: deterministic).
            std::vector<char> dropped(static_cast<std::size_t>(count), 0);
            for (int k = 0; k < n; ++k) {
                const int i = distinct[k];
                for (const auto& [loser, winner] : close)
                    if (loser == i && !dropped[static_cast<std::size_t>(winner)]) dropped[static_cast<std::size_t>(i)] = 1;
            }
            distinctCount = 0;
            for (int k = 0; k < n; ++k)
                if (!dropped[static_cast<std::size_t>(distinct[k])]) distinct[distinctCount++] = distinct[k];
        }
        if (distinctCount <= budget) {
            kept.insert(kept.end(), distinct, distinct + distinctCount);
            continue;
        }

        // 3. The budget, by the per-geom-pair reduction's ranking (detail::rankContacts): the
        //    deepest, the farthest from it, then by area, each with its hysteresis (gains within
        //    Settings::reductionHysteresis of the best equal, depths within rounding equal, ties
        //    to the larger identity). Not its centroid rule: that swaps in the point of largest
        //    area without a band (two nearly equal swaps flip under a 1e-9 perturbation: 45 of
        //    12 000 perturbed composites in tests/body_pair_test.cpp), and one swap cannot always
        //    restore a centre; the rule below can, and keeps the band.
        const double push = up.dot(first.normal);  // > 0: the normal (from B into A) lifts A
        const bool carriesA = push > 0 && frame.hasCentreA, carriesB = push < 0 && frame.hasCentreB;
        const bool carries = budget >= 3 && (carriesA || carriesB);
        Vec2 centre = Vec2::Zero();
        if (carries) {
            const Vec3 relative = (carriesA ? frame.centreA : frame.centreB) - first.position;
            centre = Vec2(relative.dot(u), relative.dot(v));
        }
        ranked.resize(static_cast<std::size_t>(distinctCount));
        for (int k = 0; k < distinctCount; ++k) {
            const int i = distinct[k];
            ranked[static_cast<std::size_t>(k)] = {planar[i], contacts[i].depth, identity[i]};
        }
        detail::RankingRule rule{budget, settings.reductionHysteresis, tolerance, detail::identityDirection()};
        std::array<int, kMaxManifoldPoints + 2> chosen;
        int size = detail::rankContacts(ranked.data(), distinctCount, rule, chosen.data());
        for (int k = 0; k < size; ++k) chosen[k] = distinct[chosen[k]];
        const int deepest = chosen[0];

        // The carried body's centre of mass: where it lay over the whole polygon and is not over
        // the kept one, keep the triangle of the deepest and two polygon vertices that holds it
        // (the triangles of the deepest with the polygon's edges cover the polygon), filled up by
        // area with the same band.
        if (carries) {
            const double slack = 1e-9 * extent;
            const SmallHull keptHull(planar, chosen.data(), size);
            if (!strictlyInside(planar, keptHull.vertices.data(), keptHull.size, centre, slack)) {
                std::copy(distinct, distinct + distinctCount, members);  // hullOf sorts its input
                const int wholeSize = hullOf(planar, members, distinctCount, hull);
                if (strictlyInside(planar, hull, wholeSize, centre, slack)) {
                    // The largest such triangle, with the band: areas within it are equal and go
                    // to the pair of larger identities (the larger of the two first). Not the
                    // polygon's own edges: which points on a straight side of the polygon are
                    // its vertices is decided by rounding.
                    const double keep = 1 - settings.reductionHysteresis;
                    auto triangleArea = [&](int a, int b) {
                        const int triangle[3] = {deepest, a, b};
                        const SmallHull corner(planar, triangle, 3);
                        // Closed triangles: a centre on a side from the deepest counts for both.
                        if (!strictlyInside(planar, corner.vertices.data(), corner.size, centre, -slack)) return -1.0;
                        return 0.5 * std::abs(cross2(planar[a] - planar[deepest], planar[b] - planar[deepest]));
                    };
                    // Each pair's area once (−1: the triangle does not hold the centre), then the
                    // choice within the band.
                    std::vector<double> area(static_cast<std::size_t>(distinctCount) * static_cast<std::size_t>(distinctCount), -1.0);
                    auto areaOf = [&](int j, int k) -> double& { return area[static_cast<std::size_t>(j) * static_cast<std::size_t>(distinctCount) + static_cast<std::size_t>(k)]; };
                    double largest = 0;
                    for (int j = 0; j < distinctCount; ++j)
                        for (int k = j + 1; k < distinctCount; ++k)
                            if (distinct[j] != deepest && distinct[k] != deepest)
                                largest = std::max(largest, areaOf(j, k) = triangleArea(distinct[j], distinct[k]));
                    int bestJ = -1, bestK = -1;
                    auto rank = [&](int j, int k) {
                        const double a = identity[distinct[j]], b = identity[distinct[k]];
                        return std::make_pair(std::max(a, b), std::min(a, b));
                    };
                    for (int j = 0; j < distinctCount && largest > 0; ++j)
                        for (int k = j + 1; k < distinctCount; ++k) {
                            if (distinct[j] == deepest || distinct[k] == deepest || areaOf(j, k) < keep * largest) continue;
                            if (bestJ < 0 || rank(j, k) > rank(bestJ, bestK)) bestJ = j, bestK = k;
                        }
                    if (bestJ >= 0) {
                        // The rest of the budget by area from that triangle: the ranking from a
                        // given prefix (positions in `ranked`, which follows `distinct`).
                        int positions[kMaxManifoldPoints];
                        positions[0] = static_cast<int>(std::find(distinct, distinct + distinctCount, deepest) - distinct);
                        positions[1] = bestJ, positions[2] = bestK;
                        detail::RankingRule fill = rule;
                        fill.fixedCount = 3;
                        fill.areaTolerance = tolerance * extent;
                        size = detail::rankContacts(ranked.data(), distinctCount, fill, positions);
                        for (int k = 0; k < size; ++k) chosen[k] = distinct[positions[k]];
                    }
                }
            }
        }
        kept.insert(kept.end(), chosen.begin(), chosen.begin() + size);
    }
    std::sort(kept.begin(), kept.end());
    return static_cast<int>(kept.size());
}

}  // namespace gdc

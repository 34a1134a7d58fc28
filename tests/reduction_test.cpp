// The contact set a pair hands the solver (reduction.cpp, docs/algorithm.md "The contact set the
// solver gets"), against exact answers: the deepest point first, every prefix covering a stated
// fraction of the best subset of its size (a brute-force oracle), the swapped call giving the
// mirrored set, the same points under tiny perturbations, and the centroid rule.
#include "box_poses.hpp"
#include "geometry_oracles.hpp"
#include "contact/reduction.hpp"
#include "shapes/box_shape.hpp"

#include <gdcontact/gdcontact.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

using namespace gdc;
using namespace gdc::testing;

namespace {

// Area of points in convex position (every point a hull vertex): sorted by angle about their mean,
// then the shoelace formula — a different route than the library's monotone chain.
double convexPositionArea(std::vector<Vec2> points) {
    if (points.size() < 3) return 0;
    Vec2 mean = Vec2::Zero();
    for (const Vec2& p : points) mean += p;
    mean /= static_cast<double>(points.size());
    std::sort(points.begin(), points.end(), [&](const Vec2& a, const Vec2& b) {
        return std::atan2(a.y() - mean.y(), a.x() - mean.x()) < std::atan2(b.y() - mean.y(), b.x() - mean.x());
    });
    double twice = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec2& a = points[i];
        const Vec2& b = points[(i + 1) % points.size()];
        twice += a.x() * b.y() - a.y() * b.x();
    }
    return 0.5 * std::abs(twice);
}

// The largest area of any k of `points` (convex position), by trying every subset.
double bestSubsetArea(const std::vector<Vec2>& points, int k) {
    const int n = static_cast<int>(points.size());
    double best = 0;
    std::vector<int> pick(k);
    std::function<void(int, int)> choose = [&](int from, int depth) {
        if (depth == k) {
            std::vector<Vec2> subset;
            for (int i : pick) subset.push_back(points[i]);
            best = std::max(best, convexPositionArea(subset));
            return;
        }
        for (int i = from; i < n; ++i) pick[depth] = i, choose(i + 1, depth + 1);
    };
    choose(0, 0);
    return best;
}

// A random convex polygon: n points on a random ellipse at random angles, random depths.
detail::LiftedPoints randomPolygon(std::mt19937& random, int n) {
    std::uniform_real_distribution<double> unit(0, 1);
    const double a = 0.2 + unit(random), b = 0.2 + unit(random), turn = 6.283 * unit(random);
    std::vector<double> angles;
    for (int i = 0; i < n; ++i) angles.push_back(6.283185307179586 * unit(random));
    std::sort(angles.begin(), angles.end());
    detail::LiftedPoints points;
    for (double t : angles) {
        const Vec2 local(a * std::cos(t), b * std::sin(t));
        const Vec2 q(std::cos(turn) * local.x() - std::sin(turn) * local.y(),
                     std::sin(turn) * local.x() + std::cos(turn) * local.y());
        points.push_back({Vec3(q.x(), q.y(), 0), 0.01 * unit(random), q});
    }
    return points;
}

detail::RankingRule ruleFor(int maxCount, double hysteresis) {
    return detail::RankingRule{maxCount, hysteresis, 1e-12, detail::identityDirection()};
}

std::vector<Vec2> planarOf(const detail::LiftedPoints& points, const int* chosen, int count) {
    std::vector<Vec2> out;
    for (int i = 0; i < count; ++i) out.push_back(points[chosen[i]].planar);
    return out;
}

}  // namespace

TEST_CASE("The ranked contact set starts with the deepest point, whatever the hysteresis") {
    std::mt19937 random(7);
    for (double hysteresis : {0.0, 0.01, 0.1})
        for (int trial = 0; trial < 2000; ++trial) {
            const detail::LiftedPoints points = randomPolygon(random, 3 + trial % 10);
            double deepest = -INFINITY;
            for (const auto& p : points) deepest = std::max(deepest, p.depth);
            for (int budget : {1, 2, 4, 16}) {
                int chosen[kMaxManifoldPoints];
                const int count = detail::rankContacts(points, ruleFor(budget, hysteresis), chosen);
                REQUIRE(count == std::min(budget, static_cast<int>(points.size())));
                INFO("hysteresis " << hysteresis << " budget " << budget);
                REQUIRE(points[chosen[0]].depth >= deepest - 1e-12);  // the rule's tolerance: rounding
                std::vector<int> sorted(chosen, chosen + count);
                std::sort(sorted.begin(), sorted.end());
                REQUIRE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());  // no point twice
            }
        }
}

// Every prefix of the ranked set is itself a good set. The bound is exact for k = 2 (the point
// farthest from any point p is at least half the diameter away, by the triangle inequality, less
// the hysteresis band) and, for k = 3, 4 and 6, just below the least ratio found over these 3000
// random polygons (0.497, 0.695 and 0.903; the greedy choice is pinned to the deepest point, which
// may lie anywhere on the polygon), against the best k-subset found by trying every subset.
TEST_CASE("Every prefix of the ranked set covers a stated fraction of the best subset of its size") {
    std::mt19937 random(11);
    double leastRatio[5] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY};
    for (int trial = 0; trial < 3000; ++trial) {
        const detail::LiftedPoints points = randomPolygon(random, 5 + trial % 8);
        const double hysteresis = trial % 2 ? 0.0 : 0.01;
        int chosen[kMaxManifoldPoints];
        const int count = detail::rankContacts(points, ruleFor(8, hysteresis), chosen);
        REQUIRE(count == std::min(8, static_cast<int>(points.size())));
        std::vector<Vec2> all;
        for (const auto& p : points) all.push_back(p.planar);
        double diameter = 0;
        for (const Vec2& p : all)
            for (const Vec2& q : all) diameter = std::max(diameter, (p - q).norm());
        const double segment = (points[chosen[1]].planar - points[chosen[0]].planar).norm();
        leastRatio[2] = std::min(leastRatio[2], segment / diameter);
        REQUIRE(segment >= (1 - hysteresis) * 0.5 * diameter);
        for (int k : {3, 4}) {
            const double ratio = convexPositionArea(planarOf(points, chosen, k)) / bestSubsetArea(all, k);
            leastRatio[k] = std::min(leastRatio[k], ratio);
            INFO("trial " << trial << " k " << k);
            REQUIRE(ratio >= (k == 3 ? 0.45 : 0.65));
        }
        // The whole budget: at most what the best subset of its size covers, at least 70 % of it.
        if (static_cast<int>(points.size()) > 6) {
            const double ratio = convexPositionArea(planarOf(points, chosen, 6)) / bestSubsetArea(all, 6);
            leastRatio[0] = std::min(leastRatio[0], ratio);
            REQUIRE(ratio >= 0.85);
            REQUIRE(ratio <= 1 + 1e-12);
        }
    }
    WARN("least ratio to the best subset: 2 points (of the diameter) " << leastRatio[2] << ", 3 points "
                                                                        << leastRatio[3] << ", 4 points "
                                                                        << leastRatio[4] << ", 6 points " << leastRatio[0]);
}

TEST_CASE("The centroid rule: a centroid inside the polygon stays inside the kept points") {
    // A long thin hexagon whose largest-area quadrilateral through the deepest point (its left
    // tip) leaves out a sliver at the right end, where the upper body's centroid projects.
    detail::LiftedPoints points;
    auto add = [&](double x, double y, double depth) { points.push_back({Vec3(x, y, 0), depth, Vec2(x, y)}); };
    add(-1.0, 0.0, 0.02);   // the deepest: the left tip
    add(-0.5, -0.3, 0.01);
    add(0.5, -0.3, 0.01);
    add(1.0, -0.05, 0.01);
    add(1.0, 0.05, 0.01);
    add(0.5, 0.3, 0.01);
    add(-0.5, 0.3, 0.01);
    const Vec2 centroid(0.97, 0.0);
    int chosen[kMaxManifoldPoints];
    detail::RankingRule rule = ruleFor(4, 0.0);
    const int plain = detail::rankContacts(points, rule, chosen);
    REQUIRE(plain == 4);
    auto keptContains = [&](const Vec2& c) {
        // Point in convex polygon: inside iff the kept points' area equals the sum of the
        // triangles c makes with the hull's edges (sorted by angle about their mean).
        std::vector<Vec2> kept = planarOf(points, chosen, 4);
        const double area = convexPositionArea(kept);
        Vec2 mean = Vec2::Zero();
        for (const Vec2& p : kept) mean += p;
        mean /= 4;
        std::sort(kept.begin(), kept.end(), [&](const Vec2& a, const Vec2& b) {
            return std::atan2(a.y() - mean.y(), a.x() - mean.x()) < std::atan2(b.y() - mean.y(), b.x() - mean.x());
        });
        double sum = 0;
        for (int i = 0; i < 4; ++i) sum += convexPositionArea({kept[i], kept[(i + 1) % 4], c});
        return sum <= area * (1 + 1e-12);
    };
    REQUIRE_FALSE(keptContains(centroid));  // the greedy set alone leaves the centroid out
    rule.centroids = &centroid;
    rule.centroidCount = 1;
    const int withRule = detail::rankContacts(points, rule, chosen);
    REQUIRE(withRule == 4);
    CHECK(chosen[0] == 0);  // the deepest point is never swapped out
    CHECK(keptContains(centroid));
    // A centroid outside the whole polygon (the body overhangs: it tips whatever is kept) changes nothing.
    const Vec2 outside(1.5, 0.0);
    rule.centroids = &outside;
    int unchanged[kMaxManifoldPoints];
    detail::rankContacts(points, rule, unchanged);
    int reference[kMaxManifoldPoints];
    detail::rankContacts(points, ruleFor(4, 0.0), reference);
    CHECK(std::equal(unchanged, unchanged + 4, reference));
}

namespace {

// Whether two manifolds hold the same points (positions within `tolerance`, depths within it).
bool samePointSets(const Manifold& a, const Manifold& b, double tolerance) {
    if (a.pointCount != b.pointCount) return false;
    for (int i = 0; i < a.pointCount; ++i) {
        bool found = false;
        for (int j = 0; j < b.pointCount && !found; ++j)
            found = (a.points[i].position - b.points[j].position).norm() <= tolerance &&
                    std::abs(a.points[i].depth - b.points[j].depth) <= tolerance;
        if (!found) return false;
    }
    return true;
}

bool sameOrder(const Manifold& a, const Manifold& b, double tolerance) {
    if (a.pointCount != b.pointCount) return false;
    for (int i = 0; i < a.pointCount; ++i)
        if ((a.points[i].position - b.points[i].position).norm() > tolerance) return false;
    return true;
}

}  // namespace

// Resting face pairs that make more points than the budget: a box turned about the normal on a
// bigger box (an octagon of 8 points), slightly tilted, over random turns and tilts.
TEST_CASE("The swapped call gives the mirrored set, in the same order") {
    std::mt19937 random(3);
    std::uniform_real_distribution<double> unit(-1, 1);
    const Polytope lower = Polytope::box(Vec3(1.0, 0.8, 0.5));
    const Polytope upper = Polytope::box(Vec3(0.6, 0.5, 0.3));
    std::vector<Vec3> prism;  // a hexagonal prism: hexagon over an 8-point octagon-like clip
    for (int i = 0; i < 6; ++i)
        for (double z : {-0.3, 0.3}) prism.push_back(Vec3(0.7 * std::cos(1.0471975511965976 * i), 0.6 * std::sin(1.0471975511965976 * i), z));
    const Polytope hull = Polytope::fromPoints(prism);
    Settings budgetFour;  // so that most of these polygons are reduced
    budgetFour.maxContacts = 4;
    int reduced = 0, sameOrders = 0, total = 0;
    for (const Polytope* top : {&upper, &hull})
        for (int trial = 0; trial < 500; ++trial) {
            const Mat3 turn = rotationAbout(Vec3::UnitZ(), 3.14159 * unit(random)) *
                              rotationAbout(Vec3(unit(random), unit(random), 0).normalized() + Vec3(0, 0, 1e-9),
                                            0.01 * unit(random));
            const Pose poseA = makePose(Vec3(0.1 * unit(random), 0.1 * unit(random), 0));
            const Pose poseB = makePose(Vec3(0.1 * unit(random), 0.1 * unit(random), 0.8 - 0.003), turn);
            const Manifold ab = collide(lower, poseA, *top, poseB, budgetFour);
            const Manifold ba = collide(*top, poseB, lower, poseA, budgetFour);
            REQUIRE(ab.pointCount > 0);
            INFO("trial " << trial);
            REQUIRE(ba.normal.isApprox(-ab.normal, 1e-12));
            REQUIRE(samePointSets(ab, ba, 1e-9));
            CHECK(ab.pointCount <= budgetFour.maxContacts);
            // The first point is the deepest of the whole polygon (every point kept: budget 16),
            // within rounding (1e-9 of the pair's size).
            Settings all;
            all.maxContacts = kMaxManifoldPoints;
            const double deepest = collide(lower, poseA, *top, poseB, all).maxDepth();
            CHECK(ab.points[0].depth >= deepest - 1e-8);
            CHECK(ab.points[0].depth <= deepest);
            ++total;
            reduced += ab.pointCount == budgetFour.maxContacts ? 1 : 0;
            sameOrders += sameOrder(ab, ba, 1e-9) ? 1 : 0;
        }
    WARN("swapped calls: " << total << " poses, " << reduced << " at the budget, the same order in " << sameOrders);
    CHECK(reduced > total / 2);
    // The order is decided by depth, distance and area (the same in either frame) and, within the
    // hysteresis band, by each point's position along a fixed world direction (the same point in
    // either call): the same order, but for ties within rounding, which these poses do not make.
    CHECK(sameOrders == total);
}

TEST_CASE("A tiny perturbation of a resting face pair keeps the same contact points") {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(-1, 1);
    const Polytope lower = Polytope::box(Vec3(1.0, 0.8, 0.5));
    const Polytope upper = Polytope::box(Vec3(0.6, 0.5, 0.3));
    int checked = 0, sameOrders = 0;
    for (int trial = 0; trial < 500; ++trial) {
        const Mat3 turn = rotationAbout(Vec3::UnitZ(), 3.14159 * unit(random));
        const Pose poseA = makePose(Vec3::Zero());
        const Pose poseB = makePose(Vec3(0.05 * unit(random), 0.05 * unit(random), 0.8 - 0.001), turn);
        Settings budgetFour;  // an octagon reduced to 4: the choice the perturbation must not change
        budgetFour.maxContacts = 4;
        const Manifold reference = collide(lower, poseA, upper, poseB, budgetFour);
        REQUIRE(reference.pointCount > 0);
        for (int k = 0; k < 10; ++k) {
            // 1e-9 relative: the positions moved by 1e-9 of the size, the rotation turned by 1e-9 rad.
            Pose moved = poseB;
            moved.position += 1e-9 * Vec3(unit(random), unit(random), unit(random));
            moved.rotation = rotationAbout(Vec3(unit(random), unit(random), unit(random)), 1e-9) * moved.rotation;
            const Manifold perturbed = collide(lower, poseA, upper, moved, budgetFour);
            INFO("trial " << trial << " perturbation " << k);
            REQUIRE(samePointSets(reference, perturbed, 1e-7));
            sameOrders += sameOrder(reference, perturbed, 1e-7) ? 1 : 0;
            ++checked;
        }
    }
    // Exactly resting faces have equal depths at every corner: the first point is the tie's
    // identity, the same under any perturbation within the band.
    CHECK(sameOrders == checked);
}

// The certificate that lets the ranking take each free point's gain from its two neighbours on the
// kept hull (isStrictlyConvexCycle), against exact answers: convex polygons counter-clockwise in
// any rotation of their order are certified; clockwise order, a second winding (a pentagram), a
// repeated point, a point exactly on an edge, a reflex vertex and a turn within rounding are not.
TEST_CASE("Only a strictly convex counter-clockwise cycle is certified for the ranking's neighbour gains") {
    auto cycle = [](std::vector<Vec2> planar) {
        std::vector<detail::RankPoint> points;
        for (const Vec2& q : planar) points.push_back({q, 0, 0});
        return detail::isStrictlyConvexCycle(points.data(), static_cast<int>(points.size()));
    };
    const std::vector<Vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    CHECK(cycle(square));
    CHECK(cycle({{1, 1}, {0, 1}, {0, 0}, {1, 0}}));                  // started elsewhere
    CHECK(cycle({{0, 0}, {2, 0}, {0, 1}}));                          // a triangle
    CHECK_FALSE(cycle({{0, 0}, {0, 1}, {1, 1}, {1, 0}}));            // clockwise
    CHECK_FALSE(cycle({{0, 0}, {1, 0}, {2, 0}, {1, 1}}));            // a point on an edge
    CHECK_FALSE(cycle({{0, 0}, {1, 0}, {1, 0}, {1, 1}, {0, 1}}));    // a repeated point
    CHECK_FALSE(cycle({{0, 0}, {1, 0}, {0.5, 0.5}, {1, 1}, {0, 1}}));  // a reflex vertex
    CHECK_FALSE(cycle({{0, 0}, {1, 0}}));                            // a segment
    CHECK_FALSE(cycle({{0, 0}, {1, 0}, {2, 1e-14}, {1, 1}}));        // a turn within the rounding margin
    CHECK(cycle({{0, 0}, {1, 0}, {2, 1e-9}, {1, 1}}));               // a small turn beyond it
    // A regular pentagon visited twice around (every turn left, the boundary winding twice).
    std::vector<Vec2> pentagram;
    for (int i = 0; i < 5; ++i) {
        const double angle = 6.283185307179586 * (2 * i % 5) / 5;
        pentagram.push_back({std::cos(angle), std::sin(angle)});
    }
    CHECK_FALSE(cycle(pentagram));
    // An octagon in cyclic order and its order reversed.
    std::vector<Vec2> octagon;
    for (int i = 0; i < 8; ++i) octagon.push_back({std::cos(0.3 + 0.785 * i), std::sin(0.3 + 0.785 * i)});
    CHECK(cycle(octagon));
    std::reverse(octagon.begin(), octagon.end());
    CHECK_FALSE(cycle(octagon));
}

// The ranking of lifted points (emitManifold's entry) against exact answers, on 130000 sets of every
// kind the pipeline hands it and their near misses: the clips of two rectangles (at any angle,
// nearly aligned), regular octagons and squares (exact when axis-aligned: every gain tied),
// rectangles with their edges' midpoints (collinear triples) and repeated points, collinear points
// with duplicates, octagons whose radii differ within the hysteresis band, random polygons with
// tilted depths; depths all equal, tilted, or the runner-up exactly at the first pick's band and
// just inside or outside it; the identity direction generic, along x (ties in pairs) or along z
// (every identity 0); every budget 1..n+1, three hysteresis bands, 0–2 centroids. Each ranking:
// min(budget, n) distinct indices, a deepest point (within the tolerance) first, and — for sets in
// convex position without centroids or a wide band — its first 3 and 4 points covering the stated
// fraction of the best subset of that size (a brute-force oracle, as above).
TEST_CASE("The ranking of lifted points keeps distinct points, the deepest first, and most of the best area") {
    std::mt19937 random(2031);
    std::uniform_real_distribution<double> unit(0, 1);
    auto rotated = [](const Vec2& p, double angle) {
        return Vec2(std::cos(angle) * p.x() - std::sin(angle) * p.y(), std::sin(angle) * p.x() + std::cos(angle) * p.y());
    };
    long sets = 0, compared = 0, byCycle = 0, areaChecked = 0;
    double leastRatio[5] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY};
    for (int trial = 0; trial < 130000; ++trial) {
        const int kind = trial % 7;
        const double scale = 0.1 + unit(random), turn = trial % 11 == 0 ? 0.0 : 6.283185307179586 * unit(random);
        std::vector<Vec2> planar;
        if (kind == 0) {  // the clip of two rectangles, at any angle or nearly aligned
            const double w1 = 0.2 + unit(random), h1 = 0.2 + unit(random), w2 = 0.2 + unit(random), h2 = 0.2 + unit(random);
            const double angle = trial % 2 ? 6.283185307179586 * unit(random) : std::pow(10.0, -9 + 8 * unit(random));
            const Vec2 offset(0.6 * (unit(random) - 0.5), 0.6 * (unit(random) - 0.5));
            Vec2 first[4] = {{-w1, -h1}, {w1, -h1}, {w1, h1}, {-w1, h1}};
            Vec2 second[4] = {{-w2, -h2}, {w2, -h2}, {w2, h2}, {-w2, h2}};
            for (Vec2& p : first) p = rotated(scale * p, turn);
            for (Vec2& p : second) p = rotated(scale * (rotated(p, angle) + offset), turn);
            for (const Vec2& p : detail::clipConvexPolygon(second, 4, first, 4, 1e-9)) planar.push_back(p);
        } else if (kind == 1) {  // a regular octagon or a square
            const int corners = trial % 2 ? 8 : 4;
            for (int i = 0; i < corners; ++i)
                planar.push_back(rotated(scale * Vec2(std::cos(6.283185307179586 * i / corners), std::sin(6.283185307179586 * i / corners)), turn));
        } else if (kind == 2) {  // a rectangle with its edges' midpoints, some points repeated
            const double w = scale, h = scale * (0.2 + unit(random));
            for (const Vec2& q : {Vec2(-w, -h), Vec2(0, -h), Vec2(w, -h), Vec2(w, 0), Vec2(w, h), Vec2(0, h), Vec2(-w, h), Vec2(-w, 0)})
                planar.push_back(rotated(q, turn));
            if (trial % 3 == 0) planar.push_back(planar[2]), planar.push_back(planar[5]);
        } else if (kind == 3) {  // collinear with duplicates
            for (int i = 0; i < 5 + trial % 8; ++i) planar.push_back(rotated(Vec2(scale * std::floor(5 * unit(random)), 0), turn));
        } else if (kind == 4) {  // an octagon whose radii differ by a fraction near the hysteresis band
            for (int i = 0; i < 8; ++i) {
                const double angle = 6.283185307179586 * i / 8, radius = scale * (1 + 0.02 * (unit(random) - 0.5));
                planar.push_back(rotated(Vec2(radius * std::cos(angle), radius * std::sin(angle)), turn));
            }
        } else {  // a random convex polygon, started anywhere
            for (const auto& q : randomPolygon(random, 5 + trial % 12)) planar.push_back(scale * q.planar);
            std::rotate(planar.begin(), planar.begin() + static_cast<int>(unit(random) * planar.size()) % planar.size(), planar.end());
        }
        const int n = static_cast<int>(planar.size());
        if (n < 1) continue;
        // Depths: equal (a resting face), tilted (affine), or (kind 6) tilted with the runner-up
        // exactly at the first pick's band, just inside or just outside it.
        const double tolerance = trial % 2 ? std::ldexp(1.0, -30) : 0.0;
        const Vec2 tilt(unit(random) - 0.5, unit(random) - 0.5);
        std::vector<double> depths;
        for (const Vec2& q : planar) depths.push_back(trial % 4 == 0 ? 0.005 : 0.005 + 0.01 * tilt.dot(q));
        if (kind == 6 && n >= 2) {
            const int deepest = static_cast<int>(std::max_element(depths.begin(), depths.end()) - depths.begin());
            const int other = (deepest + 1 + trial % (n - 1)) % n;
            const double band = depths[static_cast<size_t>(deepest)] - tolerance;
            depths[static_cast<size_t>(other)] = trial % 3 == 0 ? band : std::nextafter(band, trial % 3 == 1 ? 1.0 : -1.0);
        }
        // The points: positions in the plane z = 0.1 (the identity a dot product with them).
        detail::LiftedPoints lifted;
        for (int i = 0; i < n; ++i) {
            const Vec2& q = planar[static_cast<size_t>(i)];
            lifted.push_back({Vec3(q.x(), q.y(), 0.1), depths[static_cast<size_t>(i)], q});
        }
        const Vec3 direction = trial % 5 == 0 ? Vec3::UnitX() : trial % 5 == 1 ? Vec3::UnitZ() : detail::identityDirection();
        std::vector<detail::RankPoint> points;
        for (const auto& p : lifted) points.push_back({p.planar, p.depth, p.position.dot(direction)});
        ++sets;
        const bool cycle = detail::isStrictlyConvexCycle(points.data(), n);
        const double deepest = *std::max_element(depths.begin(), depths.end());
        const bool convexPosition = kind == 0 || kind == 1 || kind == 4 || kind == 5 || kind == 6;
        const double hysteresis = trial % 3 == 0 ? 0.0 : trial % 3 == 1 ? 0.01 : 0.1;
        const Vec2 centroids[2] = {rotated(Vec2(0.1 * scale * (unit(random) - 0.5), 0), turn),
                                   rotated(Vec2(scale * (unit(random) - 0.5), 0.5 * scale), turn)};
        for (int budget = 1; budget <= n + 1; ++budget) {
            detail::RankingRule rule{budget, hysteresis, tolerance, direction};
            rule.centroids = centroids;
            rule.centroidCount = (trial / 7) % 3;
            int ours[kMaxManifoldPoints];
            const int count = detail::rankContacts(lifted, rule, ours);
            ++compared;
            const int wanted = std::min({budget, n, kMaxManifoldPoints});
            byCycle += cycle && n >= 5 && n <= kMaxManifoldPoints && wanted - 3 - (wanted == n ? 1 : 0) >= 1;
            INFO("trial " << trial << " kind " << kind << " points " << n << " budget " << budget << " cycle " << cycle);
            REQUIRE(count == wanted);
            bool seen[kMaxManifoldPoints + 2] = {};
            for (int i = 0; i < count; ++i) {
                REQUIRE(ours[i] >= 0);
                REQUIRE(ours[i] < n);
                REQUIRE_FALSE(seen[ours[i]]);
                seen[ours[i]] = true;
            }
            REQUIRE(depths[static_cast<size_t>(ours[0])] >= deepest - tolerance);
            if (convexPosition && rule.centroidCount == 0 && hysteresis <= 0.01 && n <= 12 && budget == n + 1) {
                ++areaChecked;
                for (int k : {3, 4}) {
                    if (n <= k) continue;
                    const double best = bestSubsetArea(planar, k);
                    if (!(best > 1e-9 * scale * scale)) continue;  // a sliver: every subset is as good
                    const double ratio = convexPositionArea(planarOf(lifted, ours, k)) / best;
                    leastRatio[k] = std::min(leastRatio[k], ratio);
                    INFO("k " << k);
                    REQUIRE(ratio >= (k == 3 ? 0.45 : 0.65));
                }
            }
        }
    }
    WARN(sets << " sets; " << compared << " rankings of lifted points, " << byCycle << " of certified cycles; "
              << areaChecked << " against the best subsets: least ratio 3 points " << leastRatio[3] << ", 4 points "
              << leastRatio[4]);
    CHECK(compared >= 1000000);
    CHECK(byCycle >= 300000);
    CHECK(areaChecked >= 10000);
}

// The replacement rule in isolation, against brute-force oracles: the convex hull area, the
// protection of the deepest point, and the largest-area choice.
#include <gdcontact/tracking.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using gdc::Vec2;
using gdc::tracking::choosePointToReplace;
using gdc::tracking::convexHullArea;

namespace {

// Hull area by brute force, independent of the library's monotone chain: a directed pair (p, q) is
// a hull edge (counter-clockwise) when no point lies to its right and no point lies on its line
// beyond the segment; the hull's area is half the sum of cross(p, q) over those edges.
double bruteForceHullArea(const std::vector<Vec2>& points) {
    std::vector<Vec2> unique;  // duplicates would count an edge twice
    for (const Vec2& p : points)
        if (std::none_of(unique.begin(), unique.end(), [&](const Vec2& q) { return (p - q).norm() < 1e-15; }))
            unique.push_back(p);
    double twice = 0.0;
    const int m = static_cast<int>(unique.size());
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) {
            if (i == j) continue;
            const Vec2 edge = unique[j] - unique[i];
            bool hullEdge = true, strictlyLeft = false;
            for (int k = 0; k < m && hullEdge; ++k) {
                if (k == i || k == j) continue;
                const Vec2 to = unique[k] - unique[i];
                const double side = edge.x() * to.y() - edge.y() * to.x();
                if (side < -1e-12) hullEdge = false;
                if (side > 1e-12) strictlyLeft = true;
                // A collinear point beyond the segment means (i, j) is not a whole hull edge.
                if (std::abs(side) <= 1e-12 && (to.dot(edge) < 0.0 || to.dot(edge) > edge.squaredNorm()))
                    hullEdge = false;
            }
            if (hullEdge && strictlyLeft)
                twice += unique[i].x() * unique[j].y() - unique[i].y() * unique[j].x();
        }
    return 0.5 * twice;
}

std::vector<Vec2> randomPoints(std::mt19937& random, int count) {
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    std::vector<Vec2> points;
    for (int i = 0; i < count; ++i) points.emplace_back(coordinate(random), coordinate(random));
    return points;
}

}  // namespace

TEST_CASE("convex hull area against exact answers and a brute-force oracle", "[tracking]") {
    const std::vector<Vec2> squareWithInside{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}, {0.2, 0.7}};
    CHECK(convexHullArea(squareWithInside.data(), 6) == Approx(1.0).margin(1e-15));
    const std::vector<Vec2> collinear{{0, 0}, {1, 1}, {2, 2}, {0.5, 0.5}};
    CHECK(convexHullArea(collinear.data(), 4) == 0.0);
    const std::vector<Vec2> repeated{{1, 1}, {1, 1}, {1, 1}};
    CHECK(convexHullArea(repeated.data(), 3) == 0.0);
    const std::vector<Vec2> triangle{{0, 0}, {4, 0}, {0, 3}, {0, 0}};
    CHECK(convexHullArea(triangle.data(), 4) == Approx(6.0).margin(1e-14));
    CHECK(convexHullArea(nullptr, 0) == 0.0);

    std::mt19937 random(11);
    for (int trial = 0; trial < 300; ++trial) {
        const int count = 3 + trial % 15;  // 3 … 17 points
        const std::vector<Vec2> points = randomPoints(random, count);
        CHECK(convexHullArea(points.data(), count) == Approx(bruteForceHullArea(points)).margin(1e-12));
    }
}

TEST_CASE("the replaced point leaves the largest area and is never the deepest", "[tracking]") {
    std::mt19937 random(3);
    std::uniform_real_distribution<double> depth(0.0, 0.01);
    for (int trial = 0; trial < 500; ++trial) {
        const int count = 2 + trial % 7;  // 2 … 8 stored points
        const std::vector<Vec2> stored = randomPoints(random, count);
        const Vec2 candidate = randomPoints(random, 1)[0];
        std::vector<double> depths;
        for (int i = 0; i < count; ++i) depths.push_back(depth(random));
        const double candidateDepth = depth(random);

        const int chosen =
            choosePointToReplace(stored.data(), depths.data(), count, candidate, candidateDepth);
        REQUIRE(chosen >= 0);
        REQUIRE(chosen < count);
        const int deepest = static_cast<int>(std::max_element(depths.begin(), depths.end()) - depths.begin());
        const bool deepestProtected = depths[deepest] > candidateDepth;
        if (deepestProtected) CHECK(chosen != deepest);

        auto areaWithout = [&](int removed) {
            std::vector<Vec2> kept{candidate};
            for (int i = 0; i < count; ++i)
                if (i != removed) kept.push_back(stored[i]);
            return bruteForceHullArea(kept);
        };
        double best = 0.0;
        for (int removed = 0; removed < count; ++removed)
            if (!(deepestProtected && removed == deepest)) best = std::max(best, areaWithout(removed));
        CHECK(areaWithout(chosen) == Approx(best).margin(1e-12));
    }
}

TEST_CASE("the replacement rule on the exact cases Bullet's rule is about", "[tracking]") {
    // Four corners of a unit square; the new point lies just inside corner 2. Replacing corner 2
    // by it keeps almost the whole square; any other choice loses a quarter to a half of it.
    const std::vector<Vec2> corners{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const std::vector<double> equal{0.01, 0.01, 0.01, 0.01};
    CHECK(choosePointToReplace(corners.data(), equal.data(), 4, Vec2(0.9, 0.9), 0.01) == 2);

    // Same, but corner 2 is the deepest point: it must stay. Removing corner 0, 1 or 3 leaves a
    // triangle of three corners (area 0.5, perimeter 2 + √2) with the new point inside or on an
    // edge: a three-way tie, which goes to the lowest index.
    const std::vector<double> cornerTwoDeepest{0.01, 0.01, 0.05, 0.01};
    CHECK(choosePointToReplace(corners.data(), cornerTwoDeepest.data(), 4, Vec2(0.9, 0.9), 0.01) == 0);

    // A new point deeper than every stored one: the deepest stored point loses its protection.
    CHECK(choosePointToReplace(corners.data(), cornerTwoDeepest.data(), 4, Vec2(0.9, 0.9), 0.06) == 2);

    // Collinear points (a box edge resting on a face): every area is 0 and the longest spread
    // wins. With the new point at x = 1.2, removing 0.3, 0.6 or 1.0 keeps the span [0, 1.2]
    // (a tie, lowest index: 1); removing 0 would shrink it to [0.3, 1.2].
    const std::vector<Vec2> onALine{{0, 0}, {0.3, 0}, {0.6, 0}, {1, 0}};
    CHECK(choosePointToReplace(onALine.data(), equal.data(), 4, Vec2(1.2, 0), 0.01) == 1);

    // One stored point deeper than the candidate and nothing else: nothing may be replaced.
    const double deep = 0.05;
    CHECK(choosePointToReplace(corners.data(), &deep, 1, Vec2(0.5, 0.5), 0.01) == -1);
    const double shallow = 0.001;
    CHECK(choosePointToReplace(corners.data(), &shallow, 1, Vec2(0.5, 0.5), 0.01) == 0);
}

TEST_CASE("the replacement rule rejects bad input", "[tracking]") {
    const std::vector<Vec2> points{{0, 0}, {1, 0}};
    const std::vector<double> depths{0.0, 0.0};
    CHECK_THROWS_AS(choosePointToReplace(points.data(), depths.data(), 0, Vec2(0, 0), 0.0),
                    gdc::InvalidInput);
    CHECK_THROWS_AS(choosePointToReplace(nullptr, depths.data(), 2, Vec2(0, 0), 0.0), gdc::InvalidInput);
    CHECK_THROWS_AS(choosePointToReplace(points.data(), depths.data(), 2, Vec2(NAN, 0), 0.0),
                    gdc::InvalidInput);
    CHECK_THROWS_AS(convexHullArea(points.data(), -1), gdc::InvalidInput);
}

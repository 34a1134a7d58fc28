// Where the hull's stage-1 enumeration (src/hull_gauge.cpp) stops paying: instructions per growth
// distance of the enumeration and of the GJK ray cast, for two copies of a Fibonacci-sphere hull of
// n vertices (3n − 6 edges) in 64 random orientations, placed along a random direction to overlap by
// 1 % of their radius. Run under callgrind, one contender and size per run:
//
//   valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file=/dev/null \
//            bench_hull_gauge_crossover N enumeration|cast
//
// and divide callgrind's "Collected" by the calls printed. kHullGaugeMaxEdgePairs is set from it.
#include "geometry/growth_distance.hpp"
#include "geometry/hull_gauge.hpp"
#include "geometry/minkowski.hpp"

#include <valgrind/callgrind.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

int main(int argc, char** argv) {
    using namespace gdc;
    if (argc != 3) {
        std::fprintf(stderr, "usage: bench_hull_gauge_crossover N enumeration|cast\n");
        return 2;
    }
    const int n = std::atoi(argv[1]);
    const bool cast = std::string(argv[2]) == "cast";
    std::vector<Vec3> points;
    for (int i = 0; i < n; ++i) {
        const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
        points.emplace_back(0.5 * r * std::cos(phi), 0.5 * r * std::sin(phi), 0.5 * z);
    }
    const Polytope hull = Polytope::fromPoints(points);
    const Settings settings;
    std::mt19937 random(1);
    std::normal_distribution<double> gauss;
    std::vector<Pose> poses;
    for (int i = 0; i < 64; ++i) {
        const Eigen::Quaterniond q(gauss(random), gauss(random), gauss(random), gauss(random));
        const Vec3 direction = Vec3(gauss(random), gauss(random), gauss(random)).normalized();
        Pose pose{q.normalized().toRotationMatrix(), Vec3::Zero()};
        const detail::SeparationAlong apart = detail::separationAlong(hull, hull, pose, direction, settings);
        pose.position = (apart.distance - 0.01 * hull.radius()) * direction;
        poses.push_back(pose);
    }
    constexpr int kCycles = 10;
    double sum = 0;
    CALLGRIND_TOGGLE_COLLECT;
    for (int cycle = 0; cycle < kCycles; ++cycle)
        for (const Pose& pose : poses) {
            const detail::MinkowskiDifference pair(hull, hull, pose, settings.bruteForceSupportLimit);
            sum += cast ? detail::growthDistance(pair, settings, false).growth : detail::hullGrowth(pair).growth;
        }
    CALLGRIND_TOGGLE_COLLECT;
    std::printf("%d vertices, %zu edges (%zu edge pairs), %s: %d calls (checksum %.6f)\n", n, hull.edges().size(),
                hull.edges().size() * hull.edges().size(), cast ? "cast" : "enumeration", kCycles * 64, sum);
    return 0;
}

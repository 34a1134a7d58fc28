// A driver for profilers (perf, callgrind): runs one benchmark configuration in a loop, with only
// that configuration's set-up, so that a profile shows where the time of the query goes.
//   bench_profile CASE [CPU-SECONDS]
// Cases: the targets of docs/benchmarks.md that a profile explains (see kCases below).
#include "fixtures.hpp"
#include "reference.hpp"

#include <gdcontact/collide.hpp>

#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

namespace gdcbench {
namespace {

using Query = std::function<int(int)>;  // pose index → contacts

/// The canonical cube pair case of that name.
PairCase cubeCase(const std::string& name) {
    for (const PairCase& c : cubePairCases())
        if (c.name == name) return c;
    throw std::runtime_error("no cube case " + name);
}

Query cubePair(const gdc::Polytope& shape, const std::string& caseName) {
    const PairCase c = cubeCase(caseName);
    gdc::Settings settings;
    settings.maxContacts = c.maxContacts;
    auto polytope = std::make_shared<gdc::Polytope>(shape);
    return [polytope, c, settings](int) { return gdc::collide(*polytope, c.poseA, *polytope, c.poseB, settings).pointCount; };
}

Query sizedPair(int vertexCount) {
    const std::vector<Vec3> points = sweepHullPoints(vertexCount);
    auto hull = std::make_shared<gdc::Polytope>(gdc::Polytope::fromPoints(points));
    // The same poses as the size sweep of bench_pairs (same seed).
    const auto poses = touchingPoses(points, points, 16, kRestingOverlap, 20100701 + vertexCount);
    return [hull, poses](int i) {
        const auto& [a, b] = poses[i % poses.size()];
        return gdc::collide(*hull, a, *hull, b).pointCount;
    };
}

const std::map<std::string, std::function<Query()>>& cases() {
    static const std::map<std::string, std::function<Query()>> all{
        {"box_box_face_8", [] { return cubePair(gdc::Polytope::box(Vec3::Constant(kCubeHalfExtent)), "face_face_8"); }},
        {"hull8_face_8",
         [] { return cubePair(gdc::Polytope::fromPoints(boxVertices(Vec3::Constant(kCubeHalfExtent))), "face_face_8"); }},
        {"convex_plane_face",
         [] {
             auto hull = std::make_shared<gdc::Polytope>(
                 gdc::Polytope::fromPoints(boxVertices(Vec3::Constant(kCubeHalfExtent))));
             const PlaneCase c = cubePlaneCases().front();
             return Query([hull, c](int) { return gdc::collide(*hull, c.pose, c.plane).pointCount; });
         }},
        {"hull_hull_8", [] { return sizedPair(8); }},
        {"hull_hull_4096", [] { return sizedPair(4096); }},
    };
    return all;
}

}  // namespace
}  // namespace gdcbench

int main(int argc, char** argv) {
    using namespace gdcbench;
    if (argc < 2 || !cases().count(argv[1])) {
        std::cerr << "usage: bench_profile CASE [CPU-SECONDS]; cases:";
        for (const auto& [name, make] : cases()) std::cerr << ' ' << name;
        std::cerr << '\n';
        return 2;
    }
    const double seconds = argc > 2 ? std::stod(argv[2]) : 1.0;
    const Query query = cases().at(argv[1])();
    const double start = threadCpuSeconds();
    long long calls = 0, contacts = 0;
    while (threadCpuSeconds() - start < seconds)  // the clock is read rarely: it is not what we profile
        for (int i = 0; i < 256; ++i) contacts += query(static_cast<int>(calls++));
    std::cout << argv[1] << ": " << calls << " calls, " << 1e9 * (threadCpuSeconds() - start) / calls
              << " ns per call, " << static_cast<double>(contacts) / calls << " contacts per call\n";
    return 0;
}

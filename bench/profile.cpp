// A driver for profilers (perf, callgrind): runs one contender of one per-pair case
// (pair_cases.hpp, the very calls bench_pairs times: its cycled poses) in a loop, with only that
// case's set-up, so that a profile shows where the time of the query goes.
//   bench_profile FAMILY/CASE/CONTENDER [CPU-SECONDS]     e.g. box_box/face_face_8/gdcontact_ode_box
//   bench_profile --list
#include <gdcontact/ode.hpp>
#include "fixtures.hpp"
#include "ode_shapes.hpp"
#include "pair_cases.hpp"

#include <iostream>
#include <string>

int main(int argc, char** argv) {
    using namespace gdcbench;
    const std::string wanted = argc > 1 ? argv[1] : "";
    OdeSession ode;
    // The per-pair cases cycle fixed poses of geoms without bodies, which the adapter's exact pair
    // cache would answer by repetition: they measure a query, so the cache is off (its repeated
    // answers are measured by tests/ode/adapter_overhead.sh and in the Big worlds section).
    gdc::ode::setPairCacheEnabled(false);
    for (const PairCaseSet& set : pairCaseSets()) {
        const std::string prefix = set.name() + "/";
        if (wanted != "--list" && wanted.compare(0, prefix.size(), prefix) != 0) continue;
        const ContenderFilter only = [&](const std::string& name) {
            return wanted == "--list" || prefix + name == wanted;
        };
        for (const PairContender& c : set.make(only)) {
            if (wanted == "--list") {
                std::cout << prefix << c.name << '\n';
                continue;
            }
            if (prefix + c.name != wanted) continue;
            const double seconds = argc > 2 ? std::stod(argv[2]) : 1.0;
            const double start = threadCpuSeconds();
            long long calls = 0, contacts = 0;
            while (threadCpuSeconds() - start < seconds)  // the clock is read rarely: it is not what we profile
                for (int i = 0; i < 256; ++i, ++calls) contacts += c.collide(static_cast<int>(calls % set.poseCount));
            std::cout << wanted << ": " << calls << " calls, " << 1e9 * (threadCpuSeconds() - start) / calls
                      << " ns per call, " << static_cast<double>(contacts) / calls << " contacts per call\n";
            return 0;
        }
        if (wanted != "--list") break;
    }
    if (wanted == "--list") return 0;
    std::cerr << "usage: bench_profile FAMILY/CASE/CONTENDER [CPU-SECONDS]  (bench_profile --list for the names)\n";
    return 2;
}

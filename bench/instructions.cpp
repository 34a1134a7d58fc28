// Instructions per call under callgrind, for the very calls bench_pairs times (pair_cases.hpp):
// every contender of every case cycles through its poses `cycles` times with callgrind's
// collection switched on only around those calls, and a dump is written after each one, named
// family/case/contender. Instruction counts are stable where time on a busy machine is not.
//
//   valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file=DIR/callgrind.out
//            bench_instructions [--cycles N] [--big-cycles N] [--others-up-to N] [--manifest FILE.csv]
//                               [FILTER...]
//
// bench/callgrind_counts.py runs this and turns the dumps into instructions per call (CSV).
// FILTER: only the cases whose family/case starts with one of these prefixes. --others-up-to N:
// ODE's and Bullet's contenders only for hulls of at most N vertices (default 1024; building their
// shapes for 4096 vertices takes minutes under callgrind). Without valgrind the
// client requests do nothing (the run then only checks that every case builds and runs).
#include <gdcontact/ode.hpp>
#include "ode_shapes.hpp"
#include "pair_cases.hpp"

#include <valgrind/callgrind.h>

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace gdcbench {
namespace {

/// Hulls of at least this many vertices are cycled `bigCycles` times (their calls are long, and
/// the instruction count varies little from cycle to cycle); so is Bullet's SAT beyond the cube
/// (O(E²·V): 17 million instructions per call at 64 vertices).
constexpr int kBigHull = 256;

int measure(const std::string& name, const PairContender& contender, int poseCount, int cycles) {
    int contacts = 0;
    for (int i = 0; i < poseCount; ++i) contacts += contender.collide(i);  // warm-up: lazy set-up, caches
    CALLGRIND_TOGGLE_COLLECT;
    for (int cycle = 0; cycle < cycles; ++cycle)
        for (int i = 0; i < poseCount; ++i) contacts += contender.collide(i);
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_DUMP_STATS_AT(name.c_str());
    return contacts;
}

bool wanted(const std::string& caseName, const std::vector<std::string>& filters) {
    if (filters.empty()) return true;
    for (const std::string& f : filters)
        if (caseName.compare(0, f.size(), f) == 0) return true;
    return false;
}

}  // namespace
}  // namespace gdcbench

int main(int argc, char** argv) {
    using namespace gdcbench;
    int cycles = 20, bigCycles = 2, othersUpTo = 1024;
    std::string manifest;
    std::vector<std::string> filters;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--cycles" && i + 1 < argc) {
            cycles = std::stoi(argv[++i]);
        } else if (arg == "--big-cycles" && i + 1 < argc) {
            bigCycles = std::stoi(argv[++i]);
        } else if (arg == "--others-up-to" && i + 1 < argc) {
            othersUpTo = std::stoi(argv[++i]);
        } else if (arg == "--manifest" && i + 1 < argc) {
            manifest = argv[++i];
        } else if (!arg.empty() && arg[0] != '-') {
            filters.push_back(arg);
        } else {
            std::cerr << "usage: bench_instructions [--cycles N] [--big-cycles N] [--others-up-to N]"
                         " [--manifest FILE.csv] [FILTER...]\n";
            return 2;
        }
    }
    OdeSession ode;
    // The per-pair cases cycle fixed poses of geoms without bodies, which the adapter's exact pair
    // cache would answer by repetition: they measure a query, so the cache is off (its repeated
    // answers are measured by tests/ode/adapter_overhead.sh and in the Big worlds section).
    gdc::ode::setPairCacheEnabled(false);
    std::ofstream file;
    if (!manifest.empty()) file.open(manifest);
    std::ostream& out = manifest.empty() ? std::cout : file;
    out << "family,case,contender,calls,contacts_per_call\n";
    // The loop itself (an empty query through the same std::function), subtracted by the parser.
    {
        const PairContender empty{"empty", [](int) { return 0; }};
        measure("loop/overhead/empty", empty, kPosesPerCase, cycles);
        out << "loop,overhead,empty," << kPosesPerCase * cycles << ",0\n";
    }
    for (const PairCaseSet& set : pairCaseSets()) {
        if (!wanted(set.name(), filters)) continue;
        const bool sweep = set.family == "hull_hull" || set.family == "hull_plane";
        const int size = sweep ? std::stoi(set.caseName) : 8;
        const ContenderFilter filter = [&](const std::string& name) {
            return size <= othersUpTo || name.compare(0, 9, "gdcontact") == 0;
        };
        const std::vector<PairContender> contenders = set.make(filter);
        for (const PairContender& c : contenders) {
            const int n = size >= kBigHull || (c.name == "bullet_sat_clip" && size > 8) ? bigCycles : cycles;
            const int contacts = measure(set.name() + "/" + c.name, c, set.poseCount, n);
            const int calls = set.poseCount * n;
            out << set.family << ',' << set.caseName << ',' << c.name << ',' << calls << ','
                << static_cast<double>(contacts) / (calls + set.poseCount) << '\n';
        }
        std::cerr << "bench_instructions: " << set.name() << '\n';
    }
    return 0;
}

// Per-pair collide time of gdcontact, ODE 0.16.2's native colliders and Bullet on the same shapes
// and poses (pair_cases.hpp: 16 slightly jittered poses per case, a distinct geom pair per pose).
// Names are family/case/contender; the counter "contacts" is the mean number of contacts per call.
//
//   bench_pairs [--rounds N] [--seconds S] [Google Benchmark options]
//
// Interleaved: for each case, N rounds, each round timing every contender of the case once, one
// after the other; so the N samples of each contender (the same name appears N times in the
// output) are taken at the same times as its rivals'. scripts/bench reports the median and the
// spread of the rounds, and ratios to ODE's native collider for the same pair.
// Each sample runs about S CPU seconds (default 0.1), a whole number of cycles through the poses;
// the iteration count is set once per contender from a short trial before the runs (instead of
// Google Benchmark's calibration in every sample, which would double the time).
//
// Poses are set outside the timed loop: every contender is timed on the query alone (ODE gets one
// geom per pose, so that no dGeomSetRotation is timed; see pair_cases.cpp for the big hulls).
#include <gdcontact/ode.hpp>
#include "ode_shapes.hpp"
#include "pair_cases.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>
#include <string>

namespace gdcbench {
namespace {

/// Iterations for about `seconds` of CPU time per sample: a whole number of cycles through the
/// poses, from a trial after one warm-up cycle (batches doubled until one takes 2 ms, so that the
/// clock, read once per batch, costs nothing that matters).
benchmark::IterationCount iterationsFor(const PairContender& contender, int poseCount, double seconds) {
    int sink = 0;
    for (int i = 0; i < poseCount; ++i) sink += contender.collide(i);
    double elapsed = 0;
    long long cycles = 1;
    for (;; cycles *= 2) {
        const double start = threadCpuSeconds();
        for (long long c = 0; c < cycles; ++c)
            for (int i = 0; i < poseCount; ++i) sink += contender.collide(i);
        elapsed = threadCpuSeconds() - start;
        if (elapsed >= 2e-3) break;
    }
    benchmark::DoNotOptimize(sink);
    const double perCycle = elapsed / static_cast<double>(cycles);
    return static_cast<benchmark::IterationCount>(std::clamp(std::ceil(seconds / perCycle), 1.0, 1e9 / poseCount)) *
           poseCount;
}

/// Registers a benchmark calling `contender.collide(poseIndex)` `iterations` times with indices
/// cycling through 0 … poseCount−1.
void registerPair(const std::string& name, int poseCount, std::shared_ptr<const PairContender> contender,
                  benchmark::IterationCount iterations) {
    auto* registered = benchmark::RegisterBenchmark(name.c_str(), [poseCount, contender](benchmark::State& state) {
        long long contacts = 0;
        int pose = 0;
        for (auto _ : state) {
            const int n = contender->collide(pose);
            benchmark::DoNotOptimize(n);
            contacts += n;
            if (++pose == poseCount) pose = 0;
        }
        state.counters["contacts"] =
            benchmark::Counter(static_cast<double>(contacts), benchmark::Counter::kAvgIterations);
    });
    registered->Iterations(iterations);
}

}  // namespace
}  // namespace gdcbench

int main(int argc, char** argv) {
    using namespace gdcbench;
    int rounds = 1;
    double seconds = 0.1;
    // Our own option first; the rest goes to Google Benchmark.
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--rounds") == 0 && i + 1 < argc)
            rounds = std::max(1, std::atoi(argv[++i]));
        else if (std::strncmp(argv[i], "--rounds=", 9) == 0)
            rounds = std::max(1, std::atoi(argv[i] + 9));
        else if (std::strcmp(argv[i], "--seconds") == 0 && i + 1 < argc)
            seconds = std::atof(argv[++i]);
        else
            argv[kept++] = argv[i];
    }
    argc = kept;
    OdeSession ode;
    // The per-pair cases cycle fixed poses of geoms without bodies, which the adapter's exact pair
    // cache would answer by repetition: they measure a query, so the cache is off (its repeated
    // answers are measured by tests/ode/adapter_overhead.sh and in the Big worlds section).
    gdc::ode::setPairCacheEnabled(false);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    for (const PairCaseSet& set : pairCaseSets()) {
        std::vector<std::shared_ptr<const PairContender>> contenders;
        std::vector<benchmark::IterationCount> iterations;
        for (PairContender& c : set.make({})) {
            contenders.push_back(std::make_shared<const PairContender>(std::move(c)));
            iterations.push_back(iterationsFor(*contenders.back(), set.poseCount, seconds));
        }
        for (int round = 0; round < rounds; ++round)
            for (std::size_t k = 0; k < contenders.size(); ++k)
                registerPair(set.name() + "/" + contenders[k]->name, set.poseCount, contenders[k], iterations[k]);
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    // Destroy the geoms the benchmarks hold while ODE is still initialised.
    benchmark::ClearRegisteredBenchmarks();
    return 0;
}

// bench_solver_seeds: the solver benchmark over seeds (issue 22, item 1). See solver_seeds.hpp for
// what one run is; this program runs scene × stepper × contender × seed on worker processes (ODE's
// random generator, which dWorldQuickStep's row shuffle draws from, is process-wide: threads would
// share it), measures the cost of one step on identical states, and writes CSV files.
//
// Usage: bench_solver_seeds [--quick | --full] [--out DIR] [--scene NAME]... [--stepper NAME]...
//          [--contender SPEC]... [--no-default-contenders] [--seeds N] [--seeds-for SCENE[:STEPPER]=N]...
//          [--first-seed N] [--jobs N]
//          [--no-sleep] [--duration-scale X] [--jitter-scale X] [--island-root lowest|as-built] [--compare-contacts TIME] [--cost-states N] [--cost-repetitions N] [--no-cost]
//   SPEC: gdc | ode-box | ode-convex | gdc:NAME=VALUE[,NAME=VALUE...] (a gdc::Settings variant)
// Writes DIR/solver_seeds_runs.csv (one row per run), DIR/solver_seeds_summary.csv (one row per
// scene × stepper × contender), DIR/solver_seeds_scenes.csv, DIR/solver_seeds_limits.csv and
// DIR/solver_seeds_command.txt; `python3 -m gdcreport solver-seeds` (scripts/gdcreport) turns them into tables and a plot.
#include "solver_seeds.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <new>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <ode/ode.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

namespace ss = gdc::solver_seeds;

namespace {

struct Options {
    std::string mode = "default";  // default | quick | full
    std::string out = ".";
    std::vector<std::string> scenes, steppers, contenders;
    bool defaultContenders = true;
    int seeds = -1;  // −1: the mode's
    int firstSeed = 1;
    int jobs = 0;    // 0: hardware threads
    bool sleep = true;
    double durationScale = 1.0;
    double jitterScale = 1.0;
    bool rootIslandsAtLowest = false;  // --island-root lowest (RunOptions::rootIslandsAtLowest)
    int costStates = -1;
    int costRepetitions = 3;
    bool cost = true;
    std::map<std::string, int> seedsFor;  // "SCENE" or "SCENE:STEPPER" → seeds (--seeds-for)
    double compareAt = -1;  // --compare-contacts TIME: the rows each contender hands the solver, on one state
    std::string command;
};

struct Job {
    std::size_t scene, stepper, contender;
    int seed;
};

double percentile(std::vector<double> values, double p) {
    if (values.empty()) return std::nan("");
    std::sort(values.begin(), values.end());
    const double rank = p * (values.size() - 1);
    const std::size_t below = static_cast<std::size_t>(std::floor(rank));
    const std::size_t above = std::min(below + 1, values.size() - 1);
    return values[below] + (rank - below) * (values[above] - values[below]);
}

/// Wilson score interval (95 %) of a fraction k/n: what the binomial noise of a fail fraction is.
std::pair<double, double> wilson(int k, int n) {
    if (n == 0) return {0, 1};
    const double z = 1.959964, p = static_cast<double>(k) / n;
    const double denominator = 1 + z * z / n;
    const double centre = (p + z * z / (2 * n)) / denominator;
    const double half = z * std::sqrt(p * (1 - p) / n + z * z / (4.0 * n * n)) / denominator;
    return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 0; i < argc; ++i) o.command += (i ? " " : "") + std::string(i == 0 ? "bench_solver_seeds" : argv[i]);
    auto value = [&](int& i) -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(std::string(argv[i]) + " needs a value");
        return argv[++i];
    };
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--quick") o.mode = "quick";
        else if (a == "--full") o.mode = "full";
        else if (a == "--out") o.out = value(i);
        else if (a == "--scene") o.scenes.push_back(value(i));
        else if (a == "--stepper") o.steppers.push_back(value(i));
        else if (a == "--contender") o.contenders.push_back(value(i));
        else if (a == "--no-default-contenders") o.defaultContenders = false;
        else if (a == "--seeds") o.seeds = std::stoi(value(i));
        else if (a == "--first-seed") o.firstSeed = std::stoi(value(i));
        else if (a == "--seeds-for") {
            const std::string item = value(i);
            const auto equals = item.find('=');
            if (equals == std::string::npos || std::stoi(item.substr(equals + 1)) < 1)
                throw std::invalid_argument("--seeds-for SCENE[:STEPPER]=N, N >= 1");
            o.seedsFor[item.substr(0, equals)] = std::stoi(item.substr(equals + 1));
        }
        else if (a == "--jobs") o.jobs = std::stoi(value(i));
        else if (a == "--no-sleep") o.sleep = false;
        else if (a == "--island-root") {
            const std::string root = value(i);
            if (root != "lowest" && root != "as-built") throw std::invalid_argument("--island-root lowest|as-built");
            o.rootIslandsAtLowest = root == "lowest";
        }
        else if (a == "--duration-scale") o.durationScale = std::stod(value(i));
        else if (a == "--jitter-scale") o.jitterScale = std::stod(value(i));
        else if (a == "--compare-contacts") o.compareAt = std::stod(value(i));
        else if (a == "--cost-states") o.costStates = std::stoi(value(i));
        else if (a == "--cost-repetitions") o.costRepetitions = std::stoi(value(i));
        else if (a == "--no-cost") o.cost = false;
        else if (a == "--help" || a == "-h") {
            std::cout << "bench_solver_seeds [--quick | --full] [--out DIR] [--scene NAME]... [--stepper NAME]...\n"
                         "  [--contender gdc|ode-box|ode-convex|gdc:NAME=VALUE,...]... [--no-default-contenders]\n"
                         "  [--seeds N] [--seeds-for SCENE[:STEPPER]=N]... [--first-seed N] [--jobs N] [--no-sleep]\n"
                         "  [--duration-scale X] [--jitter-scale X] [--island-root lowest|as-built] [--compare-contacts TIME]\n"
                         "  [--cost-states N] [--cost-repetitions N] [--no-cost]\nsettings:";
            for (const std::string& name : ss::settingNames()) std::cout << ' ' << name;
            std::cout << "\nscenes:";
            for (const ss::SceneSpec& s : ss::sceneSpecs()) std::cout << ' ' << s.name;
            std::cout << "\nsteppers: quick10 quick20 quick50 world\n";
            std::exit(0);
        } else throw std::invalid_argument("unknown argument '" + a + "' (--help)");
    }
    if (o.rootIslandsAtLowest && o.sleep)
        throw std::invalid_argument("--island-root lowest disables bodies before each step, which keeps ODE's auto-disable "
                                    "from sampling them: use it with --no-sleep");
    if (o.seeds == 0 || o.seeds < -1 || o.jobs < 0 || !(o.durationScale > 0) || o.costRepetitions < 1)
        throw std::invalid_argument("--seeds, --jobs, --duration-scale, --cost-repetitions out of range");
    return o;
}

/// Runs every job on `workers` processes that share `results`; a job whose process died is
/// marked Crashed and the rest go on.
void runJobs(const std::vector<Job>& jobs, const std::vector<ss::SceneSpec>& scenes, const std::vector<ss::Stepper>& steppers,
             const std::vector<ss::Contender>& contenders, const ss::RunOptions& runOptions, int workers,
             std::vector<ss::SeedResult>& out) {
    const std::size_t bytes = sizeof(std::atomic<int>) + jobs.size() * sizeof(ss::SeedResult);
    void* memory = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (memory == MAP_FAILED) throw std::runtime_error("mmap failed");
    auto* next = new (memory) std::atomic<int>(0);
    auto* results = reinterpret_cast<ss::SeedResult*>(static_cast<char*>(memory) + sizeof(std::atomic<int>));
    for (std::size_t j = 0; j < jobs.size(); ++j) new (&results[j]) ss::SeedResult();
    const int total = static_cast<int>(jobs.size());
    const auto start = std::chrono::steady_clock::now();
    while (next->load() < total) {
        std::vector<pid_t> children;
        for (int w = 0; w < workers; ++w) {
            const pid_t pid = fork();
            if (pid < 0) throw std::runtime_error("fork failed");
            if (pid == 0) {
                for (int j = next->fetch_add(1); j < total; j = next->fetch_add(1)) {
                    results[j].done = 2;  // claimed: stays 2 if this process dies in the run
                    const Job& job = jobs[j];
                    results[j] = ss::runSeed(scenes[job.scene], steppers[job.stepper], contenders[job.contender], job.seed, runOptions);
                }
                std::fflush(nullptr);
                _exit(0);
            }
            children.push_back(pid);
        }
        auto lastReport = std::chrono::steady_clock::now();
        std::size_t running = children.size();
        while (running > 0) {
            int status = 0;
            const pid_t pid = waitpid(-1, &status, WNOHANG);
            if (pid > 0) {
                --running;
                continue;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            const auto now = std::chrono::steady_clock::now();
            if (now - lastReport > std::chrono::seconds(20)) {
                lastReport = now;
                int done = 0;
                for (int j = 0; j < total; ++j) done += results[j].done == 1;
                std::cerr << "  " << done << " of " << total << " runs ("
                          << std::chrono::duration_cast<std::chrono::seconds>(now - start).count() << " s)\n";
            }
        }
        for (int j = 0; j < std::min(next->load(), total); ++j) {
            if (results[j].done == 2) {  // its process died: ODE aborted
                results[j] = ss::SeedResult();
                results[j].done = 1;
                results[j].failure = static_cast<int>(ss::Failure::Crashed);
                results[j].collapsed = 1;
            }
        }
    }
    out.assign(results, results + jobs.size());
    munmap(memory, bytes);
}

std::string csvText(const std::string& text) {
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

}  // namespace

int main(int argc, char** argv) {
    try {
        Options o = parse(argc, argv);
        dInitODE2(0);
        ss::installMessageCounter();

        // What runs.
        std::vector<ss::SceneSpec> scenes;
        if (o.scenes.empty()) {
            for (const ss::SceneSpec& s : ss::sceneSpecs())
                if (o.mode != "quick" || s.name == "stack10" || s.name == "stack20") scenes.push_back(s);
        } else {
            for (const std::string& name : o.scenes) scenes.push_back(ss::findScene(name));
        }
        std::vector<ss::Stepper> steppers;
        if (o.steppers.empty()) {
            for (const ss::Stepper& s : ss::allSteppers())
                if (o.mode != "quick" || s.name == "quick20" || s.name == "world") steppers.push_back(s);
        } else {
            for (const std::string& name : o.steppers) steppers.push_back(ss::parseStepper(name));
        }
        std::vector<ss::Contender> contenders;
        if (o.defaultContenders)
            for (const char* name : {"gdc", "ode-box", "ode-convex"}) contenders.push_back(ss::parseContender(name));
        for (const std::string& spec : o.contenders) {
            const bool present = std::any_of(contenders.begin(), contenders.end(), [&](const ss::Contender& c) { return c.name == spec; });
            if (!present) contenders.push_back(ss::parseContender(spec));
        }
        if (contenders.empty()) throw std::invalid_argument("no contenders");
        if (o.mode == "quick" && o.durationScale == 1.0) o.durationScale = 0.5;
        if (o.compareAt >= 0) {
            // The rows each contender hands the solver on the state of the first contender's run
            // at that time (first scene, first stepper, --first-seed), as CSV on stdout.
            ss::RunOptions compareOptions;
            compareOptions.jitterScale = o.jitterScale;
            ss::compareContacts(scenes.front(), steppers.front(), contenders, contenders.front(), o.firstSeed, o.compareAt,
                                compareOptions, stdout);
            dCloseODE();
            return 0;
        }
        const int costStates = o.costStates >= 0 ? o.costStates : (o.mode == "full" ? 8 : o.mode == "quick" ? 0 : 5);
        const int workers = o.jobs > 0 ? o.jobs : std::max(1u, std::thread::hardware_concurrency());

        auto seedsFor = [&](const ss::SceneSpec& s, bool quickStepper, const std::string& stepper = "") {
            if (!stepper.empty() && o.seedsFor.count(s.name + ":" + stepper)) return o.seedsFor.at(s.name + ":" + stepper);
            if (o.seedsFor.count(s.name)) return o.seedsFor.at(s.name);
            if (o.seeds > 0) return o.seeds;
            if (o.mode == "quick") return 5;
            if (o.mode == "full") return std::max(50, s.fullSeeds);
            return quickStepper ? s.defaultSeeds : std::min(s.defaultSeeds, s.defaultWorldSeeds);
        };
        auto applies = [](const ss::SceneSpec& s, const ss::Stepper& st, const ss::Contender& c) {
            if (!st.quick && !s.worldStep) return false;
            // ode-box: dBox geoms, or in a curved scene ODE's own colliders on its dCylinder,
            // dCapsule and dBox geoms; ode-convex would turn only a curved scene's boxes into dConvex.
            if (c.kind == ss::ColliderKind::OdeBox && !s.hasBoxes && !s.curved) return false;
            if (c.kind == ss::ColliderKind::OdeConvex && s.curved) return false;
            return true;
        };
        std::vector<Job> jobs;
        for (std::size_t si = 0; si < scenes.size(); ++si)
            for (std::size_t ti = 0; ti < steppers.size(); ++ti)
                for (std::size_t ci = 0; ci < contenders.size(); ++ci)
                    if (applies(scenes[si], steppers[ti], contenders[ci]))
                        for (int k = 0; k < seedsFor(scenes[si], steppers[ti].quick, steppers[ti].name); ++k) jobs.push_back({si, ti, ci, o.firstSeed + k});
        // The longest runs first, so that no worker is left with one at the end.
        std::stable_sort(jobs.begin(), jobs.end(), [&](const Job& a, const Job& b) {
            auto weight = [&](const Job& j) { return scenes[j.scene].name == "pile1000" ? 2 : !steppers[j.stepper].quick ? 1 : 0; };
            return weight(a) > weight(b);
        });

        ss::RunOptions runOptions;
        runOptions.sleep = o.sleep;
        runOptions.durationScale = o.durationScale;
    runOptions.jitterScale = o.jitterScale;
        runOptions.rootIslandsAtLowest = o.rootIslandsAtLowest;
        std::cerr << "bench_solver_seeds (" << o.mode << "): " << jobs.size() << " runs on " << workers << " processes\n";
        const auto start = std::chrono::steady_clock::now();
        std::vector<ss::SeedResult> results;
        runJobs(jobs, scenes, steppers, contenders, runOptions, workers, results);
        const double runSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::cerr << "  runs done in " << std::fixed << std::setprecision(1) << runSeconds << " s\n";

        // Per scene × stepper × contender.
        struct Aggregate {
            std::vector<ss::SeedResult> runs;
            ss::CostResult cost;
            bool hasCost = false;
        };
        std::map<std::tuple<std::size_t, std::size_t, std::size_t>, Aggregate> aggregates;
        for (std::size_t j = 0; j < jobs.size(); ++j)
            aggregates[{jobs[j].scene, jobs[j].stepper, jobs[j].contender}].runs.push_back(results[j]);

        // Cost on identical states: one reference run per scene × stepper, its states copied into
        // every contender's world. The reference: the first of ode-box, gdc, ode-convex (as present)
        // that did not fail the first seed, so the states are those of a scene that stands.
        const auto costStart = std::chrono::steady_clock::now();
        if (o.cost && costStates > 0) {
            for (std::size_t si = 0; si < scenes.size(); ++si) {
                for (std::size_t ti = 0; ti < steppers.size(); ++ti) {
                    std::vector<std::size_t> indices;
                    std::vector<ss::Contender> present;
                    for (std::size_t ci = 0; ci < contenders.size(); ++ci)
                        if (applies(scenes[si], steppers[ti], contenders[ci])) {
                            indices.push_back(ci);
                            present.push_back(contenders[ci]);
                        }
                    if (present.empty()) continue;
                    const ss::Contender* reference = &present.front();
                    bool found = false;
                    // The states of the first contender that stood in the first seed: ODE's dBox, else
                    // gdcontact under any settings ("gdc" or "gdc:NAME=VALUE"), else dConvex — so that a
                    // scene is timed on a standing pile, not on one that has fallen (fewer contacts).
                    auto isNamed = [](const std::string& contender, const std::string& name) {
                        return contender == name || (name == "gdc" && contender.rfind("gdc:", 0) == 0);
                    };
                    for (const char* name : {"ode-box", "gdc", "ode-convex"}) {
                        for (std::size_t k = 0; k < present.size() && !found; ++k) {
                            if (!isNamed(present[k].name, name)) continue;
                            const auto& runs = aggregates[{si, ti, indices[k]}].runs;
                            if (!runs.empty() && runs.front().failure == 0) {
                                reference = &present[k];
                                found = true;
                            }
                        }
                    }
                    const auto costs = ss::measureCost(scenes[si], steppers[ti], present, *reference, o.firstSeed, costStates,
                                                       o.costRepetitions, runOptions);
                    for (std::size_t k = 0; k < present.size(); ++k) {
                        Aggregate& a = aggregates[{si, ti, indices[k]}];
                        a.cost = costs[k];
                        a.hasCost = true;
                    }
                    std::cerr << "  cost " << scenes[si].name << " " << steppers[ti].name << " (reference " << reference->name << ")\n";
                }
            }
        }
        const double costSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - costStart).count();

        // The best ODE option of each scene × stepper: the ODE contender failing the fewest seeds
        // (ties: the cheaper whole step on identical states); where even it fails more than half
        // the seeds, none stands and the cheapest ODE option is taken.
        std::map<std::pair<std::size_t, std::size_t>, std::size_t> bestOde;
        for (std::size_t si = 0; si < scenes.size(); ++si) {
            for (std::size_t ti = 0; ti < steppers.size(); ++ti) {
                std::vector<std::size_t> odes;
                for (std::size_t ci = 0; ci < contenders.size(); ++ci)
                    if (contenders[ci].kind != ss::ColliderKind::Gdcontact && aggregates.count({si, ti, ci}))
                        odes.push_back(ci);
                if (odes.empty()) continue;
                auto failed = [&](std::size_t ci) {
                    const auto& runs = aggregates[{si, ti, ci}].runs;
                    return static_cast<double>(std::count_if(runs.begin(), runs.end(), [](const ss::SeedResult& r) { return r.failure != 0; })) /
                           std::max<std::size_t>(1, runs.size());
                };
                auto whole = [&](std::size_t ci) {
                    const Aggregate& a = aggregates[{si, ti, ci}];
                    return a.hasCost ? a.cost.collisionMs + a.cost.solverMs : 1e300;
                };
                std::size_t best = odes.front();
                for (std::size_t ci : odes)
                    if (failed(ci) < failed(best) || (failed(ci) == failed(best) && whole(ci) < whole(best))) best = ci;
                if (failed(best) > 0.5)
                    for (std::size_t ci : odes)
                        if (whole(ci) < whole(best)) best = ci;
                bestOde[{si, ti}] = best;
            }
        }

        // ---- files ----
        std::filesystem::create_directories(o.out);
        const std::string prefix = o.out + "/solver_seeds_";
        {
            std::ofstream f(prefix + "runs.csv");
            f << "scene,stepper,contender,seed,failed,failure,fail_time,drift,max_tilt,contacts_per_step,collision_ms,"
                 "solver_ms,sleep_time,asleep_at_end,messages,lcp_errors,invalid_contacts,steps,bodies,collapsed,creep\n";
            f << std::setprecision(6);
            for (std::size_t j = 0; j < jobs.size(); ++j) {
                const ss::SeedResult& r = results[j];
                f << scenes[jobs[j].scene].name << ',' << steppers[jobs[j].stepper].name << ',' << csvText(contenders[jobs[j].contender].name)
                  << ',' << jobs[j].seed << ',' << (r.failure != 0) << ',' << ss::failureName(static_cast<ss::Failure>(r.failure)) << ','
                  << r.failTime << ',' << r.drift << ',' << r.maxTilt << ',' << r.contactsPerStep << ',' << r.collisionMs << ','
                  << r.solverMs << ',' << r.sleepTime << ',' << r.asleepAtEnd << ',' << r.messages << ',' << r.lcpErrors << ','
                  << r.invalidContacts << ',' << r.steps << ',' << r.bodies << ',' << r.collapsed << ',' << r.creep << '\n';
            }
            if (!f) throw std::runtime_error("cannot write " + prefix + "runs.csv");
        }
        {
            std::ofstream f(prefix + "summary.csv");
            f << "scene,stepper,contender,seeds,failed,fail_fraction,fail_low95,fail_high95,failures,drift_p50,drift_p90,"
                 "drift_max,contacts_per_step,collision_ms,solver_ms,slept_fraction,sleep_p50,asleep_at_end,messages,"
                 "lcp_errors,invalid_contacts,cost_collision_ms,cost_solver_ms,cost_whole_ms,cost_contacts,best_ode,"
                 "ratio_to_best_ode,collapsed,collapse_fraction,collapse_low95,collapse_high95\n";
            f << std::setprecision(6);
            for (auto& [key, a] : aggregates) {
                const auto [si, ti, ci] = key;
                const int n = static_cast<int>(a.runs.size());
                int failed = 0, slept = 0, messages = 0, lcp = 0, invalid = 0, collapsed = 0;
                std::map<std::string, int> reasons;
                std::vector<double> drift, sleep;
                double contacts = 0, collision = 0, solver = 0, asleep = 0;
                for (const ss::SeedResult& r : a.runs) {
                    collapsed += r.collapsed;
                    if (r.failure) {
                        ++failed;
                        ++reasons[ss::failureName(static_cast<ss::Failure>(r.failure))];
                    }
                    drift.push_back(r.drift);
                    if (r.sleepTime >= 0) {
                        ++slept;
                        sleep.push_back(r.sleepTime);
                    }
                    contacts += r.contactsPerStep;
                    collision += r.collisionMs;
                    solver += r.solverMs;
                    asleep += r.asleepAtEnd;
                    messages += r.messages;
                    lcp += r.lcpErrors;
                    invalid += r.invalidContacts;
                }
                std::string why;
                for (const auto& [reason, count] : reasons) why += (why.empty() ? "" : " ") + reason + ":" + std::to_string(count);
                const auto [low, high] = wilson(failed, n);
                f << scenes[si].name << ',' << steppers[ti].name << ',' << csvText(contenders[ci].name) << ',' << n << ',' << failed
                  << ',' << static_cast<double>(failed) / n << ',' << low << ',' << high << ',' << csvText(why) << ','
                  << percentile(drift, 0.5) << ',' << percentile(drift, 0.9) << ',' << percentile(drift, 1.0) << ','
                  << contacts / n << ',' << collision / n << ',' << solver / n << ',' << static_cast<double>(slept) / n << ','
                  << (sleep.empty() ? std::nan("") : percentile(sleep, 0.5)) << ',' << asleep / n << ',' << messages << ',' << lcp
                  << ',' << invalid << ',';
                const auto best = bestOde.find({si, ti});
                if (a.hasCost) {
                    const double whole = a.cost.collisionMs + a.cost.solverMs;
                    f << a.cost.collisionMs << ',' << a.cost.solverMs << ',' << whole << ',' << a.cost.contacts << ',';
                    if (best != bestOde.end() && aggregates[{si, ti, best->second}].hasCost) {
                        const ss::CostResult& b = aggregates[{si, ti, best->second}].cost;
                        f << csvText(contenders[best->second].name) << ',' << whole / (b.collisionMs + b.solverMs);
                    } else {
                        f << ",";
                    }
                } else {
                    f << ",,,,,";
                }
                const auto [collapseLow, collapseHigh] = wilson(collapsed, n);
                f << ',' << collapsed << ',' << static_cast<double>(collapsed) / n << ',' << collapseLow << ',' << collapseHigh;
                f << '\n';
            }
            if (!f) throw std::runtime_error("cannot write " + prefix + "summary.csv");
        }
        {
            std::ofstream f(prefix + "scenes.csv");
            f << "scene,description,seconds,seeds,world_seeds,world_step,world_skip_reason,ode_box\n";
            for (const ss::SceneSpec& s : scenes)
                f << s.name << ',' << csvText(s.description) << ',' << s.duration * o.durationScale << ','
                  << seedsFor(s, true, "quick20") << ',' << (s.worldStep ? seedsFor(s, false, "world") : 0) << ',' << s.worldStep << ',' << csvText(s.worldSkipReason) << ',' << (s.hasBoxes || s.curved) << '\n';
        }
        {
            std::ofstream f(prefix + "limits.csv");
            f << "failure,scenes,rule,kind\n";
            for (const ss::FailureLimit& l : ss::failureLimits())
                f << ss::failureName(l.failure) << ',' << l.scenes << ',' << csvText(l.rule) << ",fine\n";
            for (const ss::FailureLimit& l : ss::collapseLimits())
                f << ss::failureName(l.failure) << ',' << l.scenes << ',' << csvText(l.rule) << ",collapse\n";
        }
        {
            std::ofstream f(prefix + "command.txt");
            f << o.command << "\nmode " << o.mode << "; " << jobs.size() << " runs on " << workers << " processes in "
              << std::fixed << std::setprecision(0) << runSeconds << " s; cost on identical states: " << costStates
              << " states x " << o.costRepetitions << " repetitions in " << costSeconds << " s; sleep "
              << (o.sleep ? "on (ODE auto-disable, default thresholds)" : "off (emulated)") << "\n";
        }
        std::cerr << "  wrote " << prefix << "{runs,summary,scenes,limits}.csv\n";
        dCloseODE();
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "bench_solver_seeds: " << e.what() << "\n";
        return 2;
    }
}

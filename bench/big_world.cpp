// Big worlds (issue 15): collision milliseconds per step against the number of bodies, for ODE's
// native colliders and for gdcontact three ways (the classic near-callback loop, spaceCollide on
// one thread, spaceCollide on every hardware thread), each with gdcontact's pair cache on and off;
// the whole step under dWorldQuickStep; the phases inside spaceCollide; and the resting brick wall
// and pyramid against ODE's native colliders.
//
// Worlds (dBox worlds, so that ODE's exact dBoxBox and gdcontact see the same shapes):
//   pile N     — N boxes of 0.40 × 0.30 × 0.20 m dropped 2 cm in layers of side × side into a
//                walled bin (side = ⌈√(N/10)⌉: about ten layers at any N), every other layer across
//                the gaps of the one below, each box turned and tilted a little (bench/scenes.cpp's
//                box pile at N = 1000); auto-disable off, so every body is simulated every step;
//   brick wall — bench/scenes.cpp's 20 × 10 bricks; pyramid — its 15 rows of cubes (120): both
//                measured awake (auto-disable off) and asleep (ODE's auto-disable on, see
//                kSleepLinearSpeed: the resting bodies stop, their poses repeat bit for bit, and the
//                exact pair cache answers for them; ODE's broad phase still reports their pairs).
// Each world runs its settling steps first (unmeasured; under gdcontact's contacts), then the
// measured steps. Every measured step times, on the same world state, one after the other:
//   broad_phase      dSpaceCollide with an empty near callback (ODE's hash space alone);
//   ode              dSpaceCollide + near callback + dCollide: ODE's dBoxBox and dCollideBoxPlane;
//   loop / loop_cache            dSpaceCollide + near callback + gdc::ode::collide, the pairs' contacts
//                                collected in gdc::ode::BodyPairContacts and delivered after the
//                                broad phase (docs/ode.md: what spaceCollide equals bit for bit);
//   space_1t / space_1t_cache    gdc::ode::spaceCollide, setThreadCount(1);
//   space_mt / space_mt_cache    gdc::ode::spaceCollide, setThreadCount(0): every hardware thread;
//   profile_1t, profile_mt       spaceCollide (cache off) with its phase timing on
//                                (src/ode/space_collide_profile.hpp);
// each handing every contact to the same cheap consumer (copied into an array). The cache-off
// contenders run every step; of the cache-on ones one per step, in turn: the cache holds the last
// step's answers, and a second cache-on pass over the same unchanged state would find every answer
// repeated. Then the step's contact joints are made and dWorldQuickStep (20 iterations) steps the
// world (timed: "solver"). The gdcontact contenders must give the same contacts bit for bit (the
// program stops with an error if not). spaceCollide applies the per-body-pair budget
// (Settings::maxBodyPairContacts) wherever two bodies touch through several geom pairs — here a box
// against the static world through the ground and a wall of the bin —, so the loop it is held to
// is the near callback with BodyPairContacts, not plain dCollide's contacts (those differ where the
// budget drops or merges a point: a box standing against a wall, 2 of its wall pair's 3 points).
// Wall-clock time (threads are the point); per contender the median, quartiles, minimum and
// maximum over the measured steps.
//
// Usage: bench_big_world [--bodies 100,300,1000,3000,10000] [--settle N] [--steps N]
//                        [--resting] [--no-pile] [--space hash|sap] [--only CONTENDER [--repeat K]]
//                        [--seed N] [--out FILE.csv] [--profile-out FILE.csv]
//   --only C [--repeat K]: that contender alone, K times a step (default 1), for perf record or
//   callgrind on one configuration (the world still steps once a step).
//   --steps N: measured steps at 1000 bodies; a count c gets N·1000/c (at least 15, at most 4 N), so
//   that every size takes about as long; --settle N: settling steps up to 1000 bodies, N·√(1000/c)
//   above (at least 30). Without --out, the table goes to stdout.
//   --space sap: ODE's sweep-and-prune space instead of its hash space for every world.
//   --seed N: ODE's random generator (QuickStep's constraint shuffling) is set to N (default 1) as
//   each world is built, so a world's states do not depend on which worlds ran before it.
#include "fixtures.hpp"
#include "ode_shapes.hpp"
#include "ode/space_collide_profile.hpp"

#include <gdcontact/ode.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace gdcbench;

namespace {

constexpr double kTimeStep = 1.0 / 60.0;
constexpr int kSolverIterations = 20;
constexpr int kMaxContactsPerPair = 8;
// The asleep worlds' auto-disable: a body whose speeds, averaged over 10 steps, stay under these for
// ODE's default 10 steps sleeps. Under QuickStep's 20 iterations resting bricks keep jittering at up
// to 0.07 m/s and 0.4 rad/s, so ODE's default thresholds (0.01, 0.01) never put a wall to sleep.
constexpr int kSleepAverageSteps = 10;
constexpr double kSleepLinearSpeed = 0.1;   // m/s
constexpr double kSleepAngularSpeed = 0.3;  // rad/s

// The broad phase of every world: ODE's hash space (what the scenes use), or with --space sap ODE's
// sweep-and-prune space. ODE's hash space allocates and clears an n × n bit matrix on every
// dSpaceCollide (n²/8 bytes: 12.5 MB at 10 000 geoms), so its cost grows as n².
bool sweepAndPrune = false;  // --space sap
unsigned long randomSeed = 1;  // --seed: dRandSetSeed as each world is built

struct World {
    dWorldID world = dWorldCreate();
    dSpaceID space = sweepAndPrune ? dSweepAndPruneSpaceCreate(nullptr, dSAP_AXES_XYZ) : dHashSpaceCreate(nullptr);
    dJointGroupID joints = dJointGroupCreate(0);
    std::vector<dBodyID> bodies;
    std::vector<dContactGeom> contacts;  // the consumer: every contact of a step, with its pair
    std::vector<std::array<dGeomID, 2>> pairs;
    // The loop contenders' contacts, reduced per pair of bodies as spaceCollide reduces them (the
    // installed settings: this program installs none, so the defaults).
    gdc::ode::BodyPairContacts collected;

    World() {
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetQuickStepNumIterations(world, kSolverIterations);
        dWorldSetAutoDisableFlag(world, 0);
    }
    ~World() {
        dJointGroupDestroy(joints);
        dSpaceDestroy(space);
        dWorldDestroy(world);
    }
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    void addBox(const Vec3& halfExtents, const Pose& pose, double massKg) {
        dBodyID body = dBodyCreate(world);
        dMass mass;
        dMassSetBoxTotal(&mass, massKg, 2 * halfExtents.x(), 2 * halfExtents.y(), 2 * halfExtents.z());
        dBodySetMass(body, &mass);
        dGeomSetBody(createOdeBox(space, halfExtents), body);
        setBodyPose(body, pose);
        bodies.push_back(body);
    }
    void consume(dGeomID o1, dGeomID o2, const dContactGeom* c, int count) {
        for (int i = 0; i < count; ++i) {
            contacts.push_back(c[i]);
            pairs.push_back({o1, o2});
        }
    }
    void clear() {
        contacts.clear();
        pairs.clear();
    }
    void makeJoints() {
        for (std::size_t i = 0; i < contacts.size(); ++i) {
            dBodyID b1 = dGeomGetBody(pairs[i][0]), b2 = dGeomGetBody(pairs[i][1]);
            if (!b1 && !b2) continue;  // the bin's walls and the ground
            dContact contact{};
            contact.surface.mode = dContactApprox1;
            contact.surface.mu = 0.6;
            contact.geom = contacts[i];
            dJointAttach(dJointCreateContact(world, joints, &contact), b1, b2);
        }
    }
};

// ---- worlds ---------------------------------------------------------------------------------------

void addBin(World& w, double half) {
    for (int side = 0; side < 4; ++side) {
        const Vec3 centre = side < 2 ? Vec3((side ? 1 : -1) * (half + 0.1), 0, 2.5)
                                     : Vec3(0, (side == 3 ? 1 : -1) * (half + 0.1), 2.5);
        const Vec3 extents = side < 2 ? Vec3(0.1, half + 0.2, 2.5) : Vec3(half + 0.2, 0.1, 2.5);
        setGeomPose(createOdeBox(w.space, extents), {Mat3::Identity(), centre});
    }
}

void buildPile(World& w, int count) {
    dCreatePlane(w.space, 0, 0, 1, 0);
    const Vec3 box(0.2, 0.15, 0.1);
    const double dx = 0.45, dy = 0.36;
    const int side = std::max(1, static_cast<int>(std::ceil(std::sqrt(count / 10.0))));
    addBin(w, 0.5 * side * dx + 0.3);  // room for the shifted layers: 2.55 m at 1000, as bench/scenes.cpp
    Random random(1000);
    int made = 0;
    for (int layer = 0; made < count; ++layer) {
        const double shift = (layer % 2) ? 0.5 : 0.0;
        for (int i = 0; i < side && made < count; ++i)
            for (int j = 0; j < side && made < count; ++j, ++made) {
                const Mat3 turn = rotation(Vec3::UnitZ(), random.uniform(-0.15, 0.15)) *
                                  rotation(random.unitVector(), random.uniform(-0.02, 0.02));
                const double x = (i - 0.5 * (side - 1) + shift) * dx, y = (j - 0.5 * (side - 1) + shift) * dy;
                w.addBox(box, {turn, Vec3(x, y, box.z() + 0.01 + layer * (2 * box.z() + 0.02))}, 1.0);
            }
    }
}

void buildBrickWall(World& w) {  // bench/scenes.cpp's brick wall
    dCreatePlane(w.space, 0, 0, 1, 0);
    const Vec3 brick(0.2, 0.1, 0.065);
    const double gap = 1e-4;
    for (int row = 0; row < 10; ++row) {
        const double shift = (row % 2) ? 0.5 * brick.x() : 0.0;
        for (int i = 0; i < 20; ++i)
            w.addBox(brick, {Mat3::Identity(), Vec3((2 * i - 19) * (brick.x() + gap) + shift, 0,
                                                    brick.z() + row * (2 * brick.z() + gap))}, 2.0);
    }
}

void buildPyramid(World& w) {  // bench/scenes.cpp's pyramid
    dCreatePlane(w.space, 0, 0, 1, 0);
    const double h = 0.25, gap = 0.01;
    for (int row = 0; row < 15; ++row) {
        const int count = 15 - row;
        for (int i = 0; i < count; ++i)
            w.addBox(Vec3::Constant(h), {Mat3::Identity(), Vec3((i - 0.5 * (count - 1)) * (2 * h + gap), 0,
                                                                h + row * (2 * h + 1e-4))}, 1.0);
    }
}

// ---- contenders -----------------------------------------------------------------------------------

void emptyCallback(void*, dGeomID, dGeomID) {}

void handler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
    static_cast<World*>(data)->consume(o1, o2, contacts, count);
}

// ODE's colliders: dCollide's contacts as they are (ODE has no per-body-pair budget).
void odeCallback(void* data, dGeomID o1, dGeomID o2) {
    World& w = *static_cast<World*>(data);
    std::array<dContactGeom, kMaxContactsPerPair> geoms;
    const int n = dCollide(o1, o2, kMaxContactsPerPair, geoms.data(), sizeof(dContactGeom));
    if (n > 0) w.consume(o1, o2, geoms.data(), n);
}

// gdcontact's: collected, then delivered reduced per pair of bodies (runContender) — what
// spaceCollide hands over. Pairs without contacts are left out: they add nothing to a body pair.
void loopCallback(void* data, dGeomID o1, dGeomID o2) {
    World& w = *static_cast<World*>(data);
    std::array<dContactGeom, kMaxContactsPerPair> geoms;
    const int n = gdc::ode::collide(o1, o2, kMaxContactsPerPair, geoms.data(), sizeof(dContactGeom));
    if (n > 0) w.collected.add(o1, o2, geoms.data(), n);
}

enum class Kind { BroadPhase, Ode, Loop, Space1, SpaceAll };

struct Contender {
    std::string name;
    Kind kind;
    bool cache;
    bool profiled;
    bool everyStep;  // false: one of the cache-on contenders, which take turns
};

const std::vector<Contender>& contenders() {
    static const std::vector<Contender> list = {
        {"broad_phase", Kind::BroadPhase, false, false, true}, {"ode", Kind::Ode, false, false, true},
        {"loop", Kind::Loop, false, false, true},              {"space_1t", Kind::Space1, false, false, true},
        {"space_mt", Kind::SpaceAll, false, false, true},      {"profile_1t", Kind::Space1, false, true, true},
        {"profile_mt", Kind::SpaceAll, false, true, true},     {"loop_cache", Kind::Loop, true, false, false},
        {"space_1t_cache", Kind::Space1, true, false, false},  {"space_mt_cache", Kind::SpaceAll, true, false, false},
    };
    static const std::vector<Contender> built = [] {
        if (gdc::ode::detail::spaceCollideProfilingBuilt()) return list;
        std::cerr << "bench_big_world: built without GDCONTACT_PHASE_PROFILING: no profile contenders\n";
        std::vector<Contender> unprofiled;
        for (const Contender& c : list)
            if (!c.profiled) unprofiled.push_back(c);
        return unprofiled;
    }();
    return built;
    return list;
}

void runContender(World& w, const Contender& c) {
    gdc::ode::setPairCacheEnabled(c.cache);
    gdc::ode::detail::setSpaceCollideProfiling(c.profiled);
    switch (c.kind) {
        case Kind::BroadPhase: dSpaceCollide(w.space, &w, &emptyCallback); break;
        case Kind::Ode: dSpaceCollide(w.space, &w, &odeCallback); break;
        case Kind::Loop:
            dSpaceCollide(w.space, &w, &loopCallback);
            w.collected.deliver(&w, &handler);
            break;
        case Kind::Space1:
        case Kind::SpaceAll:
            gdc::ode::setThreadCount(c.kind == Kind::Space1 ? 1 : 0);
            gdc::ode::spaceCollide(w.space, kMaxContactsPerPair, &w, &handler);
            break;
    }
    gdc::ode::detail::setSpaceCollideProfiling(false);
}

double secondsOf(const std::function<void()>& f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Stats {
    double median = 0, p25 = 0, p75 = 0, min = 0, max = 0;
};

Stats statsOf(std::vector<double> v) {
    Stats s;
    if (v.empty()) return s;
    std::sort(v.begin(), v.end());
    auto at = [&](double q) {
        const double x = q * static_cast<double>(v.size() - 1);
        const std::size_t i = static_cast<std::size_t>(x);
        return i + 1 < v.size() ? v[i] + (x - static_cast<double>(i)) * (v[i + 1] - v[i]) : v[i];
    };
    s.median = at(0.5);
    s.p25 = at(0.25);
    s.p75 = at(0.75);
    s.min = v.front();
    s.max = v.back();
    return s;
}

// What one world's measured steps gave.
struct Series {
    std::vector<double> ms;
    long long contacts = 0;
    long long cacheHits = 0, cacheCarried = 0, cacheMisses = 0;  // pairCacheStats' counts
    int steps = 0;
};

struct ProfileSeries {
    std::vector<double> total, broad, drain, handler, narrow, narrowCaller, poolStart;
    int poolJoined = 0;  // calls in which a pool thread took a chunk
    double gdcontactPairs = 0, otherPairs = 0;
    int threads = 0, samples = 0;
};

std::uint64_t hashContacts(const World& w) {
    // A 64-bit mix over each contact's meaningful words (pos and normal without their padding
    // element, which ODE leaves unset; depth; the pair): a word at a time, so that checking every
    // step costs little beside the contenders.
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&](std::uint64_t word) { h = (h ^ word) * 0x100000001B3ull + (h >> 29); };
    auto bits = [](double value) {
        std::uint64_t word;
        std::memcpy(&word, &value, sizeof word);
        return word;
    };
    for (std::size_t i = 0; i < w.contacts.size(); ++i) {
        const dContactGeom& c = w.contacts[i];
        for (int k = 0; k < 3; ++k) mix(bits(c.pos[k]));
        for (int k = 0; k < 3; ++k) mix(bits(c.normal[k]));
        mix(bits(c.depth));
        mix(reinterpret_cast<std::uintptr_t>(w.pairs[i][0]));
        mix(reinterpret_cast<std::uintptr_t>(w.pairs[i][1]));
    }
    return h;
}

std::vector<Vec3> positions(const World& w) {
    std::vector<Vec3> out;
    for (dBodyID b : w.bodies) {
        const dReal* p = dBodyGetPosition(b);
        out.emplace_back(p[0], p[1], p[2]);
    }
    return out;
}

struct Measured {
    std::string world;
    int bodies = 0, settle = 0, steps = 0;
    std::map<std::string, Series> series;  // by contender, plus "solver"
    std::map<std::string, ProfileSeries> profiles;
    int moving = 0;        // bodies that moved > 1 cm during the measured steps
    int sleeping = 0;      // bodies disabled by ODE's auto-disable at the end
    double farthest = 0;   // m, the largest such move
};

std::string onlyContender;  // --only
int repeat = 1;             // --repeat, with --only

Measured measure(const std::string& name, const std::function<void(World&)>& build, bool autoDisable, int settle,
                 int steps) {
    dRandSetSeed(randomSeed);
    World w;
    build(w);
    Measured m;
    m.world = name;
    m.bodies = static_cast<int>(w.bodies.size());
    m.settle = settle;
    m.steps = steps;
    // The step with the last contender's contacts (every gdcontact contender gives the same):
    // the contact joints and dWorldQuickStep, timed together.
    auto stepWorld = [&] {
        return secondsOf([&] {
            w.makeJoints();
            dWorldQuickStep(w.world, kTimeStep);
        });
    };
    // Auto-disable from half-way through the settling; a body takes the world's settings only when
    // it is made, so each is told.
    auto allowSleep = [&] {
        dWorldSetAutoDisableFlag(w.world, 1);
        for (dBodyID b : w.bodies) {
            dBodySetAutoDisableFlag(b, 1);
            dBodySetAutoDisableAverageSamplesCount(b, kSleepAverageSteps);
            dBodySetAutoDisableLinearThreshold(b, kSleepLinearSpeed);
            dBodySetAutoDisableAngularThreshold(b, kSleepAngularSpeed);
        }
    };
    const Contender settler{"settle", Kind::SpaceAll, true, false, true};
    for (int i = 0; i < settle; ++i) {
        if (i == settle / 2 && autoDisable) allowSleep();
        w.clear();
        runContender(w, settler);
        stepWorld();
        dJointGroupEmpty(w.joints);
    }
    if (autoDisable && settle == 0) allowSleep();
    const std::vector<Vec3> before = positions(w);
    for (int step = 0; step < steps; ++step) {
        int cacheOn = 0;
        std::uint64_t reference = 0;
        bool haveReference = false;
        for (const Contender& c : contenders()) {
            if (!onlyContender.empty()) {
                if (c.name != onlyContender) continue;
            } else if (!c.everyStep && cacheOn++ != step % 3) {
                continue;  // the cache-on three take turns
            }
            w.clear();
            const gdc::ode::PairCacheStats cacheBefore = gdc::ode::pairCacheStats();
            double seconds = 0;
            for (int k = 0; k < repeat; ++k) {
                if (k) w.clear();
                seconds += secondsOf([&] { runContender(w, c); }) / repeat;
            }
            const gdc::ode::PairCacheStats cacheAfter = gdc::ode::pairCacheStats();
            Series& s = m.series[c.name];
            s.ms.push_back(1e3 * seconds);
            s.contacts += static_cast<long long>(w.contacts.size());
            s.cacheHits += static_cast<long long>(cacheAfter.hits - cacheBefore.hits);
            s.cacheCarried += static_cast<long long>(cacheAfter.carried - cacheBefore.carried);
            s.cacheMisses += static_cast<long long>(cacheAfter.misses - cacheBefore.misses);
            ++s.steps;
            if (c.profiled) {
                const gdc::ode::detail::SpaceCollideProfile p = gdc::ode::detail::lastSpaceCollideProfile();
                ProfileSeries& ps = m.profiles[c.name];
                ps.total.push_back(1e3 * p.totalSeconds);
                ps.broad.push_back(1e3 * p.broadPhaseSeconds);
                ps.drain.push_back(1e3 * p.drainSeconds);
                ps.handler.push_back(1e3 * p.handlerSeconds);
                ps.narrow.push_back(1e3 * p.narrowSeconds);
                ps.narrowCaller.push_back(1e3 * p.narrowOnCallerSeconds);
                if (p.poolStartSeconds >= 0) {
                    ps.poolStart.push_back(1e3 * p.poolStartSeconds);
                    ++ps.poolJoined;
                }
                ps.gdcontactPairs += static_cast<double>(p.gdcontactPairs);
                ps.otherPairs += static_cast<double>(p.otherPairs);
                ps.threads = p.threads;
                ++ps.samples;
            }
            if (c.kind == Kind::Loop || c.kind == Kind::Space1 || c.kind == Kind::SpaceAll) {
                const std::uint64_t h = hashContacts(w);
                if (haveReference && h != reference) {
                    std::cerr << "bench_big_world: " << c.name << " gave other contacts than the loop on " << name
                              << " (step " << step << ")\n";
                    std::exit(1);
                }
                reference = h;
                haveReference = true;
            }
        }
        m.series["solver"].ms.push_back(1e3 * stepWorld());
        dJointGroupEmpty(w.joints);
        ++m.series["solver"].steps;
    }
    const std::vector<Vec3> after = positions(w);
    for (std::size_t i = 0; i < before.size(); ++i) {
        const double moved = (after[i] - before[i]).norm();
        m.moving += moved > 0.01;
        m.farthest = std::max(m.farthest, moved);
    }
    for (dBodyID b : w.bodies) m.sleeping += !dBodyIsEnabled(b);
    return m;
}

std::vector<int> parseCounts(const std::string& text) {
    std::vector<int> counts;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) counts.push_back(std::max(1, std::stoi(item)));
    return counts;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<int> counts = {100, 300, 1000, 3000, 10000};
    int settle = 90, steps = 60;
    bool pile = true, resting = false;
    std::string out, profileOut;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--bodies") counts = parseCounts(value());
        else if (arg == "--settle") settle = std::max(0, std::stoi(value()));
        else if (arg == "--steps") steps = std::max(1, std::stoi(value()));
        else if (arg == "--resting") resting = true;
        else if (arg == "--no-pile") pile = false;
        else if (arg == "--out") out = value();
        else if (arg == "--only") onlyContender = value();
        else if (arg == "--space") {
            const std::string kind = value();
            if (kind != "hash" && kind != "sap") throw std::invalid_argument("--space hash|sap");
            sweepAndPrune = kind == "sap";
        }
        else if (arg == "--repeat") repeat = std::max(1, std::stoi(value()));
        else if (arg == "--profile-out") profileOut = value();
        else if (arg == "--seed") randomSeed = std::stoul(value());
        else {
            std::cerr << "usage: bench_big_world [--bodies 100,300,...] [--settle N] [--steps N] [--resting] "
                         "[--no-pile] [--space hash|sap] [--only CONTENDER [--repeat K]] [--seed N] [--out FILE.csv] "
                         "[--profile-out FILE.csv]\n";
            return 2;
        }
    }
    OdeSession ode;  // no install(): dCollide is ODE's native collider
    std::vector<Measured> results;
    auto run = [&](const std::string& name, const std::function<void(World&)>& build, bool autoDisable, int n,
                   int settleSteps) {
        results.push_back(measure(name, build, autoDisable, settleSteps, n));
        Measured& m = results.back();
        std::cerr << "bench_big_world: " << m.world << " (" << m.bodies << " bodies): ode "
                  << statsOf(m.series["ode"].ms).median << " ms, space_1t " << statsOf(m.series["space_1t"].ms).median
                  << " ms, space_mt " << statsOf(m.series["space_mt"].ms).median << " ms, solver "
                  << statsOf(m.series["solver"].ms).median << " ms (medians); " << m.moving
                  << " bodies moved > 1 cm while measured, " << m.sleeping << " asleep\n";
    };
    if (resting) {
        // Three times the pile's steps at 1000 bodies: these worlds are small.
        for (bool asleep : {false, true}) {
            run(asleep ? "brick_wall_asleep" : "brick_wall", buildBrickWall, asleep, 3 * steps, settle);
            run(asleep ? "pyramid_asleep" : "pyramid", buildPyramid, asleep, 3 * steps, settle);
        }
    }
    if (pile)
        for (int count : counts) {
            const int n = std::clamp(static_cast<int>(std::lround(steps * 1000.0 / count)), std::min(15, steps), 4 * steps);
            // Above 1000 bodies the settling shrinks as 1/√count, to a third at 10 000 (the solver
            // takes most of a step there; the table shows how many bodies still moved).
            const int settleSteps = count <= 1000 ? settle
                                                  : std::max(std::min(settle, 30), static_cast<int>(std::lround(
                                                                 settle * std::sqrt(1000.0 / count))));
            run("pile", [count](World& w) { buildPile(w, count); }, false, n, settleSteps);
        }

    std::ofstream file;
    if (!out.empty()) file.open(out);
    std::ostream& csv = out.empty() ? std::cout : file;
    csv << "world,bodies,settle_steps,contender,steps,median_ms,p25_ms,p75_ms,min_ms,max_ms,contacts_per_step,"
           "cache_hits_per_step,cache_carried_per_step,cache_misses_per_step,moving_bodies,farthest_m,sleeping_bodies,hardware_threads\n";
    for (const Measured& m : results)
        for (const auto& [name, s] : m.series) {
            const Stats st = statsOf(s.ms);
            const double n = std::max(1, s.steps);
            csv << m.world << ',' << m.bodies << ',' << m.settle << ',' << name << ',' << s.steps << ',' << st.median
                << ',' << st.p25 << ',' << st.p75 << ',' << st.min << ',' << st.max << ',' << s.contacts / n << ','
                << s.cacheHits / n << ',' << s.cacheCarried / n << ',' << s.cacheMisses / n << ',' << m.moving << ',' << m.farthest << ','
                << m.sleeping << ',' << std::thread::hardware_concurrency() << '\n';
        }
    if (!profileOut.empty()) {
        std::ofstream profile(profileOut);
        profile << "world,bodies,contender,threads,samples,total_ms,broad_phase_ms,drain_ms,handler_ms,narrow_ms,"
                   "narrow_on_caller_ms,gdcontact_pairs,other_pairs,pool_joined_calls,pool_start_ms\n";
        for (const Measured& m : results)
            for (const auto& [name, p] : m.profiles) {
                const double n = std::max(1, p.samples);
                profile << m.world << ',' << m.bodies << ',' << name << ',' << p.threads << ',' << p.samples << ','
                        << statsOf(p.total).median << ',' << statsOf(p.broad).median << ','
                        << statsOf(p.drain).median << ',' << statsOf(p.handler).median << ','
                        << statsOf(p.narrow).median << ',' << statsOf(p.narrowCaller).median << ','
                        << p.gdcontactPairs / n << ',' << p.otherPairs / n << ',' << p.poolJoined << ','
                        << statsOf(p.poolStart).median << '\n';
            }
    }
    return 0;
}

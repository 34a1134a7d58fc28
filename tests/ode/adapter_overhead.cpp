// A driver for callgrind that measures what the ODE adapter adds to the core: the same stream of
// geom pairs collided through gdc::ode::collide and, with the same polytopes, poses and A/B order,
// through gdc::collide directly. Not a test (nothing is asserted); see tests/ode/CMakeLists.txt.
//   ode_adapter_overhead CASE MODE [ROUNDS]           one measured loop (callgrind toggles it)
// MODE: core (gdc::collide), adapter (gdc::ode::collide, pair cache off), cached (pair cache on,
// nothing moves: every call after the first round a hit), cached-moving (pair cache on, every geom
// nudged by 1e-9 between rounds, outside the measurement: every call a miss).
//   ode_adapter_overhead dump [POSES]                 every contact of many pairs, as hex floats
// Adapter overhead per call = Ir(adapter) − Ir(core) for the same CASE (tests/ode/adapter_overhead.sh
// runs every case), e.g.
//   valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file=/dev/null \
//       ode_adapter_overhead box_box adapter
// prints "calls N" and callgrind prints the collected instruction total ("Collected : I").
// `dump` gives a byte-exact record of the adapter's answers (order, normal, depth, flags, skip,
// argument order, misuse excluded) to diff between two versions of the adapter.
//   ode_adapter_overhead scene THREADS STEPS [jitter]   a running scene through spaceCollide
//   ode_adapter_overhead scene-dump THREADS STEPS       its contacts, as hex floats
// `scene` zeroes callgrind's counts after a warm-up step and dumps them (named "scene") after
// STEPS steps, every thread counted: run it with callgrind collecting from the start, e.g.
//   valgrind --tool=callgrind ode_adapter_overhead scene 2 20
// and subtract the same run with `jitter` (the steps' moves without spaceCollide); docs/ode.md,
// "The hull registry", has the numbers.
#include <gdcontact/ode.hpp>

#include "ode_support.hpp"

#include <valgrind/callgrind.h>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

using namespace gdc;
using namespace gdc::ode::test;

namespace {

constexpr int kPoses = 16;
constexpr double kOverlap = 0.005;  // resting pairs overlap by 5 mm

struct Pair {
    dGeomID o1, o2;
};

// The stream of one case: its pairs, cycled.
struct Stream {
    std::vector<Pair> pairs;
};

// A pose jittered by about ±1 mm and ±0.01 rad, as in design.md's measuring rules.
Pose jittered(std::mt19937_64& random, const Vec3& position, double yaw = 0.0) {
    std::uniform_real_distribution<double> millimetre(-1e-3, 1e-3), centiradian(-0.01, 0.01);
    const Mat3 rotation = (Eigen::AngleAxisd(yaw + centiradian(random), Vec3::UnitZ()) *
                           Eigen::AngleAxisd(centiradian(random), Vec3::UnitX()) *
                           Eigen::AngleAxisd(centiradian(random), Vec3::UnitY()))
                              .toRotationMatrix();
    return Pose{rotation, position + Vec3(millimetre(random), millimetre(random), millimetre(random))};
}

dGeomID cube() { return dCreateBox(0, 1, 1, 1); }
dGeomID hull() {
    static const std::vector<dReal> corners = boxCorners(Vec3::Constant(0.5));
    return gdc::ode::createConvex(0, corners.data(), 8);
}

// A cube resting on another, turned by 45° about the vertical: an octagon of 8 contacts.
Stream restingPairs(const std::function<dGeomID()>& make, int count, std::uint64_t seed) {
    std::mt19937_64 random(seed);
    Stream stream;
    for (int i = 0; i < count; ++i) {
        dGeomID lower = make(), upper = make();
        setPose(lower, jittered(random, Vec3::Zero()));
        setPose(upper, jittered(random, Vec3(0, 0, 1.0 - kOverlap), M_PI / 4));
        stream.pairs.push_back({upper, lower});
    }
    return stream;
}

Stream cubesOnPlane(int count, std::uint64_t seed, const std::function<dGeomID()>& make = cube) {
    std::mt19937_64 random(seed);
    dGeomID ground = dCreatePlane(0, 0, 0, 1, 0);
    Stream stream;
    for (int i = 0; i < count; ++i) {
        dGeomID box = make();
        setPose(box, jittered(random, Vec3(0, 0, 0.5 - kOverlap)));
        stream.pairs.push_back({box, ground});
    }
    return stream;
}

Stream separatedCubes(int count, std::uint64_t seed) {
    std::mt19937_64 random(seed);
    Stream stream;
    for (int i = 0; i < count; ++i) {
        dGeomID left = cube(), right = cube();
        setPose(left, jittered(random, Vec3::Zero()));
        setPose(right, jittered(random, Vec3(1.1, 0, 0)));
        stream.pairs.push_back({left, right});
    }
    return stream;
}

Stream makeCase(const std::string& name) {
    if (name == "box_box") return restingPairs(cube, kPoses, 1);
    if (name == "box_plane") return cubesOnPlane(kPoses, 2);
    if (name == "hull_plane") return cubesOnPlane(kPoses, 6, hull);  // convex–plane: the cube as a hull
    if (name == "hull_hull") return restingPairs(hull, kPoses, 3);
    if (name == "box_box_separated") return separatedCubes(kPoses, 4);
    if (name == "hull_scene_2000") return restingPairs(hull, 1000, 5);  // 2000 hull geoms
    std::fprintf(stderr, "unknown case %s\n", name.c_str());
    std::exit(2);
}

// The core call collide() makes for the pair: the same polytopes, poses and A/B order.
struct CoreCall {
    std::shared_ptr<const Polytope> a, b;  // b null: a plane
    Pose poseA, poseB;
    HalfSpace plane;
};

CoreCall coreCallOf(const Pair& pair) {
    CoreCall call;
    dGeomID first = pair.o1, second = pair.o2;
    if (dGeomGetClass(first) == dPlaneClass) std::swap(first, second);
    if (dGeomGetClass(second) == dPlaneClass) {
        dVector4 parameters;
        dGeomPlaneGetParams(second, parameters);
        call.plane = HalfSpace{Vec3(parameters[0], parameters[1], parameters[2]).normalized(), parameters[3]};
    } else {
        const Vec3 p = gdc::ode::poseOf(first).position, q = gdc::ode::poseOf(second).position;
        const bool secondFirst = q.x() != p.x() ? q.x() < p.x()
                                 : q.y() != p.y() ? q.y() < p.y()
                                 : q.z() != p.z() ? q.z() < p.z()
                                                  : std::less<const void*>{}(second, first);
        if (secondFirst) std::swap(first, second);
        call.b = gdc::ode::polytopeOf(second);
        call.poseB = gdc::ode::poseOf(second);
    }
    call.a = gdc::ode::polytopeOf(first);
    call.poseA = gdc::ode::poseOf(first);
    return call;
}

// The settings of every call: the defaults, or with GDC_OVERHEAD_MAX_CONTACTS set, that budget (to
// compare the cost per call at an equal number of points across a change of the default budget).
Settings overheadSettings() {
    Settings settings;
    if (const char* budget = std::getenv("GDC_OVERHEAD_MAX_CONTACTS")) settings.maxContacts = std::atoi(budget);
    return settings;
}

int measure(const std::string& name, const std::string& mode, int rounds) {
    const Stream stream = makeCase(name);
    std::vector<CoreCall> calls;
    for (const Pair& pair : stream.pairs) calls.push_back(coreCallOf(pair));
    std::vector<dContact> out(16);
    const Settings settings = overheadSettings();
    long long contacts = 0, count = 0;
    auto adapterRound = [&] {
        for (const Pair& pair : stream.pairs)
            contacts += gdc::ode::collide(pair.o1, pair.o2, 16, &out[0].geom, sizeof(dContact));
    };
    auto coreRound = [&] {
        for (const CoreCall& call : calls)
            contacts += (call.b ? gdc::collide(*call.a, call.poseA, *call.b, call.poseB, settings)
                                : gdc::collide(*call.a, call.poseA, call.plane, settings))
                            .pointCount;
    };
    const bool moving = mode == "cached-moving";
    const bool adapter = mode == "adapter" || mode == "cached" || moving;
    if (!adapter && mode != "core") {
        std::fprintf(stderr, "mode must be core, adapter, cached or cached-moving\n");
        return 2;
    }
    gdc::ode::setPairCacheEnabled(mode == "cached" || moving);
    // Moves every placeable geom of the stream by ±1e-9 along x (alternating by round), and lets ODE
    // bring its AABB up to date, as its broad phase would have before the collider runs.
    auto nudge = [&](int round) {
        for (const Pair& pair : stream.pairs)
            for (dGeomID geom : {pair.o1, pair.o2}) {
                if (dGeomGetClass(geom) == dPlaneClass) continue;
                const dReal* p = dGeomGetPosition(geom);
                dGeomSetPosition(geom, p[0] + (round % 2 ? 1e-9 : -1e-9), p[1], p[2]);
                dReal aabb[6];
                dGeomGetAABB(geom, aabb);
            }
    };
    // One round unmeasured: every per-thread cache warm, as in a running simulation.
    adapter ? adapterRound() : coreRound();
    contacts = 0;
    for (int round = 0; round < rounds; ++round) {
        if (moving) nudge(round);
        CALLGRIND_TOGGLE_COLLECT;
        adapter ? adapterRound() : coreRound();
        CALLGRIND_TOGGLE_COLLECT;
    }
    count = static_cast<long long>(rounds) * static_cast<long long>(stream.pairs.size());
    std::printf("%s %s calls %lld contacts/call %.3f\n", name.c_str(), mode.c_str(), count,
                static_cast<double>(contacts) / static_cast<double>(count));
    return 0;
}

void print(const dContactGeom& c, dGeomID o1, dGeomID o2) {
    std::printf("  %a %a %a | %a %a %a %a | %a | %d %d %d\n", c.pos[0], c.pos[1], c.pos[2], c.normal[0],
                c.normal[1], c.normal[2], c.normal[3], c.depth, c.g1 == o1, c.g2 == o2, c.side1 * 10 + c.side2);
}

// Random poses of every supported pair type, both argument orders, several contact limits and
// strides: the adapter's whole observable answer.
int dump(int poses) {
    std::mt19937_64 random(20261123);
    std::uniform_real_distribution<double> offset(-0.6, 0.6);
    dGeomID box = dCreateBox(0, 1.0, 0.8, 0.6), box2 = dCreateBox(0, 0.7, 0.7, 0.7);
    const auto points = boxCorners(Vec3(0.45, 0.35, 0.3));
    std::vector<dReal> cloud;
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    for (int i = 0; i < 3 * 30; ++i) cloud.push_back(unit(random));
    dGeomID convex = gdc::ode::createConvex(0, points.data(), 8);
    dGeomID convex2 = gdc::ode::createConvex(0, cloud.data(), 30);
    dGeomID plane = dCreatePlane(0, 0.1, -0.2, 1.0, 0.05);
    const dGeomID geoms[] = {box, box2, convex, convex2, plane};
    std::vector<dContact> out(16);
    for (int pose = 0; pose < poses; ++pose) {
        for (dGeomID g : geoms)
            if (g != plane) setPose(g, Pose{randomRotation(random), Vec3(offset(random), offset(random), offset(random))});
        // Sometimes resting faces: aligned rotations make exact ties in depth.
        if (pose % 7 == 0) {
            setPose(box, Pose{Mat3::Identity(), Vec3(0, 0, 0)});
            setPose(box2, Pose{Mat3::Identity(), Vec3(0.2, 0.1, 0.64)});
            setPose(convex, Pose{Mat3::Identity(), Vec3(0.1, 0.0, 0.6)});
        }
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j) {
                dGeomID a = geoms[i], b = geoms[j];
                if (a == b || (a == plane && b == plane)) continue;
                for (int limit : {16, 8, 3, 1}) {
                    const int skip = limit == 3 ? static_cast<int>(sizeof(dContactGeom)) : static_cast<int>(sizeof(dContact));
                    const int flags = limit | (limit == 1 ? CONTACTS_UNIMPORTANT : 0);
                    char* base = reinterpret_cast<char*>(out.data());
                    const int n = gdc::ode::collide(a, b, flags, reinterpret_cast<dContactGeom*>(base), skip);
                    std::printf("pose %d pair %d %d limit %d: %d\n", pose, i, j, limit, n);
                    for (int k = 0; k < n; ++k) print(*reinterpret_cast<dContactGeom*>(base + k * skip), a, b);
                }
            }
    }
    return 0;
}

// ---- A running scene through gdc::ode::spaceCollide ----
//
// 96 geoms (boxes of two sizes, a cube hull and a 12-point hull made with createConvex), each on
// its own body, in three loose layers over a ground plane in a hash space: box–box, box–hull,
// hull–hull, box–plane and hull–plane pairs, touching and separated. Every step moves each body
// to a fresh random pose near its place (the same sequence for a given seed).
struct Scene {
    dWorldID world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(0);
    std::vector<dBodyID> bodies;
    std::vector<Vec3> homes;
    std::mt19937_64 random;

    explicit Scene(std::uint64_t seed) : random(seed) {
        dCreatePlane(space, 0, 0, 1, 0);
        static const std::vector<dReal> cubeCorners = boxCorners(Vec3::Constant(0.35));
        static const std::vector<dReal> cloud = [] {
            std::mt19937_64 r(7);
            std::uniform_real_distribution<double> u(-0.4, 0.4);
            std::vector<dReal> points;
            for (int i = 0; i < 3 * 12; ++i) points.push_back(u(r));
            return points;
        }();
        for (int i = 0; i < 96; ++i) {
            dGeomID geom;
            switch (i % 4) {
                case 0: geom = dCreateBox(space, 0.8, 0.6, 0.5); break;
                case 1: geom = dCreateBox(space, 0.7, 0.7, 0.7); break;
                case 2: geom = gdc::ode::createConvex(space, cubeCorners.data(), 8); break;
                default: geom = gdc::ode::createConvex(space, cloud.data(), 12); break;
            }
            dBodyID body = dBodyCreate(world);
            dGeomSetBody(geom, body);
            bodies.push_back(body);
            homes.emplace_back(0.8 * (i % 8), 0.8 * ((i / 8) % 4), 0.32 + 0.75 * (i / 32));
        }
        move();
    }
    ~Scene() {
        dSpaceDestroy(space);
        dWorldDestroy(world);
    }
    void move() {
        std::uniform_real_distribution<double> centimetre(-0.05, 0.05);
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            const Mat3 rotation = randomRotation(random);
            dMatrix3 r;
            for (int row = 0; row < 3; ++row) {
                for (int column = 0; column < 3; ++column) r[4 * row + column] = rotation(row, column);
                r[4 * row + 3] = 0;
            }
            const Vec3 p = homes[i] + Vec3(centimetre(random), centimetre(random), centimetre(random));
            dBodySetPosition(bodies[i], p.x(), p.y(), p.z());
            dBodySetRotation(bodies[i], r);
        }
    }
};

struct SceneCount {
    long long pairs = 0, contacts = 0;
    bool print = false;
};

void countContacts(void* data, dGeomID, dGeomID, dContactGeom* contacts, int count) {
    SceneCount& total = *static_cast<SceneCount*>(data);
    ++total.pairs;
    total.contacts += count;
    if (total.print)
        for (int k = 0; k < count; ++k) print(contacts[k], contacts[k].g1, contacts[k].g2);
}

// `scene THREADS STEPS [jitter]`: callgrind's counts (all threads: run with --collect-atstart=yes)
// are zeroed after a warm-up step and dumped after STEPS steps; `jitter` runs the same steps
// without spaceCollide (the cost of moving the bodies, to subtract).
int sceneSteps(int threads, int steps, bool jitterOnly) {
    gdc::ode::setThreadCount(threads);
    Scene scene(11);
    SceneCount total;
    gdc::ode::spaceCollide(scene.space, 16, &total, &countContacts);  // warm: caches and pool
    total = SceneCount{};
    CALLGRIND_ZERO_STATS;
    for (int step = 0; step < steps; ++step) {
        scene.move();
        if (!jitterOnly) gdc::ode::spaceCollide(scene.space, 16, &total, &countContacts);
    }
    CALLGRIND_DUMP_STATS_AT("scene");
    std::printf("scene threads %d steps %d touching pairs/step %.1f contacts/step %.1f\n", threads, steps,
                static_cast<double>(total.pairs) / steps, static_cast<double>(total.contacts) / steps);
    return 0;
}

// `scene-dump THREADS STEPS`: every contact spaceCollide hands over, as hex floats, to diff
// between two versions of the adapter.
int sceneDump(int threads, int steps) {
    gdc::ode::setThreadCount(threads);
    Scene scene(12);
    SceneCount total;
    total.print = true;
    for (int step = 0; step < steps; ++step) {
        scene.move();
        std::printf("step %d\n", step);
        gdc::ode::spaceCollide(scene.space, 16, &total, &countContacts);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    dInitODE2(0);
    gdc::ode::install(overheadSettings());
    if (argc >= 2 && std::string(argv[1]) == "dump") return dump(argc > 2 ? std::atoi(argv[2]) : 2000);
    if (argc >= 4 && std::string(argv[1]) == "scene")
        return sceneSteps(std::atoi(argv[2]), std::atoi(argv[3]), argc > 4 && std::string(argv[4]) == "jitter");
    if (argc >= 4 && std::string(argv[1]) == "scene-dump") return sceneDump(std::atoi(argv[2]), std::atoi(argv[3]));
    if (argc < 3) {
        std::fprintf(stderr,
                     "usage: ode_adapter_overhead CASE adapter|core [ROUNDS] | dump [POSES] | scene THREADS STEPS [jitter]"
                     " | scene-dump THREADS STEPS\n"
                     "cases: box_box box_plane hull_plane hull_hull box_box_separated hull_scene_2000\n");
        return 2;
    }
    const int result = measure(argv[1], argv[2], argc > 3 ? std::atoi(argv[3]) : 50);
    dCloseODE();
    return result;
}

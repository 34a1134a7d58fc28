// Not a test: a small driver that measures how the contact set gdcontact hands ODE's solvers (its
// budget and its order) carries scenes over many seeds, against ODE's own dBox colliders in the
// same program — the measurements behind docs/algorithm.md, "The contact set the solver gets".
// Scenes are chaotic under dWorldQuickStep: each seed sets dRandSetSeed (QuickStep's row shuffles)
// and jitters the start poses; a figure is a count or a percentile over the seeds.
//
// Usage: ode_contact_order_seeds SCENE CONTENDER SEEDS [ITERATIONS]
//   SCENE: heavy (100 kg on two 1 kg boxes) | heavy1000 | stack10 | stack20 | pile (time to sleep)
//     | stack10-bench, stack20-bench (bench_solver_seeds' stacks: 20 cm cubes, its jitter, 4 s)
//     | plates20 (bench_solver_seeds' 10 plates of 50×50×2.5 cm, 3 s; failed: a plate sank by more
//     than half its thickness) | heavycube (the robustness tests' 100 kg cube turned 0.1 rad on a
//     1 kg cube, 10 s, ERP 0.2, CFM 1e-5, μ 0.8, no start jitter — only dRandSetSeed — as in
//     tests/robustness/world_test.cpp; drift: the largest horizontal displacement after 2 s, its
//     mean over the seeds printed too, as that test averages it)
//   CONTENDER: dbox (ODE's own box colliders; dbox:N passes maxc N, dBoxBox then culls to N) | gdc:ORDER:BUDGET:HYSTERESIS, ORDER one of
//     last (Settings::ContactOrder::DeepestLast), first (DeepestFirst), or, to measure what an
//     order by depth is worth, importance-last / importance-first: the core's own array (the order
//     of importance, gdc::collide) made into joints as it is / reversed, so that the solver meets
//     it reversed / as it is; BUDGET maxContacts, HYSTERESIS reductionHysteresis
//   e.g. ode_contact_order_seeds stack20 gdc:first:4:0.01 200 20
// Prints one line: the scene, the contender, the failed seeds, drift percentiles (m), contacts per
// step, and for `pile` the bodies asleep at 5 s and the median time until all sleep.
#include <gdcontact/gdcontact.hpp>
#include <gdcontact/ode.hpp>

#include <ode/ode.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

namespace {

enum class Order { Last, First, ImportanceLast, ImportanceFirst, Cyclic };

struct Contender {
    bool ode = false;
    int odeBudget = 16;  // dCollide's maxc for ODE's own colliders
    Order order = Order::Last;
    gdc::Settings settings;
};

Contender parseContender(const std::string& text) {
    Contender contender;
    if (text == "dbox" || text.rfind("dbox:", 0) == 0) {  // dbox:N asks ODE's colliders for at most N
        contender.ode = true;
        contender.odeBudget = text == "dbox" ? 16 : std::atoi(text.c_str() + 5);
        return contender;
    }
    char order[32] = {};
    int budget = 4;
    double hysteresis = 0.01;
    if (std::sscanf(text.c_str(), "gdc:%31[a-z-]:%d:%lf", order, &budget, &hysteresis) < 1) {
        std::fprintf(stderr, "bad contender %s\n", text.c_str());
        std::exit(2);
    }
    const std::string o = order;
    if (o != "first" && o != "last" && o != "importance-last" && o != "importance-first" && o != "cyclic") {
        std::fprintf(stderr, "bad order %s (first, last, importance-last, importance-first)\n", order);
        std::exit(2);
    }
    contender.order = o == "first"              ? Order::First
                      : o == "importance-last"  ? Order::ImportanceLast
                      : o == "importance-first" ? Order::ImportanceFirst
                      : o == "cyclic"           ? Order::Cyclic
                                                : Order::Last;
    contender.settings.maxContacts = budget;
    contender.settings.reductionHysteresis = hysteresis;
    contender.settings.contactOrder =
        contender.order == Order::First ? gdc::ContactOrder::DeepestFirst : gdc::ContactOrder::DeepestLast;
    return contender;
}

struct World {
    dWorldID world;
    dSpaceID space;
    dJointGroupID contacts;
    std::vector<dBodyID> bodies;
    const Contender* contender;
    long contactCount = 0;
    double mu = 0.6;
};

// The core's contacts for a box–box or box–plane pair in its own order (the order of importance),
// in ODE's convention (normal from o2 into o1, depth ≥ 0).
int coreContacts(dGeomID o1, dGeomID o2, const gdc::Settings& settings, dContactGeom* out) {
    const bool planeFirst = dGeomGetClass(o1) == dPlaneClass;
    const bool planeSecond = dGeomGetClass(o2) == dPlaneClass;
    dGeomID body = planeFirst ? o2 : o1;
    const auto a = gdc::ode::polytopeOf(body);
    gdc::Manifold m;
    if (planeFirst || planeSecond) {
        dVector4 plane;
        dGeomPlaneGetParams(planeFirst ? o1 : o2, plane);
        m = gdc::collide(*a, gdc::ode::poseOf(body), gdc::HalfSpace{gdc::Vec3(plane[0], plane[1], plane[2]), plane[3]},
                         settings);
    } else {
        m = gdc::collide(*a, gdc::ode::poseOf(o1), *gdc::ode::polytopeOf(o2), gdc::ode::poseOf(o2), settings);
    }
    const gdc::Vec3 normal = planeFirst ? m.normal : gdc::Vec3(-m.normal);  // the core's A is `body`
    int n = 0;
    for (int i = 0; i < m.pointCount; ++i) {
        if (m.points[i].depth < 0) continue;
        dContactGeom& g = out[n++];
        g = dContactGeom{};
        for (int k = 0; k < 3; ++k) g.pos[k] = m.points[i].position[k], g.normal[k] = normal[k];
        g.depth = m.points[i].depth;
        g.g1 = o1, g.g2 = o2, g.side1 = g.side2 = -1;
    }
    return n;
}

void nearCallback(void* data, dGeomID o1, dGeomID o2) {
    World& w = *static_cast<World*>(data);
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
    dContactGeom geoms[16];
    const bool importance = w.contender->order == Order::ImportanceLast ||
                            w.contender->order == Order::ImportanceFirst || w.contender->order == Order::Cyclic;
    const int n = importance ? coreContacts(o1, o2, w.contender->settings, geoms) : dCollide(o1, o2, w.contender->ode ? w.contender->odeBudget : 16, geoms, sizeof(dContactGeom));
    if (w.contender->order == Order::ImportanceFirst) std::reverse(geoms, geoms + n);
    if (w.contender->order == Order::Cyclic && n > 2) {
        // Around the polygon from the deepest point (the core's first), by angle about the points'
        // mean in a basis of the contact plane; made into joints reversed, so that the solver meets
        // them deepest first and then around.
        double mean[3] = {0, 0, 0};
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) mean[k] += geoms[i].pos[k] / n;
        const dReal* nz = geoms[0].normal;
        double u[3] = {1, 0, 0};
        if (std::abs(nz[0]) > 0.9) u[0] = 0, u[1] = 1;
        const double d = u[0] * nz[0] + u[1] * nz[1] + u[2] * nz[2];
        for (int k = 0; k < 3; ++k) u[k] -= d * nz[k];
        const double v[3] = {nz[1] * u[2] - nz[2] * u[1], nz[2] * u[0] - nz[0] * u[2], nz[0] * u[1] - nz[1] * u[0]};
        auto angle = [&](const dContactGeom& g) {
            double x = 0, y = 0;
            for (int k = 0; k < 3; ++k) x += (g.pos[k] - mean[k]) * u[k], y += (g.pos[k] - mean[k]) * v[k];
            return std::atan2(y, x);
        };
        const double start = angle(geoms[0]);
        std::stable_sort(geoms + 1, geoms + n, [&](const dContactGeom& a, const dContactGeom& b) {
            auto from = [&](const dContactGeom& g) { double t = angle(g) - start; return t < 0 ? t + 6.283185307179586 : t; };
            return from(a) < from(b);
        });
        std::reverse(geoms, geoms + n);
    }
    for (int i = 0; i < n; ++i) {
        dContact contact{};
        contact.surface.mode = dContactApprox1;
        contact.surface.mu = w.mu;
        contact.geom = geoms[i];
        dJointID joint = dJointCreateContact(w.world, w.contacts, &contact);
        dJointAttach(joint, b1, b2);
    }
    w.contactCount += n;
}

dBodyID addBox(World& w, double sx, double sy, double sz, double mass, const std::array<double, 3>& position, double yaw) {
    dBodyID body = dBodyCreate(w.world);
    dMass m;
    dMassSetBoxTotal(&m, mass, sx, sy, sz);
    dBodySetMass(body, &m);
    dBodySetPosition(body, position[0], position[1], position[2]);
    dMatrix3 r;
    dRFromAxisAndAngle(r, 0, 0, 1, yaw);
    dBodySetRotation(body, r);
    dGeomID geom = dCreateBox(w.space, sx, sy, sz);
    dGeomSetBody(geom, body);
    w.bodies.push_back(body);
    return body;
}

struct Outcome {
    bool failed = false;
    double drift = 0;      // m: the scene's drift measure
    double asleepAt5 = 0;  // pile: bodies disabled at 5 s
    double allAsleep = INFINITY;  // pile: s until every body is disabled
    double contactsPerStep = 0;
    double drop = 0;  // plates20: the largest sink of a plate below its start (m), over the run
    bool failedBenchLimits = false;  // stacks: bench_solver_seeds' limits (failureLimits(), "standing")
};

Outcome run(const std::string& scene, const Contender& contender, int seed, int iterations) {
    dInitODE2(0);
    if (!contender.ode) gdc::ode::install(contender.settings);
    dRandSetSeed(static_cast<unsigned long>(seed));
    std::mt19937 random(static_cast<unsigned>(seed) * 2654435761u + 1);
    std::uniform_real_distribution<double> jitter(-1, 1);
    World w;
    w.contender = &contender;
    w.world = dWorldCreate();
    w.space = dHashSpaceCreate(nullptr);
    w.contacts = dJointGroupCreate(0);
    dWorldSetGravity(w.world, 0, 0, -9.81);
    dWorldSetQuickStepNumIterations(w.world, iterations);
    dCreatePlane(w.space, 0, 0, 1, 0);
    const double dt = 0.01;
    double seconds = 10;
    Outcome outcome;
    std::vector<std::array<double, 3>> start;
    if (scene == "heavy" || scene == "heavy1000") {
        const double heavy = scene == "heavy" ? 100 : 1000;
        for (int side : {-1, 1}) {
            const std::array<double, 3> p = {side * 0.75 + 0.01 * jitter(random), 0.01 * jitter(random), 0.5};
            addBox(w, 1, 1, 1, 1, p, 0.02 * jitter(random));
        }
        const std::array<double, 3> p = {0.02 * jitter(random), 0.02 * jitter(random), 1.5};
        addBox(w, 3, 1, 1, heavy, p, 0.02 * jitter(random));
        seconds = 5;
    } else if (scene == "stack10" || scene == "stack20") {
        const int count = scene == "stack10" ? 10 : 20;
        for (int i = 0; i < count; ++i) {
            const std::array<double, 3> p = {0.01 * jitter(random), 0.01 * jitter(random), 0.5 + i};
            addBox(w, 1, 1, 1, 1, p, 0.01 * jitter(random));
        }
        seconds = 10;
    } else if (scene == "stack10-bench" || scene == "stack20-bench") {
        // bench_solver_seeds' stacks: 20 cm cubes of 1000 kg/m³ (8 kg), no gap, its jitter ranges
        // (±1 mm, ±0.01 rad yaw, ±0.002 rad tilt about x and y), 4 s.
        const int count = scene == "stack10-bench" ? 10 : 20;
        for (int i = 0; i < count; ++i) {
            const std::array<double, 3> p = {1e-3 * jitter(random), 1e-3 * jitter(random), 0.1 + 0.2 * i};
            dBodyID body = addBox(w, 0.2, 0.2, 0.2, 8, p, 0);
            dMatrix3 r;
            dRFromEulerAngles(r, 0.002 * jitter(random), 0.002 * jitter(random), 0.01 * jitter(random));
            dBodySetRotation(body, r);
        }
        seconds = 4;
    } else if (scene == "pile") {
        dWorldSetAutoDisableFlag(w.world, 1);  // ODE's default thresholds
        std::uniform_real_distribution<double> unit(0, 1);
        for (int i = 0; i < 24; ++i) {
            const std::array<double, 3> p = {1.5 * jitter(random), 1.5 * jitter(random), 0.6 + 1.1 * i / 3.0};
            dBodyID body = addBox(w, 1, 1, 1, 1, p, 3.14159 * jitter(random));
            dMatrix3 r;
            dRFromEulerAngles(r, 0.3 * jitter(random), 0.3 * jitter(random), 3.14159 * jitter(random));
            dBodySetRotation(body, r);
        }
        seconds = 10;
    } else if (scene == "plates20") {
        // bench/solver_seeds' plates20 with its jitter ranges (±1 mm, ±0.01 rad yaw, ±0.002 rad tilt).
        const double half = 0.25, halfThickness = half / 20;
        for (int i = 0; i < 10; ++i) {
            const std::array<double, 3> p = {1e-3 * jitter(random), 1e-3 * jitter(random), halfThickness * (1 + 2 * i)};
            dBodyID body = addBox(w, 2 * half, 2 * half, 2 * halfThickness, 1000 * 8 * half * half * halfThickness, p, 0);
            dMatrix3 r;
            dRFromEulerAngles(r, 0.002 * jitter(random), 0.002 * jitter(random), 0.01 * jitter(random));
            dBodySetRotation(body, r);
        }
        seconds = 3;
    } else if (scene == "heavycube") {
        dWorldSetERP(w.world, 0.2);
        dWorldSetCFM(w.world, 1e-5);
        w.mu = 0.8;
        const std::array<double, 3> low = {0, 0, 0.5}, high = {0.05, 0.02, 1.4999};
        addBox(w, 1, 1, 1, 1, low, 0);
        addBox(w, 1, 1, 1, 100, high, 0.1);
        seconds = 10;
    } else {
        std::fprintf(stderr, "unknown scene %s\n", scene.c_str());
        std::exit(2);
    }
    std::vector<std::array<double, 3>> startUp;
    for (dBodyID body : w.bodies) {
        const dReal* q = dBodyGetPosition(body);
        start.push_back({q[0], q[1], q[2]});
        const dReal* r = dBodyGetRotation(body);
        startUp.push_back({r[2], r[6], r[10]});
    }
    const int steps = static_cast<int>(std::lround(seconds / dt));
    std::vector<std::array<double, 3>> settled;
    for (int step = 0; step < steps; ++step) {
        dSpaceCollide(w.space, &w, &nearCallback);
        dWorldQuickStep(w.world, dt);
        dJointGroupEmpty(w.contacts);
        if (scene == "heavycube") {  // as the robustness test: the largest drift of a body after 2 s
            if (step + 1 == 200)
                for (dBodyID body : w.bodies) {
                    const dReal* q = dBodyGetPosition(body);
                    settled.push_back({q[0], q[1], q[2]});
                }
            if (step + 1 > 200)
                for (size_t i = 0; i < w.bodies.size(); ++i) {
                    const dReal* q = dBodyGetPosition(w.bodies[i]);
                    outcome.drift = std::max(outcome.drift, std::hypot(q[0] - settled[i][0], q[1] - settled[i][1]));
                }
        }
        if (scene == "plates20") {
            for (size_t i = 0; i < w.bodies.size(); ++i)
                outcome.drop = std::max(outcome.drop, start[i][2] - dBodyGetPosition(w.bodies[i])[2]);
        }
        if (scene == "pile") {
            int asleep = 0;
            for (dBodyID body : w.bodies) asleep += dBodyIsEnabled(body) ? 0 : 1;
            if (step + 1 == static_cast<int>(std::lround(5 / dt))) outcome.asleepAt5 = asleep;
            if (asleep == static_cast<int>(w.bodies.size()) && !std::isfinite(outcome.allAsleep))
                outcome.allAsleep = (step + 1) * dt;
        }
    }
    outcome.contactsPerStep = static_cast<double>(w.contactCount) / steps;
    auto horizontal = [&](int i) {
        const dReal* q = dBodyGetPosition(w.bodies[i]);
        return std::hypot(q[0] - start[i][0], q[1] - start[i][1]);
    };
    const int n = static_cast<int>(w.bodies.size());
    if (scene == "heavy" || scene == "heavy1000") {
        const dReal* top = dBodyGetPosition(w.bodies[2]);
        const dReal* r = dBodyGetRotation(w.bodies[2]);
        outcome.drift = std::max({horizontal(0), horizontal(1), horizontal(2)});
        // Collapsed: the heavy box sank by more than 10 cm, tilted by more than ~6°, or a light box slid away.
        outcome.failed = top[2] < 1.4 || r[10] < 0.995 || horizontal(0) > 0.25 || horizontal(1) > 0.25;
    } else if (scene == "heavycube") {
        outcome.failed = dBodyGetPosition(w.bodies[1])[2] < 1.0;  // the heavy cube fell off
    } else if (scene == "plates20") {
        outcome.drift = 0;
        for (int i = 0; i < n; ++i) outcome.drift = std::max(outcome.drift, horizontal(i));
        double finalDrop = 0;
        for (int i = 0; i < n; ++i) finalDrop = std::max(finalDrop, start[i][2] - dBodyGetPosition(w.bodies[i])[2]);
        outcome.failed = finalDrop > 0.0125;  // the bench's limit: half the plate's thickness, at the end
    } else if (scene == "pile") {
        outcome.drift = 0;
    } else {
        const double size = scene == "stack10" || scene == "stack20" ? 1.0 : 0.2;
        const dReal* top = dBodyGetPosition(w.bodies[n - 1]);
        outcome.drift = horizontal(n - 1);
        outcome.failed = top[2] < start[n - 1][2] - 0.5 * size;  // the top box fell (by more than half its size)
    }
    // bench_solver_seeds' limits for standing scenes (failureLimits() in bench/solver_seeds, the one
    // table of docs/benchmarks.md), at the end: a body more than half its least horizontal extent
    // from its start horizontally, its up axis turned more than 0.25 rad, or its centre lower than
    // its start by more than half its height (every body here starts on its support: no gap).
    for (int i = 0; i < n && scene != "pile"; ++i) {
        dGeomID geom = dBodyGetFirstGeom(w.bodies[i]);
        dVector3 sides;
        dGeomBoxGetLengths(geom, sides);
        const double width = std::min(sides[0], sides[1]), height = sides[2];  // boxes start upright
        const dReal* q = dBodyGetPosition(w.bodies[i]);
        const dReal* r = dBodyGetRotation(w.bodies[i]);
        const double cosTilt = r[2] * startUp[i][0] + r[6] * startUp[i][1] + r[10] * startUp[i][2];
        if (!std::isfinite(q[0] + q[1] + q[2]) || horizontal(i) > 0.5 * width || cosTilt < std::cos(0.25) ||
            start[i][2] - q[2] > 0.5 * height)
            outcome.failedBenchLimits = true;
    }
    dJointGroupDestroy(w.contacts);
    dSpaceDestroy(w.space);
    dWorldDestroy(w.world);
    dCloseODE();
    return outcome;
}

double percentile(std::vector<double> values, double p) {
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    const double at = p * (values.size() - 1);
    const size_t below = static_cast<size_t>(std::floor(at));
    const size_t above = std::min(values.size() - 1, below + 1);
    return values[below] + (at - below) * (values[above] - values[below]);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s SCENE CONTENDER SEEDS [ITERATIONS]\n", argv[0]);
        return 2;
    }
    const std::string scene = argv[1];
    const Contender contender = parseContender(argv[2]);
    const int seeds = std::atoi(argv[3]);
    const int iterations = argc > 4 ? std::atoi(argv[4]) : 20;
    int failed = 0, failedBenchLimits = 0;
    std::vector<double> drifts, asleep, allAsleep, drops;
    std::vector<int> failedSeeds;
    double contacts = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
        const Outcome o = run(scene, contender, seed, iterations);
        failed += o.failed ? 1 : 0;
        failedBenchLimits += o.failedBenchLimits ? 1 : 0;
        if (o.failed) failedSeeds.push_back(seed);
        drops.push_back(o.drop);
        drifts.push_back(o.drift);
        asleep.push_back(o.asleepAt5);
        allAsleep.push_back(o.allAsleep);
        contacts += o.contactsPerStep;
    }
    std::printf("%-9s %-18s seeds %3d iters %2d  failed %3d  drift p50 %8.4f p90 %8.4f  contacts/step %6.2f",
                scene.c_str(), argv[2], seeds, iterations, failed, percentile(drifts, 0.5), percentile(drifts, 0.9),
                contacts / seeds);
    if (scene == "pile")
        std::printf("  asleep@5s %5.2f  all-asleep p50 %5.2f s (never in %d)", percentile(asleep, 0.5) * 0 +
                    [&] { double s = 0; for (double a : asleep) s += a; return s / seeds; }(),
                    percentile(allAsleep, 0.5),
                    static_cast<int>(std::count_if(allAsleep.begin(), allAsleep.end(), [](double t) { return !std::isfinite(t); })));
    if (scene == "heavycube") {
        double mean = 0, square = 0;
        for (double d : drifts) mean += d / seeds;
        for (double d : drifts) square += (d - mean) * (d - mean);
        // The standard error of the mean: the sample's standard deviation over √seeds.
        std::printf("  drift mean %.4f (standard error %.4f)", mean, seeds > 1 ? std::sqrt(square / (seeds - 1) / seeds) : 0.0);
    }
    if (scene != "pile") std::printf("  failed by the bench's limits %d", failedBenchLimits);
    if (scene == "plates20") std::printf("  largest sink p50 %.4f p90 %.4f m", percentile(drops, 0.5), percentile(drops, 0.9));
    if (!failedSeeds.empty()) {
        std::printf("  failed seeds");
        for (int s : failedSeeds) std::printf(" %d", s);
    }
    std::printf("\n");
    return 0;
}

// Scene cost: the time of one ODE step split into collision (dSpaceCollide: broad phase, the
// narrow-phase collider, contact joint creation) and solver (dWorldQuickStep, 20 iterations),
// for gdcontact (its ODE adapter called from the near callback) and for ODE's native colliders on
// the same bodies, shapes and initial poses:
//   brick_wall — 20 × 10 bricks, rows offset by a quarter brick, on a plane (box–box, box–plane);
//   box_pile   — 1000 boxes dropped 2 cm in ten layers into a walled bin, each layer across the gaps of
//                the one below, left to settle (box–box, box–plane);
//   pyramid    — 15 rows of cubes, 120 boxes (box–box, box–plane);
//   hull_pile  — 1000 mixed convex hulls (8 to 32 vertices) dropped into a walled bin
//                (convex–convex, convex–box, convex–plane).
// The first box worlds are dBox worlds: ODE's exact dBoxBox and gdcontact see the same shapes.
// Each scene runs `settle` steps of 1/60 s unmeasured, then `steps` measured steps; it reports the
// median (and quartiles) over the measured steps of the CPU milliseconds of collision and of the
// whole step, plus contacts per step and how far the bodies moved (so that a scene that collapsed
// with one collider is not mistaken for a cheaper one). Writes CSV for scripts/bench.
#include "fixtures.hpp"
#include "ode_shapes.hpp"

#include <gdcontact/ode.hpp>
#include <gdcontact/polytope.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace gdcbench {
namespace {

constexpr double kTimeStep = 1.0 / 60.0;
constexpr int kSolverIterations = 20;
constexpr int kMaxContactsPerPair = 8;

enum class Collider { Gdcontact, OdeNative };

struct World {
    dWorldID world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(nullptr);
    dJointGroupID joints = dJointGroupCreate(0);
    Collider collider;
    long long contactsThisStep = 0;
    std::vector<dBodyID> bodies;
    std::vector<std::unique_ptr<OdeConvex>> nativeConvexes;  // data of ODE's own dConvex geoms

    explicit World(Collider c) : collider(c) {
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetQuickStepNumIterations(world, kSolverIterations);
        dWorldSetAutoDisableFlag(world, 0);  // every body is simulated every step: steady cost
    }
    ~World() {
        dJointGroupDestroy(joints);
        dSpaceDestroy(space);  // destroys the geoms; the native convex data goes after them
        nativeConvexes.clear();
        dWorldDestroy(world);
    }

    void addBody(dGeomID geom, const Pose& pose, const Vec3& boxForInertia, double massKg) {
        dBodyID body = dBodyCreate(world);
        dMass mass;
        dMassSetBoxTotal(&mass, massKg, 2 * boxForInertia.x(), 2 * boxForInertia.y(), 2 * boxForInertia.z());
        dBodySetMass(body, &mass);
        dGeomSetBody(geom, body);
        setBodyPose(body, pose);
        bodies.push_back(body);
    }
    void addBox(const Vec3& halfExtents, const Pose& pose, double massKg) {
        addBody(createOdeBox(space, halfExtents), pose, halfExtents, massKg);
    }
    void addHull(const std::vector<Vec3>& points, const Pose& pose, double massKg) {
        dGeomID geom;
        if (collider == Collider::Gdcontact) {
            std::vector<dReal> flat;
            for (const Vec3& p : points) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
            geom = gdc::ode::createConvex(space, flat.data(), static_cast<unsigned>(points.size()));
        } else {
            nativeConvexes.push_back(std::make_unique<OdeConvex>(space, gdc::Polytope::fromPoints(points)));
            geom = nativeConvexes.back()->geom();
        }
        Vec3 extent = Vec3::Zero();
        for (const Vec3& p : points) extent = extent.cwiseMax(p.cwiseAbs());
        addBody(geom, pose, extent, massKg);
    }
    void addStaticBox(const Vec3& halfExtents, const Vec3& centre) {
        setGeomPose(createOdeBox(space, halfExtents), {Mat3::Identity(), centre});
    }
};

void nearCallback(void* data, dGeomID o1, dGeomID o2) {
    World& w = *static_cast<World*>(data);
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (!b1 && !b2) return;
    std::array<dContactGeom, kMaxContactsPerPair> geoms;
    const int n = w.collider == Collider::Gdcontact
                      ? gdc::ode::collide(o1, o2, kMaxContactsPerPair, geoms.data(), sizeof(dContactGeom))
                      : dCollide(o1, o2, kMaxContactsPerPair, geoms.data(), sizeof(dContactGeom));
    for (int i = 0; i < n; ++i) {
        dContact contact{};
        contact.surface.mode = dContactApprox1;
        contact.surface.mu = 0.6;
        contact.geom = geoms[i];
        dJointAttach(dJointCreateContact(w.world, w.joints, &contact), b1, b2);
    }
    w.contactsThisStep += n;
}

// ---- scenes -------------------------------------------------------------------------------------

void brickWall(World& w) {
    dCreatePlane(w.space, 0, 0, 1, 0);
    const Vec3 brick(0.2, 0.1, 0.065);  // 0.40 × 0.20 × 0.13 m
    const double gap = 1e-4;            // start just apart, settle under gravity
    for (int row = 0; row < 10; ++row) {
        // Odd rows shifted by a quarter brick: every brick rests on two below, none balances on an edge.
        const double shift = (row % 2) ? 0.5 * brick.x() : 0.0;
        for (int i = 0; i < 20; ++i) {
            const Vec3 centre((2 * i - 19) * (brick.x() + gap) + shift, 0, brick.z() + row * (2 * brick.z() + gap));
            w.addBox(brick, {Mat3::Identity(), centre}, 2.0);
        }
    }
}

void pyramid(World& w) {
    dCreatePlane(w.space, 0, 0, 1, 0);
    const double h = 0.25, gap = 0.01;
    for (int row = 0; row < 15; ++row) {
        const int count = 15 - row;
        for (int i = 0; i < count; ++i) {
            const double x = (i - 0.5 * (count - 1)) * (2 * h + gap);
            w.addBox(Vec3::Constant(h), {Mat3::Identity(), Vec3(x, 0, h + row * (2 * h + 1e-4))}, 1.0);
        }
    }
}

/// A walled bin of inner half width `half` on the ground (static boxes, no bodies).
void addBin(World& w, double half) {
    for (int side = 0; side < 4; ++side) {
        const Vec3 centre = side < 2 ? Vec3((side ? 1 : -1) * (half + 0.1), 0, 2.5) : Vec3(0, (side == 3 ? 1 : -1) * (half + 0.1), 2.5);
        const Vec3 extents = side < 2 ? Vec3(0.1, half + 0.2, 2.5) : Vec3(half + 0.2, 0.1, 2.5);
        w.addStaticBox(extents, centre);
    }
}

void boxPile(World& w) {
    dCreatePlane(w.space, 0, 0, 1, 0);
    const Vec3 box(0.2, 0.15, 0.1);     // 0.40 × 0.30 × 0.20 m
    const double dx = 0.45, dy = 0.36;  // grid spacing: gaps of a few cm at any of the turns below
    addBin(w, 2.55);
    Random random(1000);
    int made = 0;
    for (int layer = 0; made < 1000; ++layer) {
        // Every other layer shifted by half a cell, so that its boxes land across the gaps of the
        // layer below, each on two to four boxes: a heap with most pairs resting face on face.
        const double shift = (layer % 2) ? 0.5 : 0.0;
        for (int i = 0; i < 10 && made < 1000; ++i)
            for (int j = 0; j < 10 && made < 1000; ++j, ++made) {
                // A small random turn about the vertical and tilt: no two faces exactly parallel.
                const Mat3 turn = rotation(Vec3::UnitZ(), random.uniform(-0.15, 0.15)) *
                                  rotation(random.unitVector(), random.uniform(-0.02, 0.02));
                const Vec3 centre((i - 4.5 + shift) * dx, (j - 4.5 + shift) * dy,
                                  box.z() + 0.01 + layer * (2 * box.z() + 0.02));
                w.addBox(box, {turn, centre}, 1.0);
            }
    }
}

/// Six kinds of hull, 8 to 32 vertices, about 0.15 m across.
std::vector<std::vector<Vec3>> hullKinds() {
    std::vector<std::vector<Vec3>> kinds;
    kinds.push_back(boxVertices({0.15, 0.1, 0.075}));
    kinds.push_back(fibonacciSphere(16, 0.14));
    std::vector<Vec3> ellipsoid = fibonacciSphere(32, 1.0);
    for (Vec3& p : ellipsoid) p = p.cwiseProduct(Vec3(0.18, 0.12, 0.09));
    kinds.push_back(ellipsoid);
    std::vector<Vec3> prism;
    for (int i = 0; i < 6; ++i)
        for (double z : {-0.08, 0.08}) prism.emplace_back(0.12 * std::cos(i * M_PI / 3), 0.12 * std::sin(i * M_PI / 3), z);
    kinds.push_back(prism);
    kinds.push_back({{0.15, 0, 0}, {-0.15, 0, 0}, {0, 0.15, 0}, {0, -0.15, 0}, {0, 0, 0.15}, {0, 0, -0.15}});
    Random random(7);
    std::vector<Vec3> rock;
    for (int i = 0; i < 24; ++i) rock.push_back(random.unitVector() * random.uniform(0.1, 0.15));
    kinds.push_back(rock);
    return kinds;
}

void hullPile(World& w) {
    dCreatePlane(w.space, 0, 0, 1, 0);
    addBin(w, 2.2);
    const auto kinds = hullKinds();
    Random random(2010);
    int made = 0;
    for (int layer = 0; made < 1000; ++layer)
        for (int i = 0; i < 10 && made < 1000; ++i)
            for (int j = 0; j < 10 && made < 1000; ++j, ++made) {
                const Vec3 centre(-1.8 + 0.4 * i, -1.8 + 0.4 * j, 0.25 + 0.4 * layer);
                w.addHull(kinds[made % kinds.size()], {random.rotation(), centre}, 1.0);
            }
}

struct Scene {
    std::string name;
    std::function<void(World&)> build;
};

struct Result {
    std::string scene, collider;
    int bodies = 0, settleSteps = 0, steps = 0;
    // Medians and quartiles over the measured steps, CPU ms.
    std::array<double, 3> stepMs{}, collisionMs{};  // 25th percentile, median, 75th percentile
    double solverMs = 0, broadPhaseMs = 0;          // medians
    double contactsPerStep = 0;    // mean over the measured steps
    double maxDisplacement = 0;    // metres, largest distance of a body from its start
    double settledMotion = 0;      // metres, largest distance a body moved during the measured steps
    int movingBodies = 0;          // bodies that moved more than kMovingMetres during the measured steps
};

/// The 25th percentile, median and 75th percentile of `values`.
std::array<double, 3> quartiles(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    auto at = [&](double q) {
        const double x = q * (values.size() - 1);
        const std::size_t i = static_cast<std::size_t>(x);
        return i + 1 < values.size() ? values[i] + (x - i) * (values[i + 1] - values[i]) : values[i];
    };
    return {at(0.25), at(0.5), at(0.75)};
}

std::vector<Vec3> positions(const World& w) {
    std::vector<Vec3> out;
    for (dBodyID b : w.bodies) {
        const dReal* p = dBodyGetPosition(b);
        out.emplace_back(p[0], p[1], p[2]);
    }
    return out;
}

/// A body that moves farther than this during the measured steps counts as still moving.
constexpr double kMovingMetres = 0.01;

int countMoving(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
    int moving = 0;
    for (std::size_t i = 0; i < from.size(); ++i) moving += (to[i] - from[i]).norm() > kMovingMetres;
    return moving;
}

double largestMove(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
    double largest = 0;
    for (std::size_t i = 0; i < from.size(); ++i) largest = std::max(largest, (to[i] - from[i]).norm());
    return largest;
}

Result run(const Scene& scene, Collider collider, int settleSteps, int steps) {
    World w(collider);
    scene.build(w);
    const std::vector<Vec3> start = positions(w);
    std::vector<Vec3> settled;
    std::vector<double> collision, solver, total, broadPhase;
    long long contacts = 0;
    for (int step = 0; step < settleSteps + steps; ++step) {
        if (step == settleSteps) settled = positions(w);
        w.contactsThisStep = 0;
        const double t0 = threadCpuSeconds();
        dSpaceCollide(w.space, &w, nearCallback);
        const double t1 = threadCpuSeconds();
        // The broad phase alone (a near callback that does nothing), timed apart and not part of the
        // step; run after the real pass so that it finds the bounding boxes already up to date.
        dSpaceCollide(w.space, nullptr, [](void*, dGeomID, dGeomID) {});
        const double t1b = threadCpuSeconds();
        dWorldQuickStep(w.world, kTimeStep);
        dJointGroupEmpty(w.joints);
        const double t3 = threadCpuSeconds();
        if (step < settleSteps) continue;
        broadPhase.push_back(1000 * (t1b - t1));
        collision.push_back(1000 * (t1 - t0));
        solver.push_back(1000 * (t3 - t1b));
        total.push_back(1000 * ((t3 - t0) - (t1b - t1)));
        contacts += w.contactsThisStep;
    }
    Result r;
    r.scene = scene.name;
    r.collider = collider == Collider::Gdcontact ? "gdcontact" : "ode";
    r.bodies = static_cast<int>(w.bodies.size());
    r.settleSteps = settleSteps;
    r.steps = steps;
    r.stepMs = quartiles(total);
    r.collisionMs = quartiles(collision);
    r.solverMs = quartiles(solver)[1];
    r.broadPhaseMs = quartiles(broadPhase)[1];
    r.contactsPerStep = static_cast<double>(contacts) / steps;
    const std::vector<Vec3> end = positions(w);
    r.maxDisplacement = largestMove(start, end);
    r.settledMotion = largestMove(settled.empty() ? start : settled, end);
    r.movingBodies = countMoving(settled.empty() ? start : settled, end);
    return r;
}

}  // namespace
}  // namespace gdcbench

int main(int argc, char** argv) {
    using namespace gdcbench;
    int settle = 180, steps = 120;
    std::string out;
    std::vector<std::string> only;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--steps" && i + 1 < argc) {
            steps = std::max(1, std::stoi(argv[++i]));
        } else if (arg == "--settle" && i + 1 < argc) {
            settle = std::max(0, std::stoi(argv[++i]));
        } else if (arg == "--out" && i + 1 < argc) {
            out = argv[++i];
        } else if (!arg.empty() && arg[0] != '-') {
            only.push_back(arg);
        } else {
            std::cerr << "usage: bench_scenes [--settle N] [--steps N] [--out FILE.csv] [SCENE...]\n";
            return 2;
        }
    }
    OdeSession ode;
    const std::vector<Scene> scenes{
        {"brick_wall", brickWall}, {"box_pile", boxPile}, {"pyramid", pyramid}, {"hull_pile", hullPile}};
    std::vector<Result> results;
    for (const Scene& scene : scenes) {
        if (!only.empty() && std::find(only.begin(), only.end(), scene.name) == only.end()) continue;
        for (Collider collider : {Collider::Gdcontact, Collider::OdeNative}) {
            results.push_back(run(scene, collider, settle, steps));
            const Result& r = results.back();
            std::cerr << r.scene << " " << r.collider << ": " << r.stepMs[1] << " ms/step, collision "
                      << r.collisionMs[1] << " ms (medians); while measured, " << r.movingBodies
                      << " bodies moved more than 1 cm, the farthest " << r.settledMotion << " m\n";
        }
    }
    std::ofstream file;
    if (!out.empty()) file.open(out);
    std::ostream& csv = out.empty() ? std::cout : file;
    csv << "scene,collider,bodies,settle_steps,steps,step_ms,step_ms_p25,step_ms_p75,collision_ms,collision_ms_p25,"
           "collision_ms_p75,solver_ms,broad_phase_ms,collision_fraction,contacts_per_step,max_displacement_m,"
           "settled_motion_m,moving_bodies\n";
    for (const Result& r : results)
        csv << r.scene << ',' << r.collider << ',' << r.bodies << ',' << r.settleSteps << ',' << r.steps << ','
            << r.stepMs[1] << ',' << r.stepMs[0] << ',' << r.stepMs[2] << ',' << r.collisionMs[1] << ','
            << r.collisionMs[0] << ',' << r.collisionMs[2] << ',' << r.solverMs << ',' << r.broadPhaseMs << ','
            << r.collisionMs[1] / r.stepMs[1] << ',' << r.contactsPerStep << ',' << r.maxDisplacement << ','
            << r.settledMotion << ',' << r.movingBodies << '\n';
    return 0;
}

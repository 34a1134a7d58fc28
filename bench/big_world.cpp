// Big world: gdc::ode::spaceCollide against the classic dSpaceCollide + near callback loop on a
// 1000-box pile (the box_pile scene of bench/scenes.cpp: ten layers of 0.40 × 0.30 × 0.20 m boxes
// dropped into a walled bin), on 1 and 2 threads.
//
// Each measured step times, on the same world state and interleaved in one run:
//   broad_phase   — dSpaceCollide with a near callback that does nothing (ODE's hash space alone);
//   loop_ode      — dSpaceCollide + near callback + dCollide, ODE's native dBoxBox / box–plane;
//   loop_gdc      — dSpaceCollide + near callback + gdc::ode::collide (the drop-in, serial);
//   space_1t      — gdc::ode::spaceCollide, setThreadCount(1);
//   space_2t      — gdc::ode::spaceCollide, setThreadCount(2);
// each handing every contact to the same cheap consumer (copied into an array), then steps the
// world with the contacts of space_2t (which equal loop_gdc's, bit for bit) under dWorldQuickStep.
// Wall-clock time (threads are the point here), median and quartiles over the measured steps.
// Usage: bench_big_world [settle steps = 120] [measured steps = 200] [csv file]
#include "fixtures.hpp"
#include "ode_shapes.hpp"

#include <gdcontact/ode.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

using namespace gdcbench;

namespace {

constexpr double kTimeStep = 1.0 / 60.0;
constexpr int kMaxContactsPerPair = 8;

struct World {
    dWorldID world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(nullptr);
    dJointGroupID joints = dJointGroupCreate(0);
    std::vector<dContactGeom> contacts;  // the consumer: every contact of a step, with its pair
    std::vector<std::array<dGeomID, 2>> pairs;

    World() {
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetQuickStepNumIterations(world, 20);
        dWorldSetAutoDisableFlag(world, 0);
        contacts.reserve(40000);
        pairs.reserve(40000);
    }
    ~World() {
        dJointGroupDestroy(joints);
        dSpaceDestroy(space);
        dWorldDestroy(world);
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
};

// The box_pile scene of bench/scenes.cpp.
void buildPile(World& w) {
    dCreatePlane(w.space, 0, 0, 1, 0);
    const double half = 2.55;
    for (int side = 0; side < 4; ++side) {
        const Vec3 centre = side < 2 ? Vec3((side ? 1 : -1) * (half + 0.1), 0, 2.5)
                                     : Vec3(0, (side == 3 ? 1 : -1) * (half + 0.1), 2.5);
        const Vec3 extents = side < 2 ? Vec3(0.1, half + 0.2, 2.5) : Vec3(half + 0.2, 0.1, 2.5);
        setGeomPose(createOdeBox(w.space, extents), {Mat3::Identity(), centre});
    }
    const Vec3 box(0.2, 0.15, 0.1);
    const double dx = 0.45, dy = 0.36;
    Random random(1000);
    int made = 0;
    for (int layer = 0; made < 1000; ++layer) {
        const double shift = (layer % 2) ? 0.5 : 0.0;
        for (int i = 0; i < 10 && made < 1000; ++i)
            for (int j = 0; j < 10 && made < 1000; ++j, ++made) {
                const Mat3 turn = rotation(Vec3::UnitZ(), random.uniform(-0.15, 0.15)) *
                                  rotation(random.unitVector(), random.uniform(-0.02, 0.02));
                const Vec3 centre((i - 4.5 + shift) * dx, (j - 4.5 + shift) * dy,
                                  box.z() + 0.01 + layer * (2 * box.z() + 0.02));
                dBodyID body = dBodyCreate(w.world);
                dMass mass;
                dMassSetBoxTotal(&mass, 1.0, 2 * box.x(), 2 * box.y(), 2 * box.z());
                dBodySetMass(body, &mass);
                dGeomSetBody(createOdeBox(w.space, box), body);
                setBodyPose(body, {turn, centre});
            }
    }
}

// Near callbacks of the classic loop. Static–static pairs (the bin's walls) are skipped by ODE's
// broad phase already: they share the null body.
void emptyCallback(void*, dGeomID, dGeomID) {}

template <bool Gdcontact>
void loopCallback(void* data, dGeomID o1, dGeomID o2) {
    World& w = *static_cast<World*>(data);
    std::array<dContactGeom, kMaxContactsPerPair> geoms;
    const int n = Gdcontact ? gdc::ode::collide(o1, o2, kMaxContactsPerPair, geoms.data(), sizeof(dContactGeom))
                            : dCollide(o1, o2, kMaxContactsPerPair, geoms.data(), sizeof(dContactGeom));
    if (n > 0) w.consume(o1, o2, geoms.data(), n);
}

void handler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
    static_cast<World*>(data)->consume(o1, o2, contacts, count);
}

void createJoints(World& w) {
    for (std::size_t i = 0; i < w.contacts.size(); ++i) {
        dContact contact{};
        contact.surface.mode = dContactApprox1;
        contact.surface.mu = 0.6;
        contact.geom = w.contacts[i];
        dJointAttach(dJointCreateContact(w.world, w.joints, &contact), dGeomGetBody(w.pairs[i][0]),
                     dGeomGetBody(w.pairs[i][1]));
    }
}

template <class F>
double timeMs(F&& f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

struct Series {
    const char* name;
    std::vector<double> ms;
    long long contacts = 0;
};

double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
    const int settle = argc > 1 ? std::atoi(argv[1]) : 120;
    const int steps = argc > 2 ? std::atoi(argv[2]) : 200;
    const char* csv = argc > 3 ? argv[3] : nullptr;
    dInitODE2(0);  // no install(): dCollide is ODE's native collider
    dRandSetSeed(1);
    {
        World w;
        buildPile(w);
        gdc::ode::setThreadCount(2);
        for (int i = 0; i < settle; ++i) {
            w.clear();
            gdc::ode::spaceCollide(w.space, kMaxContactsPerPair, &w, &handler);
            createJoints(w);
            dWorldQuickStep(w.world, kTimeStep);
            dJointGroupEmpty(w.joints);
        }
        std::vector<Series> series = {{"broad_phase", {}}, {"loop_ode", {}}, {"loop_gdc", {}},
                                      {"space_1t", {}},    {"space_2t", {}}, {"quickstep", {}}};
        for (int step = 0; step < steps; ++step) {
            auto run = [&](Series& s, auto&& collide) {
                w.clear();
                s.ms.push_back(timeMs(collide));
                s.contacts += static_cast<long long>(w.contacts.size());
            };
            run(series[0], [&] { dSpaceCollide(w.space, &w, &emptyCallback); });
            run(series[1], [&] { dSpaceCollide(w.space, &w, &loopCallback<false>); });
            run(series[2], [&] { dSpaceCollide(w.space, &w, &loopCallback<true>); });
            run(series[3], [&] {
                gdc::ode::setThreadCount(1);
                gdc::ode::spaceCollide(w.space, kMaxContactsPerPair, &w, &handler);
            });
            run(series[4], [&] {
                gdc::ode::setThreadCount(2);
                gdc::ode::spaceCollide(w.space, kMaxContactsPerPair, &w, &handler);
            });
            createJoints(w);  // space_2t's contacts
            series[5].ms.push_back(timeMs([&] { dWorldQuickStep(w.world, kTimeStep); }));
            dJointGroupEmpty(w.joints);
        }
        std::printf("1000-box pile, %d settle steps, %d measured steps, wall-clock ms per step\n", settle, steps);
        std::printf("%-12s %8s %8s %8s %14s\n", "contender", "q25", "median", "q75", "contacts/step");
        for (const Series& s : series)
            std::printf("%-12s %8.3f %8.3f %8.3f %14.1f\n", s.name, quantile(s.ms, 0.25), quantile(s.ms, 0.5),
                        quantile(s.ms, 0.75), static_cast<double>(s.contacts) / steps);
        const double broad = quantile(series[0].ms, 0.5);
        const double one = quantile(series[3].ms, 0.5), two = quantile(series[4].ms, 0.5);
        std::printf("spaceCollide 1 → 2 threads: whole call %.2fx; narrow phase (call − broad phase) %.2fx\n",
                    one / two, (one - broad) / (two - broad));
        std::printf("spaceCollide 1 thread vs the near-callback loop with gdc::ode::collide: %.2fx\n",
                    quantile(series[2].ms, 0.5) / one);
        if (csv) {
            std::ofstream out(csv);
            out << "step";
            for (const Series& s : series) out << ',' << s.name;
            out << '\n';
            for (int step = 0; step < steps; ++step) {
                out << step;
                for (const Series& s : series) out << ',' << s.ms[static_cast<std::size_t>(step)];
                out << '\n';
            }
        }
    }
    dCloseODE();
    return 0;
}

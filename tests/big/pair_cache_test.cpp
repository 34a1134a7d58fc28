// The ODE adapter's pair cache (gdc::ode::setPairCacheEnabled and friends): a simulation with it is
// bit-identical to one without (near callback and spaceCollide on 1 and 2 threads), it answers
// sleeping and static pairs without a query, its entries die with their geoms and age out when
// their pairs part, it never holds more than its capacity, and with Settings::manifoldReuseDistance
// it carries resting pairs' contacts.
#include <gdcontact/ode.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

namespace {

struct Session {
    explicit Session(const gdc::Settings& settings = {}) {
        dInitODE2(0);
        gdc::ode::install(settings);
        gdc::ode::clearPairCache();
        gdc::ode::setPairCacheEnabled(true);
    }
    ~Session() {
        gdc::ode::setThreadCount(0);
        gdc::ode::setPairCacheEnabled(true);
        gdc::ode::setPairCacheCapacity(65536);
        dCloseODE();
    }
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
};

std::uint64_t bitsOf(double value) {
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

// Nine stacks of three, dBoxes and createConvex hulls of irregular boxes alternating, on a plane,
// ODE's auto-disable on (as in ODE's demo_boxstack), so that the stacks settle and then sleep.
struct World {
    dWorldID world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(0);
    dJointGroupID joints = dJointGroupCreate(0);
    std::vector<dBodyID> bodies;
    std::vector<dGeomID> geoms;
    std::vector<std::uint64_t> contactBits;  // every contact of the run, as raw bits

    World(unsigned seed, int columns, int layers, bool autoDisable) {
        dRandSetSeed(1);
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetQuickStepNumIterations(world, 20);
        dWorldSetAutoDisableFlag(world, autoDisable ? 1 : 0);
        dWorldSetAutoDisableSteps(world, 10);
        dCreatePlane(space, 0, 0, 1, 0);
        std::mt19937 random(seed);
        std::uniform_real_distribution<double> unit(-1.0, 1.0);
        for (int layer = 0; layer < layers; ++layer)
            for (int column = 0; column < columns; ++column) {
                dGeomID geom;
                if ((layer + column) % 2 == 0) {
                    geom = dCreateBox(space, 0.8, 0.8, 0.5);
                } else {  // a hull of a slightly irregular box: a convex of 8 vertices, not a dBox
                    std::vector<dReal> points;
                    for (int i = 0; i < 8; ++i)
                        points.insert(points.end(), {(i & 1 ? 0.4 : -0.4) + 0.01 * unit(random),
                                                     (i & 2 ? 0.4 : -0.4) + 0.01 * unit(random), i & 4 ? 0.25 : -0.25});
                    geom = gdc::ode::createConvex(space, points.data(), 8);
                }
                dBodyID body = dBodyCreate(world);
                dMass mass;
                dMassSetBox(&mass, 1.0, 0.8, 0.8, 0.5);
                dBodySetMass(body, &mass);
                dBodySetPosition(body, 1.1 * (column % 3) + 0.02 * unit(random), 1.1 * (column / 3) + 0.02 * unit(random),
                                 0.25 + 0.5 * layer);
                dGeomSetBody(geom, body);
                bodies.push_back(body);
                geoms.push_back(geom);
            }
    }
    ~World() {
        dJointGroupDestroy(joints);
        dSpaceDestroy(space);
        dWorldDestroy(world);
    }
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    void add(dGeomID o1, dGeomID o2, const dContactGeom* contacts, int count) {
        for (int i = 0; i < count; ++i) {
            const dContactGeom& c = contacts[i];
            for (int k = 0; k < 3; ++k) contactBits.push_back(bitsOf(c.pos[k])), contactBits.push_back(bitsOf(c.normal[k]));
            contactBits.push_back(bitsOf(c.depth));
            dContact contact{};
            contact.surface.mode = dContactApprox1;
            contact.surface.mu = 0.6;
            contact.geom = c;
            dJointAttach(dJointCreateContact(world, joints, &contact), dGeomGetBody(o1), dGeomGetBody(o2));
        }
    }
    static void nearCallback(void* data, dGeomID o1, dGeomID o2) {
        dContactGeom contacts[8];
        const int count = dCollide(o1, o2, 8, contacts, sizeof(dContactGeom));
        if (count > 0) static_cast<World*>(data)->add(o1, o2, contacts, count);
    }
    static void handler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
        static_cast<World*>(data)->add(o1, o2, contacts, count);
    }
    // threads 0: dSpaceCollide + near callback; else spaceCollide on that many threads.
    void step(int threads) {
        if (threads == 0) {
            dSpaceCollide(space, this, &nearCallback);
        } else {
            gdc::ode::setThreadCount(threads);
            gdc::ode::spaceCollide(space, 8, this, &handler);
        }
        dWorldQuickStep(world, 0.01);
        dJointGroupEmpty(joints);
    }
    std::vector<std::uint64_t> stateBits() const {
        std::vector<std::uint64_t> bits;
        for (dBodyID body : bodies) {
            const dReal* p = dBodyGetPosition(body);
            const dReal* q = dBodyGetQuaternion(body);
            for (int i = 0; i < 3; ++i) bits.push_back(bitsOf(p[i]));
            for (int i = 0; i < 4; ++i) bits.push_back(bitsOf(q[i]));
        }
        return bits;
    }
    int sleeping() const {
        int count = 0;
        for (dBodyID body : bodies) count += !dBodyIsEnabled(body);
        return count;
    }
};

struct Run {
    std::vector<std::uint64_t> state, contacts;
    gdc::ode::PairCacheStats stats;
    int sleeping;
};

// `countFrom`: the cache's statistics count from this step on (the cache is emptied there).
Run simulate(bool cache, int threads, bool autoDisable, int steps = 500, int countFrom = 0) {
    gdc::ode::clearPairCache();
    gdc::ode::setPairCacheEnabled(cache);
    World world(3, 9, 3, autoDisable);
    for (int i = 0; i < steps; ++i) {
        if (i == countFrom && i > 0) gdc::ode::clearPairCache();
        world.step(threads);
    }
    return Run{world.stateBits(), world.contactBits, gdc::ode::pairCacheStats(), world.sleeping()};
}

}  // namespace

TEST_CASE("pair cache: a settling, sleeping pile is bit-identical with and without it, on 0, 1 and 2 threads",
          "[big][threads]") {
    Session session;
    const Run reference = simulate(false, 0, true);
    INFO(reference.sleeping << " of 27 bodies asleep at the end");
    REQUIRE(reference.sleeping > 9);  // the pile did come to rest, so the cache has something to answer
    REQUIRE(reference.stats.hits == 0);
    for (int threads : {0, 1, 2}) {
        INFO((threads == 0 ? "near callback" : "spaceCollide") << ", " << threads << " threads");
        const Run cached = simulate(true, threads, true);
        REQUIRE(cached.contacts.size() == reference.contacts.size());
        REQUIRE(cached.contacts == reference.contacts);
        REQUIRE(cached.state == reference.state);
        // Sleeping and static pairs were answered from the cache: a good part of the run's queries.
        std::printf("pair cache, nine sleeping stacks, %s on %d threads: %llu answers repeated, %llu queried, "
                    "%zu entries (%zu KB); contacts and states equal to the run without the cache\n",
                    threads == 0 ? "near callback" : "spaceCollide", threads,
                    static_cast<unsigned long long>(cached.stats.hits), static_cast<unsigned long long>(cached.stats.misses),
                    cached.stats.entries, cached.stats.bytes / 1024);
        CHECK(cached.stats.hits > cached.stats.misses / 4);
        CHECK(cached.stats.carried == 0);
        CHECK(cached.stats.entries > 0);
    }
}

TEST_CASE("pair cache: entries die with their geoms, age out when pairs part, and stay within the capacity", "[big]") {
    Session session;
    dSpaceID space = dSimpleSpaceCreate(0);
    std::vector<dGeomID> boxes;
    for (int i = 0; i < 10; ++i) {  // a row of overlapping boxes: 9 touching neighbours
        dGeomID box = dCreateBox(space, 1, 1, 1);
        dGeomSetPosition(box, 0.95 * i, 0, 0);
        boxes.push_back(box);
    }
    auto collideAll = [&] {
        dSpaceCollide(space, nullptr, [](void*, dGeomID o1, dGeomID o2) {
            dContactGeom contacts[8];
            dCollide(o1, o2, 8, contacts, sizeof(dContactGeom));
        });
    };
    collideAll();
    REQUIRE(gdc::ode::pairCacheStats().entries == 9);
    collideAll();
    REQUIRE(gdc::ode::pairCacheStats().entries == 9);
    REQUIRE(gdc::ode::pairCacheStats().hits == 9);  // nothing moved

    SECTION("destroyed geoms take their entries along") {
        dGeomDestroy(boxes[0]);
        dGeomDestroy(boxes[5]);
        collideAll();  // the next use of the cache removes them (6 pairs remain)
        CHECK(gdc::ode::pairCacheStats().entries == 6);
    }
    SECTION("the capacity bounds the entries; the least recently used go first") {
        gdc::ode::setPairCacheCapacity(4);
        CHECK(gdc::ode::pairCacheStats().entries == 4);
        collideAll();
        CHECK(gdc::ode::pairCacheStats().entries <= 4);
    }
    SECTION("pairs no longer asked about age out") {
        // Move the row apart and make ever new pairs elsewhere: the old ones stop being asked about.
        for (std::size_t i = 0; i < boxes.size(); ++i) dGeomSetPosition(boxes[i], 5.0 * i, 0, 0);
        dSpaceID other = dSimpleSpaceCreate(0);
        for (int round = 0; round < 40; ++round) {
            dGeomID a = dCreateBox(other, 1, 1, 1), b = dCreateBox(other, 1, 1, 1);
            for (int k = 0; k < 60; ++k) {  // 60 distinct pairs a round (new geoms each time)
                dGeomSetPosition(a, 0, 0, 0);
                dGeomSetPosition(b, 0.5, 0.01 * k, 0);
                dContactGeom contacts[8];
                dCollide(a, b, 8, contacts, sizeof(dContactGeom));
                dGeomDestroy(b);
                b = dCreateBox(other, 1, 1, 1);
            }
            dGeomDestroy(a);
            dGeomDestroy(b);
        }
        collideAll();
        // Destroyed geoms' entries were removed as they went; the row's parted pairs aged out.
        CHECK(gdc::ode::pairCacheStats().entries <= 2);
        dSpaceDestroy(other);
    }
    dSpaceDestroy(space);
}

TEST_CASE("pair cache: switched off, every call is a full query, and manifoldReuseDistance carries resting pairs", "[big]") {
    SECTION("off") {
        Session session;
        gdc::ode::setPairCacheEnabled(false);
        const Run run = simulate(false, 0, true, 100);
        CHECK(run.stats.entries == 0);
        CHECK(run.stats.hits + run.stats.misses + run.stats.carried == 0);
    }
    SECTION("manifold reuse on a pile that never sleeps") {
        gdc::Settings settings;
        settings.manifoldReuseDistance = 1e-3;
        Session session(settings);
        // Counted once the pile has landed (200 steps): then most queries are carried.
        const Run run = simulate(true, 2, false, 300, 200);
        INFO("carried " << run.stats.carried << ", hits " << run.stats.hits << ", misses " << run.stats.misses);
        CHECK(run.stats.carried > run.stats.misses);
        // Still a pile on the ground: every body above the plane, none sunk or flown off.
        for (std::size_t i = 2; i < run.state.size(); i += 7) {
            double z;
            std::memcpy(&z, &run.state[i], sizeof z);
            CHECK(z > 0.1);
            CHECK(z < 2.0);
        }
    }
}

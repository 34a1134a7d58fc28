// gdc::ode::spaceCollide: the same contacts, in the same order, as dSpaceCollide with a near
// callback calling dCollide (after install()), for every thread count; a whole simulation that is
// bit-identical for 1, 2 and 4 threads; bad input rejected where it enters; the phase profile the
// big-world benchmark reads.
#include <gdcontact/ode.hpp>

#include "ode/space_collide_profile.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

// dInitODE2 … dCloseODE around one test, gdcontact installed (so that dCollide routes its pairs to
// gdcontact, which is what spaceCollide's contract compares against); one thread per test at the end.
struct Session {
    Session() {
        dInitODE2(0);
        gdc::ode::install();
    }
    ~Session() {
        gdc::ode::setThreadCount(0);
        dCloseODE();
    }
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
};

// A pile: boxes, createConvex hulls (random points) and spheres falling onto a plane in a 4×4
// grid of columns, close enough that neighbours touch; every third column's geoms sit in a nested
// simple space, so the broad phase also goes through dSpaceCollide2. QuickStep, 20 iterations.
struct Pile {
    dWorldID world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(0);
    dSpaceID nested = dSimpleSpaceCreate(space);
    dJointGroupID joints = dJointGroupCreate(0);
    std::vector<dBodyID> bodies;
    int boxes = 0, hulls = 0, spheres = 0;

    explicit Pile(unsigned seed, int layers = 4) {
        dRandSetSeed(1);  // QuickStep's constraint shuffling
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetERP(world, 0.2);
        dWorldSetCFM(world, 1e-5);
        dWorldSetQuickStepNumIterations(world, 20);
        dCreatePlane(space, 0, 0, 1, 0);
        std::mt19937 random(seed);
        std::uniform_real_distribution<double> jitter(-0.05, 0.05), unit(-1.0, 1.0), angle(-0.4, 0.4);
        for (int layer = 0; layer < layers; ++layer) {
            for (int column = 0; column < 16; ++column) {
                dSpaceID target = column % 3 == 2 ? nested : space;
                dGeomID geom;
                const int kind = (layer + column) % 5;  // two boxes, two hulls, one sphere in five
                if (kind == 0 || kind == 3) {
                    geom = dCreateBox(target, 0.9 + jitter(random), 0.8 + jitter(random), 0.7 + jitter(random));
                    ++boxes;
                } else if (kind == 1 || kind == 4) {
                    std::vector<dReal> points;
                    for (int i = 0; i < 14; ++i) {
                        double x = unit(random), y = unit(random), z = unit(random);
                        const double length = std::sqrt(x * x + y * y + z * z) + 1e-3;
                        points.push_back(0.5 * x / length);
                        points.push_back(0.5 * y / length);
                        points.push_back(0.45 * z / length);
                    }
                    geom = gdc::ode::createConvex(target, points.data(), 14);
                    ++hulls;
                } else {
                    geom = dCreateSphere(target, 0.4);
                    ++spheres;
                }
                dBodyID body = dBodyCreate(world);
                dMass mass;
                dMassSetBox(&mass, 1.0, 0.8, 0.8, 0.8);
                dBodySetMass(body, &mass);
                dBodySetPosition(body, 0.85 * (column % 4) + jitter(random), 0.85 * (column / 4) + jitter(random),
                                 0.5 + 0.75 * layer);
                dMatrix3 rotation;
                dRFromEulerAngles(rotation, angle(random), angle(random), angle(random));
                dBodySetRotation(body, rotation);
                dGeomSetBody(geom, body);
                bodies.push_back(body);
            }
        }
    }
    ~Pile() {
        dJointGroupDestroy(joints);
        dSpaceDestroy(space);  // with the nested space and every geom
        dWorldDestroy(world);
    }
    Pile(const Pile&) = delete;
    Pile& operator=(const Pile&) = delete;

    void addContacts(dGeomID o1, dGeomID o2, const dContactGeom* contacts, int count) {
        for (int i = 0; i < count; ++i) {
            dContact contact{};
            contact.surface.mode = dContactApprox1;
            contact.surface.mu = 0.8;
            contact.geom = contacts[i];
            dJointID joint = dJointCreateContact(world, joints, &contact);
            dJointAttach(joint, dGeomGetBody(o1), dGeomGetBody(o2));
        }
    }

    static void handler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
        static_cast<Pile*>(data)->addContacts(o1, o2, contacts, count);
    }

    static void nearCallback(void* data, dGeomID o1, dGeomID o2) {
        if (dGeomIsSpace(o1) || dGeomIsSpace(o2)) {
            dSpaceCollide2(o1, o2, data, &nearCallback);
            if (dGeomIsSpace(o1)) dSpaceCollide(reinterpret_cast<dSpaceID>(o1), data, &nearCallback);
            if (dGeomIsSpace(o2)) dSpaceCollide(reinterpret_cast<dSpaceID>(o2), data, &nearCallback);
            return;
        }
        dContactGeom contacts[kMaxContacts];
        const int count = dCollide(o1, o2, kMaxContacts, contacts, sizeof(dContactGeom));
        if (count > 0) static_cast<Pile*>(data)->addContacts(o1, o2, contacts, count);
    }

    static constexpr int kMaxContacts = 8;
    static constexpr double kTimeStep = 0.01;

    // One step; spaceCollide when `useSpaceCollide`, else the classic near-callback loop.
    void step(bool useSpaceCollide) {
        if (useSpaceCollide)
            gdc::ode::spaceCollide(space, kMaxContacts, this, &handler);
        else
            dSpaceCollide(space, this, &nearCallback);
        dWorldQuickStep(world, kTimeStep);
        dJointGroupEmpty(joints);
    }

    // Every body's position and quaternion, as raw bits.
    std::vector<std::uint64_t> stateBits() const {
        std::vector<std::uint64_t> bits;
        for (dBodyID body : bodies) {
            const dReal* p = dBodyGetPosition(body);
            const dReal* q = dBodyGetQuaternion(body);
            for (int i = 0; i < 3; ++i) bits.push_back(toBits(p[i]));
            for (int i = 0; i < 4; ++i) bits.push_back(toBits(q[i]));
        }
        return bits;
    }

    static std::uint64_t toBits(double value) {
        std::uint64_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        return bits;
    }
};

// One touching pair as reported, the contacts' meaningful fields as raw bits (ODE's colliders
// leave the padding element of pos and normal unset).
struct Reported {
    dGeomID o1, o2;
    std::vector<std::uint64_t> bits;
    bool operator==(const Reported& other) const { return o1 == other.o1 && o2 == other.o2 && bits == other.bits; }
};

void record(std::vector<Reported>& out, dGeomID o1, dGeomID o2, const dContactGeom* contacts, int count) {
    Reported reported{o1, o2, {}};
    for (int i = 0; i < count; ++i) {
        const dContactGeom& c = contacts[i];
        for (int k = 0; k < 3; ++k) reported.bits.push_back(Pile::toBits(c.pos[k]));
        for (int k = 0; k < 3; ++k) reported.bits.push_back(Pile::toBits(c.normal[k]));
        reported.bits.push_back(Pile::toBits(c.depth));
        reported.bits.push_back(reinterpret_cast<std::uintptr_t>(c.g1));
        reported.bits.push_back(reinterpret_cast<std::uintptr_t>(c.g2));
        reported.bits.push_back(static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.side1)));
        reported.bits.push_back(static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.side2)));
    }
    out.push_back(std::move(reported));
}

void recordHandler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
    REQUIRE(count > 0);
    record(*static_cast<std::vector<Reported>*>(data), o1, o2, contacts, count);
}

void recordNearCallback(void* data, dGeomID o1, dGeomID o2) {
    if (dGeomIsSpace(o1) || dGeomIsSpace(o2)) {
        dSpaceCollide2(o1, o2, data, &recordNearCallback);
        if (dGeomIsSpace(o1)) dSpaceCollide(reinterpret_cast<dSpaceID>(o1), data, &recordNearCallback);
        if (dGeomIsSpace(o2)) dSpaceCollide(reinterpret_cast<dSpaceID>(o2), data, &recordNearCallback);
        return;
    }
    dContactGeom contacts[Pile::kMaxContacts];
    const int count = dCollide(o1, o2, Pile::kMaxContacts, contacts, sizeof(dContactGeom));
    if (count > 0) record(*static_cast<std::vector<Reported>*>(data), o1, o2, contacts, count);
}


}  // namespace

TEST_CASE("spaceCollide gives dCollide's contacts in the broad phase's order, bit-identical for 1, 2 and 4 threads",
          "[big][threads]") {
    Session session;
    Pile pile(7);
    for (int i = 0; i < 60; ++i) pile.step(true);  // a settling pile: resting, sliding and new pairs

    std::vector<Reported> reference;
    dSpaceCollide(pile.space, &reference, &recordNearCallback);
    // The scene exercises every route: gdcontact's pairs, ODE's (spheres), the nested space.
    int gdcontactPairs = 0, odePairs = 0, nestedPairs = 0;
    for (const Reported& reported : reference) {
        const bool ours = gdc::ode::handles(dGeomGetClass(reported.o1), dGeomGetClass(reported.o2));
        (ours ? gdcontactPairs : odePairs) += 1;
        if (dGeomGetSpace(reported.o1) == pile.nested || dGeomGetSpace(reported.o2) == pile.nested) ++nestedPairs;
    }
    INFO("gdcontact pairs " << gdcontactPairs << ", ODE pairs " << odePairs << ", nested " << nestedPairs);
    REQUIRE(gdcontactPairs >= 40);
    REQUIRE(odePairs >= 10);
    REQUIRE(nestedPairs >= 10);

    for (int threads : {1, 2, 4, 1}) {
        gdc::ode::setThreadCount(threads);
        std::vector<Reported> reported;
        gdc::ode::spaceCollide(pile.space, Pile::kMaxContacts, &reported, &recordHandler);
        INFO(threads << " threads");
        REQUIRE(reported.size() == reference.size());
        for (std::size_t i = 0; i < reported.size(); ++i) {
            INFO("pair " << i);
            REQUIRE(reported[i] == reference[i]);
        }
    }
}

TEST_CASE("a whole pile simulation is bit-identical for 1, 2 and 4 threads and equals the near-callback loop's",
          "[big][threads]") {
    Session session;
    constexpr int kSteps = 120;
    auto run = [&](int threads) {  // threads 0: the classic dSpaceCollide + dCollide loop
        if (threads > 0) gdc::ode::setThreadCount(threads);
        Pile pile(11);
        for (int i = 0; i < kSteps; ++i) pile.step(threads > 0);
        return pile.stateBits();
    };
    const std::vector<std::uint64_t> reference = run(0);
    {  // the pile did move: its first body fell from where it was placed
        Pile start(11);
        REQUIRE(start.stateBits() != reference);
    }
    for (int threads : {1, 2, 4}) {
        INFO(threads << " threads");
        REQUIRE(run(threads) == reference);
    }
}

TEST_CASE("spaceCollide's thread count: 0 is one per hardware thread, and a changed count takes effect",
          "[big][threads]") {
    Session session;
    Pile pile(3, 2);
    for (int i = 0; i < 30; ++i) pile.step(true);
    std::vector<Reported> first;
    gdc::ode::setThreadCount(0);
    gdc::ode::spaceCollide(pile.space, Pile::kMaxContacts, &first, &recordHandler);
    REQUIRE(!first.empty());
    for (int threads : {3, 2, 0}) {
        gdc::ode::setThreadCount(threads);
        std::vector<Reported> again;
        gdc::ode::spaceCollide(pile.space, Pile::kMaxContacts, &again, &recordHandler);
        REQUIRE(again == first);
    }
}

TEST_CASE("spaceCollide caps gdcontact's pairs at maxContactsPerPair and at Settings::maxContacts", "[big]") {
    dInitODE2(0);
    gdc::Settings settings;
    settings.maxContacts = 3;
    gdc::ode::install(settings);
    {
        dSpaceID space = dSimpleSpaceCreate(0);
        dCreatePlane(space, 0, 0, 1, 0);
        dGeomID box = dCreateBox(space, 1, 1, 1);
        dGeomSetPosition(box, 0, 0, 0.49);  // a face on the plane: 4 corners touch
        for (int maxContacts : {1, 2, 8}) {
            std::vector<Reported> reported;
            gdc::ode::spaceCollide(space, maxContacts, &reported, &recordHandler);
            REQUIRE(reported.size() == 1);
            REQUIRE(reported[0].bits.size() == 11u * static_cast<std::size_t>(std::min(maxContacts, 3)));
        }
        dSpaceDestroy(space);
    }
    dCloseODE();
}

TEST_CASE("spaceCollide rejects bad arguments where they enter", "[big]") {
    Session session;
    dSpaceID space = dSimpleSpaceCreate(0);
    dGeomID box = dCreateBox(space, 1, 1, 1);
    std::vector<Reported> reported;
    using gdc::InvalidInput;
    REQUIRE_THROWS_AS(gdc::ode::spaceCollide(nullptr, 4, &reported, &recordHandler), InvalidInput);
    REQUIRE_THROWS_AS(gdc::ode::spaceCollide(reinterpret_cast<dSpaceID>(box), 4, &reported, &recordHandler),
                      InvalidInput);
    REQUIRE_THROWS_AS(gdc::ode::spaceCollide(space, 4, &reported, nullptr), InvalidInput);
    REQUIRE_THROWS_AS(gdc::ode::spaceCollide(space, 0, &reported, &recordHandler), InvalidInput);
    REQUIRE_THROWS_AS(gdc::ode::spaceCollide(space, 0x10000, &reported, &recordHandler), InvalidInput);
    REQUIRE_THROWS_WITH(gdc::ode::setThreadCount(-1), Catch::Contains("0..256"));
    REQUIRE_THROWS_AS(gdc::ode::setThreadCount(257), InvalidInput);
    dSpaceDestroy(space);
}

TEST_CASE("an exception from the handler reaches the caller, and the next call works", "[big][threads]") {
    Session session;
    gdc::ode::setThreadCount(2);
    Pile pile(5, 2);
    for (int i = 0; i < 30; ++i) pile.step(true);
    auto throwing = [](void*, dGeomID, dGeomID, dContactGeom*, int) { throw std::runtime_error("handler"); };
    REQUIRE_THROWS_WITH(gdc::ode::spaceCollide(pile.space, Pile::kMaxContacts, nullptr, throwing),
                        "handler");
    std::vector<Reported> reported, reference;
    gdc::ode::spaceCollide(pile.space, Pile::kMaxContacts, &reported, &recordHandler);
    dSpaceCollide(pile.space, &reference, &recordNearCallback);
    REQUIRE(!reference.empty());
    REQUIRE(reported == reference);
}

TEST_CASE("a handler may call spaceCollide on another space", "[big][threads]") {
    Session session;
    gdc::ode::setThreadCount(2);
    Pile outer(5, 2), inner(6, 2);
    for (int i = 0; i < 30; ++i) {
        outer.step(true);
        inner.step(true);
    }
    struct Context {
        dSpaceID inner;
        std::vector<Reported> outerPairs, innerPairs;
    } context{inner.space, {}, {}};
    auto handler = [](void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
        auto& c = *static_cast<Context*>(data);
        record(c.outerPairs, o1, o2, contacts, count);
        if (c.outerPairs.size() == 1)
            gdc::ode::spaceCollide(c.inner, Pile::kMaxContacts, &c.innerPairs, &recordHandler);
    };
    gdc::ode::spaceCollide(outer.space, Pile::kMaxContacts, &context, handler);
    std::vector<Reported> outerReference, innerReference;
    dSpaceCollide(outer.space, &outerReference, &recordNearCallback);
    dSpaceCollide(inner.space, &innerReference, &recordNearCallback);
    REQUIRE(!innerReference.empty());
    REQUIRE(context.outerPairs == outerReference);
    REQUIRE(context.innerPairs == innerReference);
}

TEST_CASE("thousands of pairs (several slot blocks) and a changed maxContactsPerPair give dCollide's contacts",
          "[big][threads]") {
    Session session;
    dSpaceID space = dHashSpaceCreate(0);
    dCreatePlane(space, 0, 0, 1, 0);
    std::mt19937 random(21);
    std::uniform_real_distribution<double> angle(-0.05, 0.05);
    // A 16 × 16 × 3 block of slightly turned unit cubes spaced 0.98 apart: every neighbour overlaps.
    for (int x = 0; x < 16; ++x)
        for (int y = 0; y < 16; ++y)
            for (int z = 0; z < 3; ++z) {
                dGeomID box = dCreateBox(space, 1, 1, 1);
                dGeomSetPosition(box, 0.98 * x, 0.98 * y, 0.49 + 0.98 * z);
                dMatrix3 rotation;
                dRFromEulerAngles(rotation, angle(random), angle(random), angle(random));
                dGeomSetRotation(box, rotation);
            }
    for (int maxContacts : {16, 3, 8}) {
        std::vector<Reported> reference;
        struct Context {
            std::vector<Reported>* out;
            int maxContacts;
        } context{&reference, maxContacts};
        dSpaceCollide(space, &context, [](void* data, dGeomID o1, dGeomID o2) {
            auto& c = *static_cast<Context*>(data);
            dContactGeom contacts[16];
            const int count = dCollide(o1, o2, c.maxContacts, contacts, sizeof(dContactGeom));
            if (count > 0) record(*c.out, o1, o2, contacts, count);
        });
        INFO(maxContacts << " contacts per pair, " << reference.size() << " touching pairs");
        REQUIRE(reference.size() > 3000);  // the slot store's first block holds 1024 pairs
        for (int threads : {1, 2, 4}) {
            INFO(threads << " threads");
            gdc::ode::setThreadCount(threads);
            std::vector<Reported> reported;
            gdc::ode::spaceCollide(space, maxContacts, &reported, &recordHandler);
            REQUIRE(reported.size() == reference.size());
            REQUIRE(reported == reference);
        }
    }
    dSpaceDestroy(space);
}

namespace {

struct PairCount {
    std::size_t gdcontact = 0, other = 0;
};

void countNearCallback(void* data, dGeomID o1, dGeomID o2) {
    if (dGeomIsSpace(o1) || dGeomIsSpace(o2)) {
        dSpaceCollide2(o1, o2, data, &countNearCallback);
        if (dGeomIsSpace(o1)) dSpaceCollide(reinterpret_cast<dSpaceID>(o1), data, &countNearCallback);
        if (dGeomIsSpace(o2)) dSpaceCollide(reinterpret_cast<dSpaceID>(o2), data, &countNearCallback);
        return;
    }
    PairCount& count = *static_cast<PairCount*>(data);
    const int c1 = dGeomGetClass(o1), c2 = dGeomGetClass(o2);
    const bool ours = gdc::ode::handles(c1, c2);  // install()'s pairs (sphere–convex among them)
    ++(ours ? count.gdcontact : count.other);
}

void ignoreContacts(void*, dGeomID, dGeomID, dContactGeom*, int) {}

}  // namespace

TEST_CASE("spaceCollide's phase profile counts the broad phase's pairs and its phases make up the call",
          "[big][threads]") {
    Session session;
    Pile pile(11);
    for (int i = 0; i < 30; ++i) pile.step(true);  // settled into touching pairs
    PairCount expected;
    dSpaceCollide(pile.space, &expected, &countNearCallback);
    REQUIRE(expected.gdcontact > 20);
    REQUIRE(expected.other > 0);  // the spheres

    if (!gdc::ode::detail::spaceCollideProfilingBuilt()) {
        // Compiled out (the default build; scripts/sanitize's address build has it): asking for it
        // says why, and a call records nothing.
        CHECK_THROWS_WITH(gdc::ode::detail::setSpaceCollideProfiling(true), Catch::Contains("GDCONTACT_PHASE_PROFILING"));
        gdc::ode::spaceCollide(pile.space, Pile::kMaxContacts, nullptr, &ignoreContacts);
        CHECK(gdc::ode::detail::lastSpaceCollideProfile().totalSeconds == 0.0);
        return;
    }
    gdc::ode::detail::setSpaceCollideProfiling(true);
    for (int threads : {1, 2}) {
        gdc::ode::setThreadCount(threads);
        gdc::ode::spaceCollide(pile.space, Pile::kMaxContacts, nullptr, &ignoreContacts);
        const gdc::ode::detail::SpaceCollideProfile p = gdc::ode::detail::lastSpaceCollideProfile();
        INFO(threads << " threads");
        CHECK(p.threads == threads);
        CHECK(p.gdcontactPairs == expected.gdcontact);
        CHECK(p.otherPairs == expected.other);
        CHECK(p.narrowSeconds > 0.0);
        CHECK(p.narrowOnCallerSeconds <= p.narrowSeconds);
        CHECK(p.broadPhaseSeconds > 0.0);
        CHECK(p.handlerSeconds >= 0.0);
        // The phases are read off the same clock as the call; their sum may differ from it by rounding.
        const double phases = p.broadPhaseSeconds + p.drainSeconds + p.handlerSeconds;
        CHECK(phases <= p.totalSeconds + 1e-9);
        CHECK(phases >= 0.9 * p.totalSeconds);
        if (threads == 1) CHECK(p.narrowSeconds <= p.broadPhaseSeconds);  // serial: inside the broad phase
    }

    // Off: a call leaves the last record alone.
    const double recorded = gdc::ode::detail::lastSpaceCollideProfile().totalSeconds;
    gdc::ode::detail::setSpaceCollideProfiling(false);
    gdc::ode::spaceCollide(pile.space, Pile::kMaxContacts, nullptr, &ignoreContacts);
    CHECK(gdc::ode::detail::lastSpaceCollideProfile().totalSeconds == recorded);
}

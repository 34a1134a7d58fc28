// spaceCollide where a body touches the static world through several geoms (a box on the ground and
// against a wall, as in bench_big_world's bin): there the per-body-pair budget applies, so
// spaceCollide equals the near callback + gdc::ode::BodyPairContacts, not plain dCollide's contacts;
// and after a world of asleep bodies is destroyed, a new world whose geoms reuse its addresses gets
// the same (no state of the caches — pair cache, box polytopes, thread caches — carried over).
#include <gdcontact/ode.hpp>

#include "sanitizer_scale.hpp"

#include <catch2/catch.hpp>

#include <cstring>
#include <set>
#include <vector>

namespace {

struct Session {
    Session() {
        dInitODE2(0);
        gdc::ode::install();  // the default settings: the budget on (maxBodyPairContacts 4)
    }
    ~Session() {
        gdc::ode::setThreadCount(0);
        gdc::ode::setPairCacheEnabled(true);
        dCloseODE();
    }
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
};

constexpr int kMaxContacts = 8;

struct Reported {
    dGeomID o1, o2;
    std::vector<dContactGeom> contacts;
};

bool sameContact(const dContactGeom& a, const dContactGeom& b) {  // the fields ODE sets (no padding)
    return std::memcmp(a.pos, b.pos, 3 * sizeof(dReal)) == 0 && std::memcmp(a.normal, b.normal, 3 * sizeof(dReal)) == 0 &&
           std::memcmp(&a.depth, &b.depth, sizeof(dReal)) == 0 && a.g1 == b.g1 && a.g2 == b.g2 &&
           a.side1 == b.side1 && a.side2 == b.side2;
}

bool sameReports(const std::vector<Reported>& a, const std::vector<Reported>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].o1 != b[i].o1 || a[i].o2 != b[i].o2 || a[i].contacts.size() != b[i].contacts.size()) return false;
        for (std::size_t k = 0; k < a[i].contacts.size(); ++k)
            if (!sameContact(a[i].contacts[k], b[i].contacts[k])) return false;
    }
    return true;
}

void recordHandler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
    static_cast<std::vector<Reported>*>(data)->push_back({o1, o2, {contacts, contacts + count}});
}

// The classic loop: dSpaceCollide + gdc::ode::collide per pair, touching pairs only.
std::vector<Reported> plainLoop(dSpaceID space) {
    std::vector<Reported> out;
    dSpaceCollide(space, &out, [](void* data, dGeomID o1, dGeomID o2) {
        dContactGeom contacts[kMaxContacts];
        const int count = gdc::ode::collide(o1, o2, kMaxContacts, contacts, sizeof(dContactGeom));
        if (count > 0) recordHandler(data, o1, o2, contacts, count);
    });
    return out;
}

// The same loop with the per-body-pair budget, as docs/ode.md tells a near callback to apply it.
std::vector<Reported> loopWithBudget(dSpaceID space) {
    gdc::ode::BodyPairContacts collected;
    dSpaceCollide(space, &collected, [](void* data, dGeomID o1, dGeomID o2) {
        dContactGeom contacts[kMaxContacts];
        const int count = gdc::ode::collide(o1, o2, kMaxContacts, contacts, sizeof(dContactGeom));
        static_cast<gdc::ode::BodyPairContacts*>(data)->add(o1, o2, contacts, count);
    });
    std::vector<Reported> out;
    collected.deliver(&out, &recordHandler);
    return out;
}

std::vector<Reported> viaSpaceCollide(dSpaceID space, int threads) {
    gdc::ode::setThreadCount(threads);
    std::vector<Reported> out;
    gdc::ode::spaceCollide(space, kMaxContacts, &out, &recordHandler);
    return out;
}

dGeomID staticBox(dSpaceID space, double x, double y, double z, double lx, double ly, double lz) {
    dGeomID box = dCreateBox(space, lx, ly, lz);
    dGeomSetPosition(box, x, y, z);
    return box;
}

// A world of dBoxes: bodies on a plane inside a walled bin (bench_big_world's pile), stepped with
// spaceCollide's contacts under QuickStep; optionally with ODE's auto-disable, so that bodies sleep.
struct World {
    dWorldID world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(nullptr);
    dJointGroupID joints = dJointGroupCreate(0);
    std::vector<dBodyID> bodies;

    explicit World(bool autoDisable) {
        dRandSetSeed(1);  // QuickStep's constraint shuffling
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetQuickStepNumIterations(world, 20);
        dWorldSetAutoDisableFlag(world, autoDisable ? 1 : 0);
        dWorldSetAutoDisableLinearThreshold(world, 0.1);
        dWorldSetAutoDisableAngularThreshold(world, 0.3);
        dCreatePlane(space, 0, 0, 1, 0);
    }
    ~World() {
        dJointGroupDestroy(joints);
        dSpaceDestroy(space);
        dWorldDestroy(world);
    }
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    void addBin(double half) {  // four walls 5 m high, as bench_big_world's addBin
        staticBox(space, -(half + 0.1), 0, 2.5, 0.2, 2 * half + 0.4, 5);
        staticBox(space, half + 0.1, 0, 2.5, 0.2, 2 * half + 0.4, 5);
        staticBox(space, 0, -(half + 0.1), 2.5, 2 * half + 0.4, 0.2, 5);
        staticBox(space, 0, half + 0.1, 2.5, 2 * half + 0.4, 0.2, 5);
    }
    dBodyID addBox(double lx, double ly, double lz, double x, double y, double z, double turn) {
        dBodyID body = dBodyCreate(world);
        dMass mass;
        dMassSetBoxTotal(&mass, 1.0, lx, ly, lz);
        dBodySetMass(body, &mass);
        dGeomSetBody(dCreateBox(space, lx, ly, lz), body);
        dBodySetPosition(body, x, y, z);
        dMatrix3 r;
        dRFromAxisAndAngle(r, 0.3, 0.2, 1.0, turn);
        dBodySetRotation(body, r);
        bodies.push_back(body);
        return body;
    }
    void step() {
        gdc::ode::spaceCollide(space, kMaxContacts, this, [](void* data, dGeomID o1, dGeomID o2, dContactGeom* c, int n) {
            World& w = *static_cast<World*>(data);
            dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
            if (!b1 && !b2) return;
            for (int i = 0; i < n; ++i) {
                dContact contact{};
                contact.surface.mode = dContactApprox1;
                contact.surface.mu = 0.6;
                contact.geom = c[i];
                dJointAttach(dJointCreateContact(w.world, w.joints, &contact), b1, b2);
            }
        });
        dWorldQuickStep(world, 1.0 / 60.0);
        dJointGroupEmpty(joints);
    }
    std::set<const void*> geoms() const {
        std::set<const void*> out;
        for (int i = 0; i < dSpaceGetNumGeoms(space); ++i) out.insert(dSpaceGetGeom(space, i));
        return out;
    }
};

}  // namespace

TEST_CASE("a box standing on the ground against a wall gets from spaceCollide the loop's contacts with "
          "BodyPairContacts, not plain dCollide's (the budget merges two of the wall pair's points)",
          "[big]") {
    Session session;
    World w(false);
    w.addBin(2.55);  // the wall at y = 2.55 .. 2.75, 5.5 m long, 5 m high from z = 0 (the pile's)
    // bench_big_world's pile (1000 boxes, seed 97433387), step 5: a 0.4 × 0.3 × 0.2 box stood up
    // on its 0.3 × 0.2 end, its face pressed 0.15 mm into the wall, its lower end 0.1 mm into the
    // ground. The wall pair's polygon is clipped by the wall's bottom edge at z = 0 into two points
    // 0.3 mm apart: within the budget's near-duplicate distance (a thousandth of 0.4 m).
    dBodyID standing = w.addBox(0.4, 0.3, 0.2, 0, 0, 0, 0);
    const dQuaternion q = {-0.49498657190602718, -0.50800998816149612, -0.49210716397712462, 0.50472238381437728};
    dBodySetQuaternion(standing, q);
    dBodySetPosition(standing, 1.6039670819413894, 2.4462667798993722, 0.20086982285788474);

    const std::vector<Reported> plain = plainLoop(w.space);
    const std::vector<Reported> budgeted = loopWithBudget(w.space);
    // The box's pairs (the others are the bin's walls against each other and the ground): the
    // ground and the wall, the same two in both.
    auto ofBox = [&](const std::vector<Reported>& reports) {
        std::vector<const Reported*> out;
        for (const Reported& r : reports)
            if (dGeomGetBody(r.o1) == standing || dGeomGetBody(r.o2) == standing) out.push_back(&r);
        return out;
    };
    const std::vector<const Reported*> plainBox = ofBox(plain), budgetedBox = ofBox(budgeted);
    REQUIRE(plainBox.size() == 2);
    REQUIRE(budgetedBox.size() == 2);
    const std::size_t wall =
        dGeomGetClass(plainBox[0]->o1) == dPlaneClass || dGeomGetClass(plainBox[0]->o2) == dPlaneClass ? 1 : 0;
    CHECK(plainBox[wall]->contacts.size() == 3);
    CHECK(budgetedBox[wall]->contacts.size() == 2);  // the two points at z = 0 merged into the deeper
    CHECK(plainBox[1 - wall]->contacts.size() == budgetedBox[1 - wall]->contacts.size());  // the ground's kept

    for (int threads : {1, 2}) {
        for (bool cache : {false, true}) {
            gdc::ode::setPairCacheEnabled(cache);
            INFO(threads << " threads, pair cache " << (cache ? "on" : "off"));
            const std::vector<Reported> space = viaSpaceCollide(w.space, threads);
            CHECK(sameReports(space, budgeted));
            CHECK_FALSE(sameReports(space, plain));
        }
    }
}

TEST_CASE("after a world of asleep bodies is destroyed, a new world at reused addresses gets from spaceCollide "
          "the near callback + BodyPairContacts's contacts every step, with and without the pair cache",
          "[big][threads]") {
    Session session;
    std::set<const void*> earlier;
    {
        // A resting world that falls asleep: rows of bricks on the ground (other box sizes).
        World first(true);
        for (int row = 0; row < 4; ++row)
            for (int i = 0; i < 6; ++i)
                first.addBox(0.4, 0.2, 0.13, (i - 2.5) * 0.41 + (row % 2) * 0.1, 0, 0.065 + row * 0.1301, 0);
        gdc::ode::setThreadCount(2);
        for (int i = 0; i < 200; ++i) first.step();
        int asleep = 0;
        for (dBodyID b : first.bodies) asleep += !dBodyIsEnabled(b);
        REQUIRE(asleep == static_cast<int>(first.bodies.size()));
        earlier = first.geoms();
        for (dBodyID b : first.bodies) earlier.insert(dBodyGetFirstGeom(b));
    }
    // A pile in a bin: boxes on the ground and against the walls, half of them asleep later on.
    World second(true);
    second.addBin(0.9);
    for (int layer = 0; layer < 3; ++layer)
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 5; ++j)
                second.addBox(0.4, 0.3, 0.2, -0.67 + i * 0.45 + (layer % 2) * 0.02, -0.72 + j * 0.36,
                              0.11 + layer * 0.22, 0.1 * (i - j));
    std::size_t reused = 0;
    for (const void* g : second.geoms()) reused += earlier.count(g);
    INFO("geoms of the new world at an address of the destroyed one: " << reused);
    // The allocator hands the freed geoms' memory out again; a sanitizer's allocator quarantines
    // freed memory (no reuse), and there the rest of the test checks a fresh world.
    if (!gdc::testing::kUnderSanitizer) REQUIRE(reused >= 5);

    int budgetApplied = 0;
    for (int step = 0; step < 150; ++step) {
        if (step % 10 == 0) {
            const std::vector<Reported> reference = loopWithBudget(second.space);
            budgetApplied += !sameReports(reference, plainLoop(second.space));
            for (int threads : {1, 2}) {
                for (bool cache : {false, true}) {
                    gdc::ode::setPairCacheEnabled(cache);
                    INFO("step " << step << ", " << threads << " threads, pair cache " << (cache ? "on" : "off"));
                    REQUIRE(sameReports(viaSpaceCollide(second.space, threads), reference));
                }
            }
        }
        gdc::ode::setPairCacheEnabled(true);
        gdc::ode::setThreadCount(2);
        second.step();
    }
    INFO("checked steps where the budget changed the plain loop's contacts: " << budgetApplied);
    int asleep = 0;
    for (dBodyID b : second.bodies) asleep += !dBodyIsEnabled(b);
    CHECK(asleep > 0);  // the pair cache answered for asleep bodies
}

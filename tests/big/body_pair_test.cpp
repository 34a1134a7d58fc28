// The per-body-pair contact budget in the ODE adapter: gdc::ode::reduceBodyPair on the contacts a
// near callback collects, and gdc::ode::spaceCollide applying it (the same survivors as the near
// callback + reduceBodyPair, each geom pair handed its own; bit-identical on 1 and 2 threads).
#include <gdcontact/ode.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace {

struct Session {
    explicit Session(const gdc::Settings& settings = {}) {
        dInitODE2(0);
        gdc::ode::install(settings);
    }
    ~Session() {
        gdc::ode::setThreadCount(0);
        dCloseODE();
    }
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
};

gdc::Settings withBudget(int budget) {
    gdc::Settings settings;
    settings.maxBodyPairContacts = budget;
    return settings;
}

constexpr int kMaxContacts = 8;

// Composites: each body a slab on two legs (three dBoxes; every third body's slab a createConvex
// box), dropped in a 3 × 3 grid, two layers, onto a plane: they land on the ground and on each
// other, slab on slab and legs on slab. QuickStep, 20 iterations.
struct Heap {
    dWorldID world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(0);
    dJointGroupID joints = dJointGroupCreate(0);
    std::vector<dBodyID> bodies;

    explicit Heap(unsigned seed) {
        dRandSetSeed(1);
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetERP(world, 0.2);
        dWorldSetCFM(world, 1e-5);
        dWorldSetQuickStepNumIterations(world, 20);
        dCreatePlane(space, 0, 0, 1, 0);
        std::mt19937 random(seed);
        std::uniform_real_distribution<double> jitter(-0.05, 0.05), angle(-0.1, 0.1);
        for (int layer = 0; layer < 2; ++layer)
            for (int k = 0; k < 9; ++k) {
                dBodyID body = dBodyCreate(world);
                dMass mass;
                dMassSetBox(&mass, 500.0, 0.6, 0.4, 0.3);
                dBodySetMass(body, &mass);
                dBodySetPosition(body, 0.55 * (k % 3) + jitter(random), 0.45 * (k / 3) + jitter(random),
                                 0.2 + 0.35 * layer);
                dMatrix3 rotation;
                dRFromEulerAngles(rotation, angle(random), angle(random), angle(random) + 0.3 * layer);
                dBodySetRotation(body, rotation);
                dGeomID slab;
                if (k % 3 == 0) {
                    const dReal points[] = {-0.3, -0.2, -0.05, 0.3, -0.2, -0.05, -0.3, 0.2, -0.05, 0.3, 0.2, -0.05,
                                            -0.3, -0.2, 0.05,  0.3, -0.2, 0.05,  -0.3, 0.2, 0.05,  0.3, 0.2, 0.05};
                    slab = gdc::ode::createConvex(space, points, 8);
                } else {
                    slab = dCreateBox(space, 0.6, 0.4, 0.1);
                }
                dGeomSetBody(slab, body);
                dGeomSetOffsetPosition(slab, 0, 0, 0.05);
                for (double x : {-0.2, 0.2}) {
                    dGeomID leg = dCreateBox(space, 0.1, 0.35, 0.2);
                    dGeomSetBody(leg, body);
                    dGeomSetOffsetPosition(leg, x, 0, -0.1);
                }
                bodies.push_back(body);
            }
    }
    ~Heap() {
        dJointGroupDestroy(joints);
        dSpaceDestroy(space);
        dWorldDestroy(world);
    }
    Heap(const Heap&) = delete;
    Heap& operator=(const Heap&) = delete;

    static void handler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
        Heap& heap = *static_cast<Heap*>(data);
        for (int i = 0; i < count; ++i) {
            dContact contact{};
            contact.surface.mode = dContactApprox1;
            contact.surface.mu = 0.6;
            contact.geom = contacts[i];
            dJointID joint = dJointCreateContact(heap.world, heap.joints, &contact);
            dJointAttach(joint, dGeomGetBody(o1), dGeomGetBody(o2));
        }
    }
    void step() {
        gdc::ode::spaceCollide(space, kMaxContacts, this, &handler);
        dWorldQuickStep(world, 0.01);
        dJointGroupEmpty(joints);
    }
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

// The pair of bodies of a geom pair, order-free.
std::pair<dBodyID, dBodyID> bodyPairOf(dGeomID o1, dGeomID o2) {
    dBodyID a = dGeomGetBody(o1), b = dGeomGetBody(o2);
    if (std::less<dBodyID>()(b, a)) std::swap(a, b);
    return {a, b};
}

struct Reported {
    dGeomID o1, o2;
    std::vector<dContactGeom> contacts;
};

bool sameBits(const dContactGeom& a, const dContactGeom& b) {
    for (int k = 0; k < 3; ++k)
        if (Heap::toBits(a.pos[k]) != Heap::toBits(b.pos[k]) || Heap::toBits(a.normal[k]) != Heap::toBits(b.normal[k]))
            return false;
    return Heap::toBits(a.depth) == Heap::toBits(b.depth) && a.g1 == b.g1 && a.g2 == b.g2;
}

bool sameReports(const std::vector<Reported>& a, const std::vector<Reported>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].o1 != b[i].o1 || a[i].o2 != b[i].o2 || a[i].contacts.size() != b[i].contacts.size()) return false;
        for (std::size_t k = 0; k < a[i].contacts.size(); ++k)
            if (!sameBits(a[i].contacts[k], b[i].contacts[k])) return false;
    }
    return true;
}

void recordHandler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
    REQUIRE(count > 0);
    static_cast<std::vector<Reported>*>(data)->push_back({o1, o2, {contacts, contacts + count}});
}

// The reference: dSpaceCollide + dCollide per pair (installed), then per body pair
// gdc::ode::reduceBodyPair on the contacts of all its geom pairs, as a user's code would do it.
std::vector<Reported> nearCallbackWithReduceBodyPair(dSpaceID space, const gdc::Settings& settings) {
    std::vector<Reported> pairs;
    dSpaceCollide(space, &pairs, [](void* data, dGeomID o1, dGeomID o2) {
        dContactGeom contacts[kMaxContacts];
        const int count = dCollide(o1, o2, kMaxContacts, contacts, sizeof(dContactGeom));
        static_cast<std::vector<Reported>*>(data)->push_back({o1, o2, {contacts, contacts + count}});
    });
    std::map<std::pair<dBodyID, dBodyID>, std::vector<std::size_t>> members;
    for (std::size_t i = 0; i < pairs.size(); ++i) members[bodyPairOf(pairs[i].o1, pairs[i].o2)].push_back(i);
    for (auto& [bodies, indices] : members) {
        if (indices.size() < 2 || bodies.first == bodies.second) continue;
        std::vector<dContactGeom> all;
        for (std::size_t i : indices) all.insert(all.end(), pairs[i].contacts.begin(), pairs[i].contacts.end());
        const dBodyID b1 = dGeomGetBody(pairs[indices[0]].o1), b2 = dGeomGetBody(pairs[indices[0]].o2);
        const int kept = gdc::ode::reduceBodyPair(b1, b2, all.data(), static_cast<int>(all.size()),
                                                  sizeof(dContactGeom), settings);
        int next = 0;
        for (std::size_t i : indices) {  // each pair's survivors: a run, in the pairs' order
            std::vector<dContactGeom> survivors;
            while (next < kept && all[next].g1 == pairs[i].o1 && all[next].g2 == pairs[i].o2) survivors.push_back(all[next++]);
            pairs[i].contacts = survivors;
        }
        REQUIRE(next == kept);
    }
    std::vector<Reported> touching;
    for (Reported& r : pairs)
        if (!r.contacts.empty()) touching.push_back(std::move(r));
    return touching;
}

// Clusters of a body pair's contacts by normal (oriented into the first body), as the rule forms them.
int clusterCount(const std::vector<dContactGeom>& contacts, dBodyID first, double tolerance) {
    std::vector<gdc::Vec3> normals;
    for (const dContactGeom& c : contacts) {
        gdc::Vec3 n(c.normal[0], c.normal[1], c.normal[2]);
        if (dGeomGetBody(c.g1) != first) n = -n;
        if (std::none_of(normals.begin(), normals.end(), [&](const gdc::Vec3& m) { return n.dot(m) >= std::cos(tolerance); }))
            normals.push_back(n);
    }
    return static_cast<int>(normals.size());
}

}  // namespace

TEST_CASE("spaceCollide with the body-pair budget: the near callback + reduceBodyPair's survivors, "
          "bit-identical on 1 and 2 threads, within the budget per body pair",
          "[big][threads]") {
    const gdc::Settings settings = withBudget(4);
    Session session(settings);
    Heap heap(3);
    for (int i = 0; i < 80; ++i) heap.step();  // landed: slabs on slabs, legs on slabs and on the ground

    const std::vector<Reported> reference = nearCallbackWithReduceBodyPair(heap.space, settings);
    // The scene has composites touching through several geom pairs, and the budget cut them.
    std::map<std::pair<dBodyID, dBodyID>, std::vector<dContactGeom>> perBodyPair;
    for (const Reported& r : reference)
        for (const dContactGeom& c : r.contacts) perBodyPair[bodyPairOf(r.o1, r.o2)].push_back(c);
    int reducedPairs = 0;
    for (const auto& [bodies, contacts] : perBodyPair) {
        const dBodyID first = dGeomGetBody(contacts.front().g1);
        const int clusters = clusterCount(contacts, first, settings.bodyPairNormalTolerance);
        INFO("body pair with " << contacts.size() << " contacts in " << clusters << " clusters");
        std::map<std::pair<dGeomID, dGeomID>, int> geomPairs;
        for (const dContactGeom& c : contacts) ++geomPairs[{c.g1, c.g2}];
        if (geomPairs.size() > 1) {
            CHECK(static_cast<int>(contacts.size()) <= settings.maxBodyPairContacts * clusters);
            ++reducedPairs;
        }
    }
    INFO("body pairs touching through several geom pairs: " << reducedPairs);
    REQUIRE(reducedPairs >= 5);

    for (int threads : {1, 2, 1}) {
        gdc::ode::setThreadCount(threads);
        std::vector<Reported> reported;
        gdc::ode::spaceCollide(heap.space, kMaxContacts, &reported, &recordHandler);
        INFO(threads << " threads");
        CHECK(sameReports(reported, reference));
    }

    // A user's own near callback with gdc::ode::BodyPairContacts: the same, twice (it clears).
    gdc::ode::BodyPairContacts collected(settings);
    for (int round = 0; round < 2; ++round) {
        dSpaceCollide(heap.space, &collected, [](void* data, dGeomID o1, dGeomID o2) {
            dContactGeom contacts[kMaxContacts];
            const int count = dCollide(o1, o2, kMaxContacts, contacts, sizeof(dContactGeom));
            static_cast<gdc::ode::BodyPairContacts*>(data)->add(o1, o2, contacts, count);
        });
        std::vector<Reported> reported;
        collected.deliver(&reported, &recordHandler);
        INFO("BodyPairContacts, round " << round);
        CHECK(sameReports(reported, reference));
    }
    CHECK_THROWS_AS(collected.add(nullptr, nullptr, nullptr, 1), gdc::InvalidInput);
    CHECK_THROWS_AS(collected.deliver(nullptr, nullptr), gdc::InvalidInput);
    gdc::Settings bad = settings;
    bad.bodyPairNormalTolerance = -1;
    CHECK_THROWS_WITH(gdc::ode::BodyPairContacts(bad), Catch::Contains("bodyPairNormalTolerance"));
}

TEST_CASE("spaceCollide with the budget off (0) gives dCollide's contacts for composites", "[big]") {
    const gdc::Settings settings = withBudget(0);
    Session session(settings);
    Heap heap(3);
    for (int i = 0; i < 80; ++i) heap.step();
    std::vector<Reported> reference;
    dSpaceCollide(heap.space, &reference, [](void* data, dGeomID o1, dGeomID o2) {
        dContactGeom contacts[kMaxContacts];
        const int count = dCollide(o1, o2, kMaxContacts, contacts, sizeof(dContactGeom));
        if (count > 0) static_cast<std::vector<Reported>*>(data)->push_back({o1, o2, {contacts, contacts + count}});
    });
    gdc::ode::setThreadCount(2);
    std::vector<Reported> reported;
    gdc::ode::spaceCollide(heap.space, kMaxContacts, &reported, &recordHandler);
    CHECK(sameReports(reported, reference));
    // and more contacts than with the budget: it is what the budget removes
    std::size_t total = 0;
    for (const Reported& r : reference) total += r.contacts.size();
    gdc::ode::install(withBudget(4));
    std::vector<Reported> budgeted;
    gdc::ode::spaceCollide(heap.space, kMaxContacts, &budgeted, &recordHandler);
    std::size_t budgetedTotal = 0;
    for (const Reported& r : budgeted) budgetedTotal += r.contacts.size();
    CHECK(budgetedTotal < total);
}

TEST_CASE("a heap of composites with the body-pair budget replays bit for bit on 1 and 2 threads", "[big][threads]") {
    Session session(withBudget(4));
    auto run = [](int threads) {
        gdc::ode::setThreadCount(threads);
        Heap heap(5);
        for (int i = 0; i < 100; ++i) heap.step();
        return heap.stateBits();
    };
    const auto one = run(1);
    CHECK(run(2) == one);
    Heap start(5);
    CHECK(start.stateBits() != one);  // it moved
}

TEST_CASE("reduceBodyPair: budget, deepest kept, survivors unchanged, mirrored for swapped bodies and geoms", "[big]") {
    Session session;
    dWorldID world = dWorldCreate();
    dWorldSetGravity(world, 0, 0, -9.81);
    dSpaceID space = dSimpleSpaceCreate(0);
    // A: three slabs side by side, one body, resting tilted by 0.01 rad on B: two wide slabs.
    dBodyID a = dBodyCreate(world), b = dBodyCreate(world);
    dBodySetPosition(a, 0.0, 0.0, 0.095);
    dMatrix3 tilt;
    dRFromAxisAndAngle(tilt, 1, 0.3, 0, 0.01);
    dBodySetRotation(a, tilt);
    dBodySetPosition(b, 0.0, 0.0, -0.1);
    std::vector<dGeomID> partsA, partsB;
    for (double x : {-0.4, 0.0, 0.4}) {
        dGeomID g = dCreateBox(space, 0.38, 0.3, 0.2);
        dGeomSetBody(g, a);
        dGeomSetOffsetPosition(g, x, 0, 0);
        partsA.push_back(g);
    }
    for (double y : {-0.2, 0.2}) {
        dGeomID g = dCreateBox(space, 1.4, 0.38, 0.2);
        dGeomSetBody(g, b);
        dGeomSetOffsetPosition(g, 0, y, 0);
        partsB.push_back(g);
    }
    const gdc::Settings settings = withBudget(4);
    auto collect = [&](bool swapGeoms) {
        std::vector<dContactGeom> all;
        for (dGeomID ga : partsA)
            for (dGeomID gb : partsB) {
                dContactGeom contacts[kMaxContacts];
                const int n = swapGeoms ? gdc::ode::collide(gb, ga, kMaxContacts, contacts, sizeof(dContactGeom), settings)
                                        : gdc::ode::collide(ga, gb, kMaxContacts, contacts, sizeof(dContactGeom), settings);
                all.insert(all.end(), contacts, contacts + n);
            }
        return all;
    };
    const std::vector<dContactGeom> all = collect(false);
    REQUIRE(all.size() >= 12);  // 3 × 2 face pairs of parts
    std::vector<dContactGeom> kept = all;
    const int count = gdc::ode::reduceBodyPair(a, b, kept.data(), static_cast<int>(kept.size()), sizeof(dContactGeom), settings);
    CHECK(count == 4);  // one cluster (all normals +z within the tolerance)
    // Survivors are inputs, unchanged, in their order; the deepest is among them.
    std::size_t from = 0;
    for (int k = 0; k < count; ++k) {
        while (from < all.size() && !sameBits(all[from], kept[k])) ++from;
        CHECK(from < all.size());
    }
    const double deepest = std::max_element(all.begin(), all.end(), [](auto& p, auto& q) { return p.depth < q.depth; })->depth;
    CHECK(std::any_of(kept.begin(), kept.begin() + count, [&](const dContactGeom& c) { return c.depth == deepest; }));
    // The kept points span the outer parts of A: x from the left slab to the right one.
    double low = 1e9, high = -1e9;
    for (int k = 0; k < count; ++k) low = std::min<double>(low, kept[k].pos[0]), high = std::max<double>(high, kept[k].pos[0]);
    CHECK(high - low > 1.0);
    // A's centre of mass (dBodyGetPosition) over the kept polygon: its x and y between theirs.
    double lowY = 1e9, highY = -1e9;
    for (int k = 0; k < count; ++k) lowY = std::min<double>(lowY, kept[k].pos[1]), highY = std::max<double>(highY, kept[k].pos[1]);
    CHECK(lowY < 0.0);
    CHECK(highY > 0.0);

    // Swapped bodies: the same survivors.
    std::vector<dContactGeom> swappedBodies = all;
    const int count2 = gdc::ode::reduceBodyPair(b, a, swappedBodies.data(), static_cast<int>(all.size()), sizeof(dContactGeom), settings);
    REQUIRE(count2 == count);
    for (int k = 0; k < count; ++k) CHECK(sameBits(swappedBodies[k], kept[k]));
    // Swapped geoms in every pair (ODE's mirrored contacts): the mirrored survivors.
    std::vector<dContactGeom> mirrored = collect(true);
    REQUIRE(mirrored.size() == all.size());
    const int count3 = gdc::ode::reduceBodyPair(a, b, mirrored.data(), static_cast<int>(mirrored.size()), sizeof(dContactGeom), settings);
    REQUIRE(count3 == count);
    for (int k = 0; k < count; ++k) {
        for (int i = 0; i < 3; ++i) {
            CHECK(mirrored[k].pos[i] == Approx(kept[k].pos[i]).margin(1e-12));
            CHECK(mirrored[k].normal[i] == Approx(-kept[k].normal[i]).margin(1e-12));
        }
        CHECK(mirrored[k].g1 == kept[k].g2);
        CHECK(mirrored[k].depth == Approx(kept[k].depth).margin(1e-12));
    }

    // Off, or one geom pair: unchanged.
    std::vector<dContactGeom> untouched = all;
    CHECK(gdc::ode::reduceBodyPair(a, b, untouched.data(), static_cast<int>(all.size()), sizeof(dContactGeom), withBudget(0)) ==
          static_cast<int>(all.size()));
    dContactGeom single[kMaxContacts];
    const int n = gdc::ode::collide(partsA[1], partsB[0], kMaxContacts, single, sizeof(dContactGeom), settings);
    REQUIRE(n >= 4);  // a face pair's rectangle: more than a budget of 2, kept whole
    CHECK(gdc::ode::reduceBodyPair(a, b, single, n, sizeof(dContactGeom), withBudget(2)) == n);

    // Bad input, where it enters.
    CHECK_THROWS_AS(gdc::ode::reduceBodyPair(a, a, untouched.data(), 4, sizeof(dContactGeom), settings), gdc::InvalidInput);
    CHECK_THROWS_AS(gdc::ode::reduceBodyPair(nullptr, nullptr, untouched.data(), 4, sizeof(dContactGeom), settings), gdc::InvalidInput);
    CHECK_THROWS_AS(gdc::ode::reduceBodyPair(a, b, untouched.data(), 4, 8, settings), gdc::InvalidInput);
    CHECK_THROWS_AS(gdc::ode::reduceBodyPair(a, b, nullptr, 4, sizeof(dContactGeom), settings), gdc::InvalidInput);
    CHECK_THROWS_AS(gdc::ode::reduceBodyPair(a, b, untouched.data(), -1, sizeof(dContactGeom), settings), gdc::InvalidInput);
    dBodyID c = dBodyCreate(world);
    CHECK_THROWS_WITH(gdc::ode::reduceBodyPair(a, c, untouched.data(), 4, sizeof(dContactGeom), settings),
                      Catch::Contains("not between a geom of b1 and a geom of b2"));
    gdc::Settings bad = settings;
    bad.maxBodyPairContacts = 17;
    CHECK_THROWS_WITH(gdc::ode::reduceBodyPair(a, b, untouched.data(), 4, sizeof(dContactGeom), bad),
                      Catch::Contains("maxBodyPairContacts"));

    dSpaceDestroy(space);
    dWorldDestroy(world);
}

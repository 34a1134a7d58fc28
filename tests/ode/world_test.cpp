// gdcontact's contacts consumed by ODE's solvers: a dropped box, the 10-high cube stack, touching
// cubes, a composite gear; collide() from several threads at once; boxes spun by ODE's integrator.
#include <gdcontact/ode.hpp>

#include "ode_precision.hpp"
#include "ode_support.hpp"
#include "stack_scene.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <random>
#include <thread>
#include <vector>

using namespace gdc;
using namespace gdc::ode::test;
using namespace gdc::ode::scenes;

namespace {

// A world with the parameters every world test uses: ERP 0.2, CFM 1e-5, dt 0.01, μ 0.8.
struct World {
    dWorldID world = dWorldCreate();
    dSpaceID space = dSimpleSpaceCreate(0);
    dJointGroupID contacts = dJointGroupCreate(0);
    static constexpr double kTimeStep = 0.01;
    World() {
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetERP(world, 0.2);
        dWorldSetCFM(world, 1e-5);
        dWorldSetQuickStepNumIterations(world, 20);
    }
    ~World() {
        dSpaceDestroy(space);
        dJointGroupDestroy(contacts);
        dWorldDestroy(world);
    }
    static void nearCallback(void* data, dGeomID o1, dGeomID o2) {
        auto* self = static_cast<World*>(data);
        if (dGeomIsSpace(o1) || dGeomIsSpace(o2)) {
            dSpaceCollide2(o1, o2, data, &nearCallback);
            return;
        }
        dContact records[8];
        const int count = dCollide(o1, o2, 8, &records[0].geom, sizeof(dContact));
        for (int i = 0; i < count; ++i) {
            records[i].surface.mode = dContactApprox1;
            records[i].surface.mu = 0.8;
            dJointAttach(dJointCreateContact(self->world, self->contacts, &records[i]), dGeomGetBody(o1),
                         dGeomGetBody(o2));
        }
    }
    void step(bool quick) {
        dSpaceCollide(space, this, &nearCallback);
        if (quick)
            dWorldQuickStep(world, kTimeStep);
        else
            dWorldStep(world, kTimeStep);
        dJointGroupEmpty(contacts);
    }
};

// Angle between the body axis closest to the vertical and the vertical.
double alignmentError(dBodyID body) {
    const Mat3 rotation = bodyRotation(body);
    double best = 0.0;
    for (int axis = 0; axis < 3; ++axis) best = std::max(best, std::abs(rotation(2, axis)));
    return std::acos(std::min(1.0, best));
}

}  // namespace

TEST_CASE("a tilted box dropped on a plane settles flat under dWorldQuickStep", "[ode][world]") {
    // Three seeds of ODE's generator, which QuickStep uses to shuffle its constraints.
    for (unsigned long seed = 1; seed <= 3; ++seed) {
        OdeSession session;
        dRandSetSeed(seed);
        World scene;
        dCreatePlane(scene.space, 0, 0, 1, 0);
        dBodyID body = dBodyCreate(scene.world);
        dMass mass;
        dMassSetBoxTotal(&mass, 1.0, 1.0, 0.6, 0.4);
        dBodySetMass(body, &mass);
        dBodySetPosition(body, 0, 0, 1.2);
        const Mat3 tilt = rotationAbout(Vec3(1, 0, 0), 0.35) * rotationAbout(Vec3(0, 1, 0), 0.2);
        dMatrix3 matrix;
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) matrix[4 * r + c] = tilt(r, c);
            matrix[4 * r + 3] = 0;
        }
        dBodySetRotation(body, matrix);
        dGeomSetBody(dCreateBox(scene.space, 1.0, 0.6, 0.4), body);
        double worstAfterSettling = 0.0;
        for (int step = 0; step < 500; ++step) {
            scene.step(true);
            if (step * World::kTimeStep >= 2.0) worstAfterSettling = std::max(worstAfterSettling, alignmentError(body));
        }
        INFO("seed " << seed);
        CHECK(dBodyGetPosition(body)[2] < 0.35);  // it fell and came to rest on a face
        CHECK(worstAfterSettling < 1e-6);
    }
}

TEST_CASE("a 10-high stack of createConvex cubes stands 20 s under dWorldStep",
          "[ode][world][stack]") {
    // The same stack of dBox geoms with ODE's dBoxBox holds to ~1e-4 mm here; with createConvex
    // cubes and ODE's own convex collider (libccd MPR, one contact per pair) it falls. Neither is
    // asserted: this test is about gdcontact. Numbers: build/samples/ode_stack/ode_stack.
    const StackResult result = runStack(StackCollider::Gdcontact, Solver::Step);
    CHECK(result.standing);
    CHECK(result.driftMm < 1.0);
    CHECK(result.twistDeg < 0.1);
}

TEST_CASE("under dWorldQuickStep the convex stack drifts and twists no more than 1.5x the dBox stack",
          "[ode][world][stack]") {
    // QuickStep (20 iterations) alone lets the dBox reference drift centimetres, so this compares
    // with it instead of asserting an absolute figure. Its constraint shuffling makes single runs
    // noisy, so both sides are averaged over the same four random seeds.
    double referenceDrift = 0, referenceTwist = 0, drift = 0, twist = 0;
    for (unsigned long seed = 1; seed <= 4; ++seed) {
        StackOptions options;
        options.randomSeed = seed;
        const StackResult reference = runStack(StackCollider::OdeBoxes, Solver::QuickStep, options);
        const StackResult ours = runStack(StackCollider::Gdcontact, Solver::QuickStep, options);
        REQUIRE(reference.standing);
        CHECK(ours.standing);
        referenceDrift += reference.driftMm / 4;
        referenceTwist += reference.twistDeg / 4;
        drift += ours.driftMm / 4;
        twist += ours.twistDeg / 4;
    }
    INFO("dBox reference: drift " << referenceDrift << " mm, twist " << referenceTwist << " deg; gdcontact: drift "
                                  << drift << " mm, twist " << twist << " deg");
    CHECK(drift <= 1.5 * referenceDrift);
    CHECK(twist <= 1.5 * referenceTwist);
}

TEST_CASE("two exactly touching convex cubes: a valid normal, depth 0, and ODE steps on", "[ode][world]") {
    OdeSession session;
    World scene;
    const auto corners = boxCorners(Vec3::Constant(0.5));
    dBodyID lowerBody = dBodyCreate(scene.world), upperBody = dBodyCreate(scene.world);
    dMass mass;
    dMassSetBoxTotal(&mass, 1.0, 1, 1, 1);
    dBodySetMass(lowerBody, &mass);
    dBodySetMass(upperBody, &mass);
    dBodySetPosition(lowerBody, 0, 0, 0.5);
    dBodySetPosition(upperBody, 0.25, 0, 1.5);
    dGeomID lower = gdc::ode::createConvex(scene.space, corners.data(), 8);
    dGeomID upper = gdc::ode::createConvex(scene.space, corners.data(), 8);
    dGeomSetBody(lower, lowerBody);
    dGeomSetBody(upper, upperBody);
    dCreatePlane(scene.space, 0, 0, 1, 0);

    const auto contacts = collideThroughOde(upper, lower, 8);
    REQUIRE(!contacts.empty());
    for (const dContactGeom& contact : contacts) {
        CHECK((toVec(contact.normal) - Vec3::UnitZ()).norm() < realTolerance(1e-12));
        CHECK(contact.depth == 0.0);
    }
    // ODE's Dantzig solver prints "LCP internal error" for a first step whose contacts all have
    // depth 0 (with its own colliders too) but carries on; a zero normal would abort it.
    for (int step = 0; step < 100; ++step) scene.step(false);
    const dReal* top = dBodyGetPosition(upperBody);
    CHECK(std::isfinite(top[0]));
    CHECK(top[2] == Approx(1.5).margin(1e-4));  // still resting on the lower cube, where it was
    CHECK(top[0] == Approx(0.25).margin(1e-4));
}

TEST_CASE("a gear made of offset boxes, a hub and transformed convex teeth rests flat on a plane",
          "[ode][world][composite]") {
    OdeSession session;
    World scene;
    dCreatePlane(scene.space, 0, 0, 1, 0);
    dBodyID gear = dBodyCreate(scene.world);
    dMass mass;
    dMassSetCylinderTotal(&mass, 2.0, 3, 0.6, 0.2);
    dBodySetMass(gear, &mass);
    // Hub: a 12-sided prism, 0.2 thick, as the hull of its corners.
    std::vector<dReal> hub;
    for (int k = 0; k < 12; ++k)
        for (double z : {-0.1, 0.1}) {
            const double angle = 2 * M_PI * k / 12;
            hub.insert(hub.end(), {0.45 * std::cos(angle), 0.45 * std::sin(angle), z});
        }
    dGeomSetBody(gdc::ode::createConvex(scene.space, hub.data(), static_cast<unsigned>(hub.size() / 3)), gear);
    // Six teeth: three dBox geoms placed with geom offsets, three tapered convex teeth inside
    // dGeomTransforms. Each part is collided with its own contraction point.
    const auto toothCorners = std::vector<dReal>{-0.12, -0.08, -0.1, -0.12, 0.08, -0.1, -0.12, -0.08, 0.1, -0.12, 0.08, 0.1,
                                                 0.12, -0.04, -0.1, 0.12, 0.04, -0.1, 0.12, -0.04, 0.1, 0.12, 0.04, 0.1};
    for (int k = 0; k < 6; ++k) {
        const double angle = 2 * M_PI * k / 6;
        const Mat3 turn = rotationAbout(Vec3::UnitZ(), angle);
        const Vec3 at = turn * Vec3(0.55, 0, 0);
        dMatrix3 matrix;
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) matrix[4 * r + c] = turn(r, c);
            matrix[4 * r + 3] = 0;
        }
        if (k % 2 == 0) {
            dGeomID tooth = dCreateBox(scene.space, 0.24, 0.16, 0.2);
            dGeomSetBody(tooth, gear);
            dGeomSetOffsetPosition(tooth, at.x(), at.y(), at.z());
            dGeomSetOffsetRotation(tooth, matrix);
        } else {
            // dGeomTransform is deprecated in ODE 0.16 (geom offsets replace it) but still
            // supported, and programs still use it: gdcontact must work inside one.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
            dGeomID transform = dCreateGeomTransform(scene.space);
            dGeomTransformSetCleanup(transform, 1);
            dGeomID tooth = gdc::ode::createConvex(0, toothCorners.data(), 8);
            dGeomSetPosition(tooth, at.x(), at.y(), at.z());
            dGeomSetRotation(tooth, matrix);
            dGeomTransformSetGeom(transform, tooth);
#pragma GCC diagnostic pop
            dGeomSetBody(transform, gear);
        }
    }
    dBodySetPosition(gear, 0.0, 0.0, 0.2);
    dMatrix3 tilt;
    dRFromAxisAndAngle(tilt, 1, 1, 0, 0.1);
    dBodySetRotation(gear, tilt);
    double worstTilt = 0.0, worstHeightError = 0.0;
    // dWorldStep: under dWorldQuickStep a part can end a step a few nanometres above the plane;
    // its AABB then misses the plane's (ODE bounds an axis-aligned plane by its half-space) and
    // ODE never asks any collider for that pair, so the gear gets a ~1e-3 rad kick now and then
    // whichever collider is installed.
    for (int step = 0; step < 400; ++step) {
        scene.step(false);
        if (step * World::kTimeStep >= 2.0) {
            worstTilt = std::max(worstTilt, alignmentError(gear));
            worstHeightError = std::max(worstHeightError, std::abs(dBodyGetPosition(gear)[2] - 0.1));
        }
    }
    CHECK(worstTilt < 1e-4);
    CHECK(worstHeightError < 1e-3);  // resting on its 0.2-thick faces, neither sunk nor hovering
}

TEST_CASE("collide from several threads on disjoint geoms gives the sequential answers", "[ode][threads]") {
    OdeSession session;
    std::mt19937_64 random(7);
    constexpr int kThreads = 4, kPairsPerThread = 50;
    std::vector<dGeomID> geoms;
    const auto corners = boxCorners(Vec3(0.4, 0.3, 0.5));
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    for (int i = 0; i < kThreads * kPairsPerThread; ++i) {
        dGeomID a = i % 2 ? dCreateBox(0, 1.0, 0.7, 0.5) : gdc::ode::createConvex(0, corners.data(), 8);
        dGeomID b = gdc::ode::createConvex(0, corners.data(), 8);
        setPose(a, Pose{randomRotation(random), Vec3(jitter(random), jitter(random), jitter(random))});
        setPose(b, Pose{randomRotation(random), Vec3(jitter(random), jitter(random), 0.6)});
        geoms.push_back(a);
        geoms.push_back(b);
    }
    auto collidePair = [&](int pair, dContactGeom* out) {
        return gdc::ode::collide(geoms[2 * pair], geoms[2 * pair + 1], 8, out, sizeof(dContactGeom));
    };
    std::vector<std::array<dContactGeom, 8>> sequential(geoms.size() / 2), parallel(geoms.size() / 2);
    std::vector<int> sequentialCounts(geoms.size() / 2), parallelCounts(geoms.size() / 2);
    for (int pair = 0; pair < kThreads * kPairsPerThread; ++pair)
        sequentialCounts[pair] = collidePair(pair, sequential[pair].data());
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            for (int repeat = 0; repeat < 20; ++repeat)
                for (int pair = t * kPairsPerThread; pair < (t + 1) * kPairsPerThread; ++pair)
                    parallelCounts[pair] = collidePair(pair, parallel[pair].data());
        });
    for (std::thread& thread : threads) thread.join();
    int withContacts = 0;
    for (std::size_t pair = 0; pair < sequential.size(); ++pair) {
        REQUIRE(parallelCounts[pair] == sequentialCounts[pair]);
        withContacts += sequentialCounts[pair] > 0;
        for (int i = 0; i < sequentialCounts[pair]; ++i) {
            CHECK(toVec(parallel[pair][i].pos) == toVec(sequential[pair][i].pos));
            CHECK(toVec(parallel[pair][i].normal) == toVec(sequential[pair][i].normal));
            CHECK(parallel[pair][i].depth == sequential[pair][i].depth);
        }
    }
    CHECK(withContacts > 0);
    for (dGeomID geom : geoms) dGeomDestroy(geom);
}

// A body's rotation as ODE's own integrator leaves it: orthonormal to ~1e-16 in a double-precision
// ODE, only to a few float ulps (up to ~1.2e-6) in a single-precision one. The normal the core
// carries through such a rotation is off unit by as much; writeContacts refused it beyond 1e-6
// ("the core returned an invalid normal; pair skipped"), so a spinning box lost every contact with
// the ground in about 1 of 10^4 calls under a single-precision ODE (the 1e5 m stack showed it).
// Boxes spun fast by dWorldStep, each step sunk 1 cm into the ground plane and into a ground box:
// every call gets contacts, with unit normals, and ODE prints no message.
TEST_CASE("boxes spun by ODE's integrator keep their contacts (rotations a few ulps off orthonormal)", "[ode][world]") {
    OdeSession session;
    static int messages;
    messages = 0;
    dMessageFunction* previous = dGetMessageHandler();
    dSetMessageHandler([](int, const char*, va_list) { ++messages; });
    dWorldID world = dWorldCreate();
    dGeomID plane = dCreatePlane(nullptr, 0, 0, 1, 0);
    dGeomID groundBox = dCreateBox(nullptr, 4, 4, 1);
    dGeomSetPosition(groundBox, 0, 0, -0.5);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> spin(-30, 30);
    int calls = 0, withoutContacts = 0;
    double worstOrthonormality = 0, worstNormal = 0;
    for (int b = 0; b < 50; ++b) {
        dBodyID body = dBodyCreate(world);
        dGeomID box = dCreateBox(nullptr, 1, 0.8, 0.6);
        dGeomSetBody(box, body);
        dBodySetAngularVel(body, spin(random), spin(random), spin(random));
        for (int step = 0; step < 1000; ++step) {
            dWorldStep(world, 0.01);  // no gravity, no contacts: the rotation integrated alone
            dBodySetLinearVel(body, 0, 0, 0);
            dBodySetPosition(body, 0, 0, 0);
            dReal aabb[6];
            dGeomGetAABB(box, aabb);
            dBodySetPosition(body, 0, 0, -aabb[4] - 0.01);  // the lowest corner 1 cm deep
            const Mat3 r = gdc::ode::poseOf(box).rotation;
            worstOrthonormality = std::max(worstOrthonormality, (r * r.transpose() - Mat3::Identity()).cwiseAbs().maxCoeff());
            for (dGeomID ground : {plane, groundBox}) {
                const std::vector<dContactGeom> contacts = collideThroughOde(box, ground, 8);
                ++calls;
                withoutContacts += contacts.empty();
                for (const dContactGeom& contact : contacts)
                    worstNormal = std::max(worstNormal, std::abs(toVec(contact.normal).norm() - 1.0));
            }
        }
        dGeomDestroy(box);
        dBodyDestroy(body);
    }
    std::printf("spun boxes: %d calls, rotations off orthonormal by up to %.3g, %d without contacts, %d messages, "
                "normals off unit by up to %.3g\n",
                calls, worstOrthonormality, withoutContacts, messages, worstNormal);
    CHECK(withoutContacts == 0);
    CHECK(messages == 0);
    CHECK(worstNormal <= realTolerance(1e-12));
    dSetMessageHandler(previous);
    dGeomDestroy(groundBox);
    dGeomDestroy(plane);
    dWorldDestroy(world);
}

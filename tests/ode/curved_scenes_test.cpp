// Curved shapes (issue 33) in a real ODE world, gdcontact installed against ODE's own colliders in
// the same test: a capsule lying on a box floor and on a plane, a standing cylinder on a box floor
// and on a hull floor, a box–cylinder–box stack, a lying cylinder rolling on a plane, a standing
// cylinder pushed at its top (its tipping force against the analytic m·g·r/h), and the contract of
// every contact dCollide returns for the curved pairs.
//
// World (as tests/ode/world_test.cpp): gravity −9.81, ERP 0.2, CFM 1e-5, dt 0.01, μ 0.8 with
// dContactApprox1, dWorldQuickStep 20 iterations unless said; each scene over seeds (dRandSetSeed
// and a start jittered by a std::mt19937_64 of the same seed). ODE's own figures are printed
// (WARN), never asserted: these tests are about gdcontact.
#include <gdcontact/ode.hpp>

#include "ode_precision.hpp"
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <vector>

using namespace gdc;
using namespace gdc::ode::test;

namespace {

constexpr double kTimeStep = 0.01;
constexpr double kGravity = 9.81;
constexpr unsigned long kSeeds = 5;
constexpr double kDegree = M_PI / 180.0;

struct World {
    dWorldID world = dWorldCreate();
    dSpaceID space = dSimpleSpaceCreate(0);
    dJointGroupID contacts = dJointGroupCreate(0);
    double mu = 0.8;
    long contactCount = 0;  // contacts created, for the figures
    World() {
        dWorldSetGravity(world, 0, 0, -kGravity);
        dWorldSetERP(world, 0.2);
        dWorldSetCFM(world, 1e-5);
        dWorldSetQuickStepNumIterations(world, 20);
    }
    ~World() {
        dSpaceDestroy(space);
        dJointGroupDestroy(contacts);
        dWorldDestroy(world);
    }
    World(const World&) = delete;
    World& operator=(const World&) = delete;
    static void nearCallback(void* data, dGeomID o1, dGeomID o2) {
        auto* self = static_cast<World*>(data);
        const dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
        if (!b1 && !b2) return;
        dContact records[16];
        const int count = dCollide(o1, o2, 16, &records[0].geom, sizeof(dContact));
        for (int i = 0; i < count; ++i) {
            records[i].surface.mode = dContactApprox1;
            records[i].surface.mu = self->mu;
            dJointAttach(dJointCreateContact(self->world, self->contacts, &records[i]), b1, b2);
        }
        self->contactCount += count;
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

void setBodyRotation(dBodyID body, const Mat3& rotation) {
    dMatrix3 matrix;
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) matrix[4 * row + column] = rotation(row, column);
        matrix[4 * row + 3] = 0;
    }
    dBodySetRotation(body, matrix);
}

Vec3 bodyPosition(dBodyID body) { return toVec(dBodyGetPosition(body)); }

// Angle between the body's local z axis and the world's vertical.
double axisTilt(dBodyID body) { return std::acos(std::clamp(bodyRotation(body)(2, 2), -1.0, 1.0)); }

// Angle between the body's local z axis and the horizontal plane.
double axisElevation(dBodyID body) { return std::asin(std::min(1.0, std::abs(bodyRotation(body)(2, 2)))); }

double uniform(std::mt19937_64& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

// A rotation taking local z to the horizontal direction of `yaw`, tilted out of the horizontal by `tilt`.
Mat3 lyingRotation(double yaw, double tilt) {
    return rotationAbout(Vec3::UnitZ(), yaw) * rotationAbout(Vec3::UnitY(), M_PI / 2 + tilt);
}

// A standing rotation: local z tilted from the vertical by `tilt` about the horizontal direction `direction`.
Mat3 standingRotation(double tilt, double direction) {
    return rotationAbout(Vec3(std::cos(direction), std::sin(direction), 0), tilt);
}

// The static floors: the plane z ≤ 0, a box whose top is z = 0, a hull (an irregular octagonal
// slab, createConvex) whose top face is z = 0.
enum class Floor { Plane, Box, Hull };
const char* floorName(Floor floor) { return floor == Floor::Plane ? "plane" : floor == Floor::Box ? "box" : "hull"; }

dGeomID makeFloor(dSpaceID space, Floor floor) {
    switch (floor) {
        case Floor::Plane: return dCreatePlane(space, 0, 0, 1, 0);
        case Floor::Box: {
            dGeomID box = dCreateBox(space, 6, 6, 0.4);
            dGeomSetPosition(box, 0, 0, -0.2);
            return box;
        }
        case Floor::Hull: {
            std::vector<dReal> points;
            for (int i = 0; i < 8; ++i) {
                const double angle = 2 * M_PI * (i + 0.3) / 8;
                points.insert(points.end(), {3.0 * std::cos(angle), 3.0 * std::sin(angle), 0.0});
                const double lower = angle + 0.2;
                points.insert(points.end(), {2.6 * std::cos(lower), 2.6 * std::sin(lower), -0.5 - 0.05 * i});
            }
            return gdc::ode::createConvex(space, points.data(), 16);
        }
    }
    return nullptr;
}

// ---- A lying capsule ----

constexpr double kCapsuleRadius = 0.1, kCapsuleLength = 0.6;
constexpr double kCapsuleSinkLimit = 1e-3;  // m: how far its lowest point may go below the floor
constexpr double kSettleTime = 0.5;         // s before the 3 s measured

struct LyingResult {
    double worstSink = 0;  // m: most its lowest point went below the floor (z = 0) while measured
    double worstLift = 0;  // m: most its lowest point stood above the floor while measured
};

LyingResult capsuleLying(bool installGdcontact, Floor floor, unsigned long seed) {
    OdeSession session(installGdcontact);
    dRandSetSeed(seed);
    std::mt19937_64 rng(seed);
    World scene;
    makeFloor(scene.space, floor);
    dBodyID body = dBodyCreate(scene.world);
    dMass mass;
    dMassSetCapsuleTotal(&mass, 1.0, 3, kCapsuleRadius, kCapsuleLength);
    dBodySetMass(body, &mass);
    // Its axis within 0.1° of the horizontal, its lower end 0.5 mm above the floor.
    const double tilt = uniform(rng, -0.1, 0.1) * kDegree;
    setBodyRotation(body, lyingRotation(uniform(rng, 0, 2 * M_PI), tilt));
    dBodySetPosition(body, uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5),
                     kCapsuleRadius + 0.5 * kCapsuleLength * std::sin(std::abs(tilt)) + 5e-4);
    dGeomSetBody(dCreateCapsule(scene.space, kCapsuleRadius, kCapsuleLength), body);
    LyingResult result;
    const int settle = static_cast<int>(kSettleTime / kTimeStep);
    for (int step = 0; step < settle + 300; ++step) {
        scene.step(true);
        if (step < settle) continue;
        const Vec3 centre = bodyPosition(body), axis = bodyRotation(body) * Vec3::UnitZ();
        // The lowest point of a capsule: its lower end's sphere's bottom.
        const double lowest = centre.z() - 0.5 * kCapsuleLength * std::abs(axis.z()) - kCapsuleRadius;
        result.worstSink = std::max(result.worstSink, -lowest);
        result.worstLift = std::max(result.worstLift, lowest);
    }
    return result;
}

}  // namespace

TEST_CASE("a capsule lying on a box floor or a plane does not sink with gdcontact installed", "[curved][ode][capsule]") {
    // It starts 0.5 mm above the floor, its axis within 0.1° of the horizontal; after 0.5 s its
    // lowest point stays within kCapsuleSinkLimit of the floor for 3 s. (Capsule–plane stays with
    // ODE's own collider when gdcontact is installed: the plane is the control.)
    for (Floor floor : {Floor::Box, Floor::Plane}) {
        double worstOurs = 0, worstOde = 0, worstOursLift = 0;
        for (unsigned long seed = 1; seed <= kSeeds; ++seed) {
            const LyingResult ours = capsuleLying(true, floor, seed);
            const LyingResult theirs = capsuleLying(false, floor, seed);
            INFO(floorName(floor) << " seed " << seed << ": sunk " << ours.worstSink * 1e3 << " mm, lifted "
                                  << ours.worstLift * 1e3 << " mm");
            CHECK(ours.worstSink < kCapsuleSinkLimit);
            CHECK(ours.worstLift < kCapsuleSinkLimit);
            worstOurs = std::max(worstOurs, ours.worstSink);
            worstOursLift = std::max(worstOursLift, ours.worstLift);
            worstOde = std::max(worstOde, theirs.worstSink);
        }
        WARN("capsule r 0.1 length 0.6 lying on a " << floorName(floor) << ", 3 s after 0.5 s, " << kSeeds
                                                    << " seeds: its lowest point at most below the floor: gdcontact "
                                                    << worstOurs * 1e3 << " mm (above: " << worstOursLift * 1e3
                                                    << " mm), ODE's own " << worstOde * 1e3 << " mm");
    }
}

// ---- A standing cylinder ----

namespace {

constexpr double kCylinderRadius = 0.2, kCylinderLength = 0.5;
constexpr double kUprightLimit = 1.0 * kDegree;

struct StandingResult {
    double worstTilt = 0;  // rad, over the whole run
    double drift = 0;      // m, horizontal, from the start
};

StandingResult cylinderStanding(bool installGdcontact, Floor floor, unsigned long seed) {
    OdeSession session(installGdcontact);
    dRandSetSeed(seed);
    std::mt19937_64 rng(seed);
    World scene;
    makeFloor(scene.space, floor);
    dBodyID body = dBodyCreate(scene.world);
    dMass mass;
    dMassSetCylinderTotal(&mass, 1.0, 3, kCylinderRadius, kCylinderLength);
    dBodySetMass(body, &mass);
    setBodyRotation(body, standingRotation(uniform(rng, 0, 0.3) * kDegree, uniform(rng, 0, 2 * M_PI)) *
                              rotationAbout(Vec3::UnitZ(), uniform(rng, 0, 2 * M_PI)));
    const Vec3 start(uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5), 0.5 * kCylinderLength + 0.002);
    dBodySetPosition(body, start.x(), start.y(), start.z());
    dGeomSetBody(dCreateCylinder(scene.space, kCylinderRadius, kCylinderLength), body);
    StandingResult result;
    for (int step = 0; step < 300; ++step) {
        scene.step(true);
        result.worstTilt = std::max(result.worstTilt, axisTilt(body));
    }
    const Vec3 end = bodyPosition(body);
    result.drift = std::hypot(end.x() - start.x(), end.y() - start.y());
    return result;
}

}  // namespace

TEST_CASE("a standing cylinder on a box floor or a hull floor stays upright with gdcontact installed",
          "[curved][ode][cylinder]") {
    for (Floor floor : {Floor::Box, Floor::Hull}) {
        double worstOurs = 0, worstOde = 0, driftOurs = 0, driftOde = 0;
        for (unsigned long seed = 1; seed <= kSeeds; ++seed) {
            const StandingResult ours = cylinderStanding(true, floor, seed);
            const StandingResult theirs = cylinderStanding(false, floor, seed);
            INFO(floorName(floor) << " seed " << seed << ": tilt " << ours.worstTilt / kDegree << "°");
            CHECK(ours.worstTilt < kUprightLimit);
            worstOurs = std::max(worstOurs, ours.worstTilt);
            worstOde = std::max(worstOde, theirs.worstTilt);
            driftOurs = std::max(driftOurs, ours.drift);
            driftOde = std::max(driftOde, theirs.drift);
        }
        WARN("cylinder r 0.2 length 0.5 standing on a " << floorName(floor) << ", 3 s, " << kSeeds
                                                        << " seeds: most tilt gdcontact " << worstOurs / kDegree
                                                        << "°, ODE's own " << worstOde / kDegree << "°; drift "
                                                        << driftOurs * 1e3 << " mm, ODE's own " << driftOde * 1e3 << " mm");
    }
}

// ---- A box–cylinder–box stack ----

namespace {

struct StackResult {
    double worstTilt = 0;  // rad: the largest tilt of the three bodies over the run
    double topDrift = 0;   // m: the top box's horizontal displacement from its start
    double topSag = 0;     // m: how far the top box ended below its start height (> 0: lower)
};

StackResult boxCylinderBox(bool installGdcontact, bool quick, unsigned long seed) {
    OdeSession session(installGdcontact);
    dRandSetSeed(seed);
    std::mt19937_64 rng(seed);
    World scene;
    makeFloor(scene.space, Floor::Box);
    const double boxSide = 0.8, boxHeight = 0.3, radius = 0.3, length = 0.5;
    auto jitter = [&] { return Vec3(uniform(rng, -0.005, 0.005), uniform(rng, -0.005, 0.005), 0.0); };
    auto tiltJitter = [&]() -> Mat3 {
        return standingRotation(uniform(rng, 0, 0.2) * kDegree, uniform(rng, 0, 2 * M_PI)) *
               rotationAbout(Vec3::UnitZ(), uniform(rng, -5, 5) * kDegree);
    };
    dBodyID bodies[3];
    const double heights[3] = {0.5 * boxHeight + 0.001, boxHeight + 0.5 * length + 0.003,
                               boxHeight + length + 0.5 * boxHeight + 0.005};
    for (int i = 0; i < 3; ++i) {
        bodies[i] = dBodyCreate(scene.world);
        dMass mass;
        if (i == 1)
            dMassSetCylinderTotal(&mass, 1.0, 3, radius, length);
        else
            dMassSetBoxTotal(&mass, 1.0, boxSide, boxSide, boxHeight);
        dBodySetMass(bodies[i], &mass);
        const Vec3 at = jitter() + Vec3(0, 0, heights[i]);
        dBodySetPosition(bodies[i], at.x(), at.y(), at.z());
        setBodyRotation(bodies[i], tiltJitter());
        dGeomSetBody(i == 1 ? dCreateCylinder(scene.space, radius, length) : dCreateBox(scene.space, boxSide, boxSide, boxHeight),
                     bodies[i]);
    }
    const Vec3 topStart = bodyPosition(bodies[2]);
    StackResult result;
    for (int step = 0; step < 300; ++step) {
        scene.step(quick);
        for (dBodyID body : bodies) {
            // A box's tilt: its local z against the vertical, as the cylinder's.
            result.worstTilt = std::max(result.worstTilt, axisTilt(body));
        }
    }
    const Vec3 topEnd = bodyPosition(bodies[2]);
    result.topDrift = std::hypot(topEnd.x() - topStart.x(), topEnd.y() - topStart.y());
    result.topSag = topStart.z() - topEnd.z();
    return result;
}

}  // namespace

TEST_CASE("a box-cylinder-box stack stands 3 s with gdcontact installed", "[curved][ode][stack]") {
    // Standing: every body within 1° of upright throughout, the top box within 1 cm of where it
    // started horizontally and no lower than 1 cm below its start (it starts 5 mm high).
    for (bool quick : {true, false}) {
        double worstTilt = 0, worstDrift = 0, odeTilt = 0, odeDrift = 0;
        for (unsigned long seed = 1; seed <= (quick ? kSeeds : 2); ++seed) {
            const StackResult ours = boxCylinderBox(true, quick, seed);
            const StackResult theirs = boxCylinderBox(false, quick, seed);
            INFO((quick ? "dWorldQuickStep" : "dWorldStep") << " seed " << seed << ": tilt " << ours.worstTilt / kDegree
                                                            << "°, drift " << ours.topDrift * 1e3 << " mm, sag "
                                                            << ours.topSag * 1e3 << " mm");
            CHECK(ours.worstTilt < 1.0 * kDegree);
            CHECK(ours.topDrift < 0.01);
            CHECK(ours.topSag < 0.01);
            worstTilt = std::max(worstTilt, ours.worstTilt);
            worstDrift = std::max(worstDrift, ours.topDrift);
            odeTilt = std::max(odeTilt, theirs.worstTilt);
            odeDrift = std::max(odeDrift, theirs.topDrift);
        }
        WARN("box-cylinder-box stack, " << (quick ? "dWorldQuickStep" : "dWorldStep") << ": most tilt gdcontact "
                                        << worstTilt / kDegree << "°, top drift " << worstDrift * 1e3 << " mm; ODE's own "
                                        << odeTilt / kDegree << "°, " << odeDrift * 1e3 << " mm");
    }
}

// ---- A lying cylinder rolling ----

namespace {

constexpr double kHeadingDriftPerMetre = 0.1 * kDegree;  // rad per metre travelled

struct RollResult {
    double distance = 0;        // m travelled (horizontal)
    double headingChange = 0;   // rad: the axis' yaw at the end against the start
    double lateral = 0;         // m: the final offset from the start line
};

RollResult rollingCylinder(bool installGdcontact, unsigned long seed) {
    OdeSession session(installGdcontact);
    dRandSetSeed(seed);
    std::mt19937_64 rng(seed);
    World scene;
    makeFloor(scene.space, Floor::Plane);
    const double radius = 0.2, length = 0.4, spin = 10.0;
    dBodyID body = dBodyCreate(scene.world);
    dMass mass;
    dMassSetCylinderTotal(&mass, 1.0, 3, radius, length);
    dBodySetMass(body, &mass);
    // The axis horizontal along `yaw` + 90°; it rolls along `yaw`.
    const double yaw = uniform(rng, 0, 2 * M_PI);
    const Vec3 heading(std::cos(yaw), std::sin(yaw), 0), axis(-std::sin(yaw), std::cos(yaw), 0);
    setBodyRotation(body, lyingRotation(yaw + M_PI / 2, 0.0));
    const Vec3 start(uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5), radius);
    dBodySetPosition(body, start.x(), start.y(), start.z());
    // Rolling without slipping: ω along the axis, v = ω × (centre − contact) = ω·r along `heading`.
    const Vec3 angular = spin * axis;  // ω × (0, 0, r) = spin·r·(axis × z)
    const Vec3 linear = angular.cross(Vec3(0, 0, radius));
    dBodySetAngularVel(body, angular.x(), angular.y(), angular.z());
    dBodySetLinearVel(body, linear.x(), linear.y(), linear.z());
    dGeomSetBody(dCreateCylinder(scene.space, radius, length), body);
    const Vec3 direction = heading;
    for (int step = 0; step < 300; ++step) scene.step(true);
    const Vec3 end = bodyPosition(body);
    const Vec3 endAxis = bodyRotation(body) * Vec3::UnitZ();
    RollResult result;
    result.distance = std::hypot(end.x() - start.x(), end.y() - start.y());
    const Vec3 flatAxis(endAxis.x(), endAxis.y(), 0);
    // The axis may have turned end for end: the heading change is the angle between the lines.
    result.headingChange = std::acos(std::min(1.0, std::abs(flatAxis.normalized().dot(axis))));
    const Vec3 moved = end - start;
    result.lateral = std::abs(moved.x() * direction.y() - moved.y() * direction.x());
    return result;
}

}  // namespace

TEST_CASE("a lying cylinder rolls straight on a plane with gdcontact installed", "[curved][ode][rolling]") {
    // Radius 0.2, length 0.4, rolling at 10 rad/s (2 m/s) for 3 s: its heading may drift by less
    // than kHeadingDriftPerMetre per metre travelled.
    double worstOurs = 0, worstOde = 0, lateralOurs = 0, lateralOde = 0, shortest = INFINITY;
    for (unsigned long seed = 1; seed <= kSeeds; ++seed) {
        const RollResult ours = rollingCylinder(true, seed);
        const RollResult theirs = rollingCylinder(false, seed);
        INFO("seed " << seed << ": " << ours.distance << " m, heading change " << ours.headingChange / kDegree << "°, lateral "
                     << ours.lateral * 1e3 << " mm");
        REQUIRE(ours.distance > 3.0);  // it rolled
        CHECK(ours.headingChange / ours.distance < kHeadingDriftPerMetre);
        worstOurs = std::max(worstOurs, ours.headingChange / ours.distance);
        worstOde = std::max(worstOde, theirs.headingChange / std::max(theirs.distance, 1e-9));
        lateralOurs = std::max(lateralOurs, ours.lateral);
        lateralOde = std::max(lateralOde, theirs.lateral);
        shortest = std::min(shortest, ours.distance);
    }
    WARN("lying cylinder rolling 3 s on a plane (" << shortest << " m or more): heading drift gdcontact "
                                                   << worstOurs / kDegree << "°/m, lateral " << lateralOurs * 1e3
                                                   << " mm; ODE's own " << worstOde / kDegree << "°/m, lateral "
                                                   << lateralOde * 1e3 << " mm");
}

// ---- Tipping a standing cylinder ----

namespace {

constexpr double kTipRadius = 0.2, kTipHeight = 0.6, kTipMass = 1.0;
constexpr double kTipForceError = 0.05;  // e: no tip at (1 − e)·F*, a tip at (1 + e)·F* (0.1 asked first; 0.05 holds)
constexpr double kTippedAngle = 20 * kDegree;

// The cylinder standing on a box floor, μ = ∞, under dWorldStep; after 0.5 s of settling the force
// `force` pushes horizontally along `direction` at the centre of its top cap for 3 s. Returns the
// largest tilt while pushed.
double pushedTilt(bool installGdcontact, double force, double direction) {
    OdeSession session(installGdcontact);
    dRandSetSeed(1);
    World scene;
    scene.mu = dInfinity;
    makeFloor(scene.space, Floor::Box);
    dBodyID body = dBodyCreate(scene.world);
    dMass mass;
    dMassSetCylinderTotal(&mass, kTipMass, 3, kTipRadius, kTipHeight);
    dBodySetMass(body, &mass);
    dBodySetPosition(body, 0, 0, 0.5 * kTipHeight);
    dGeomSetBody(dCreateCylinder(scene.space, kTipRadius, kTipHeight), body);
    for (int step = 0; step < 50; ++step) scene.step(false);
    double worst = 0;
    for (int step = 0; step < 300; ++step) {
        dVector3 top;
        dBodyGetRelPointPos(body, 0, 0, 0.5 * kTipHeight, top);
        dBodyAddForceAtPos(body, force * std::cos(direction), force * std::sin(direction), 0, top[0], top[1], top[2]);
        scene.step(false);
        worst = std::max(worst, axisTilt(body));
        if (worst > kTippedAngle) break;
    }
    return worst;
}

// The tipping force by bisection, as a fraction of m·g·r/h.
double tippingRatio(bool installGdcontact, double direction) {
    const double analytic = kTipMass * kGravity * kTipRadius / kTipHeight;
    double low = 0.6, high = 1.4;
    if (pushedTilt(installGdcontact, high * analytic, direction) <= kTippedAngle) return INFINITY;
    if (pushedTilt(installGdcontact, low * analytic, direction) > kTippedAngle) return 0;
    for (int i = 0; i < 10; ++i) {
        const double middle = 0.5 * (low + high);
        (pushedTilt(installGdcontact, middle * analytic, direction) > kTippedAngle ? high : low) = middle;
    }
    return 0.5 * (low + high);
}

}  // namespace

TEST_CASE("a standing cylinder pushed at its top tips within the stated error of m*g*r/h in every push direction",
          "[curved][ode][tipping]") {
    const double analytic = kTipMass * kGravity * kTipRadius / kTipHeight;
    std::ostringstream figures;
    figures.precision(4);
    for (double degrees : {0.0, 22.5, 45.0, 67.5}) {
        const double direction = degrees * kDegree;
        const double below = pushedTilt(true, (1 - kTipForceError) * analytic, direction);
        const double above = pushedTilt(true, (1 + kTipForceError) * analytic, direction);
        INFO("push at " << degrees << "°: tilt at (1 - e)F* " << below / kDegree << "°, at (1 + e)F* " << above / kDegree << "°");
        CHECK(below < 2 * kDegree);
        CHECK(above > kTippedAngle);
        figures << "\n  " << degrees << "°: gdcontact tips at " << tippingRatio(true, direction) << "·F*, ODE's own at "
                << tippingRatio(false, direction) << "·F*";
    }
    WARN("standing cylinder r 0.2 h 0.6 pushed at its top (F* = m g r / h = " << analytic << " N), dWorldStep, mu = inf:"
                                                                               << figures.str());
}

// ---- The contract of every contact ----

namespace {

enum class Geom { Box, Convex, Plane, Cylinder, Capsule, Sphere, FlatCapsule };
const char* geomName(Geom g) {
    switch (g) {
        case Geom::Box: return "box";
        case Geom::Convex: return "convex";
        case Geom::Plane: return "plane";
        case Geom::Cylinder: return "cylinder";
        case Geom::Capsule: return "capsule";
        case Geom::Sphere: return "sphere";
        case Geom::FlatCapsule: return "capsule of length 0";
    }
    return "?";
}

dGeomID makeGeom(Geom g, std::mt19937_64& rng) {
    switch (g) {
        case Geom::Box: return dCreateBox(0, uniform(rng, 0.1, 1.5), uniform(rng, 0.1, 1.5), uniform(rng, 0.1, 1.5));
        case Geom::Convex: {
            // 8..20 points: one on each half axis (ODE's convex collider wants the origin inside)
            // and 2..14 in random directions.
            std::vector<dReal> points;
            const int count = std::uniform_int_distribution<int>(8, 20)(rng);
            std::normal_distribution<double> gauss;
            for (int i = 0; i < count; ++i) {
                const Vec3 direction = i < 6 ? Vec3::Unit(i / 2) * (i % 2 ? -1.0 : 1.0)
                                             : Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
                const Vec3 p = direction * uniform(rng, 0.3, 0.6);
                points.insert(points.end(), {p.x(), p.y(), p.z()});
            }
            return gdc::ode::createConvex(0, points.data(), static_cast<unsigned>(count));
        }
        case Geom::Plane: return dCreatePlane(0, 0, 0, 1, uniform(rng, -0.3, 0.3));
        case Geom::Cylinder: return dCreateCylinder(0, uniform(rng, 0.02, 1.0), uniform(rng, 0.05, 2.0));
        case Geom::Capsule: return dCreateCapsule(0, uniform(rng, 0.02, 1.0), uniform(rng, 0.05, 2.0));
        case Geom::Sphere: return dCreateSphere(0, uniform(rng, 0.02, 1.0));
        case Geom::FlatCapsule: return dCreateCapsule(0, uniform(rng, 0.02, 1.0), 0.0);
    }
    return nullptr;
}

}  // namespace

TEST_CASE("every contact dCollide returns for the curved pairs is finite with a unit normal and a depth of at least 0",
          "[curved][ode][contract]") {
    OdeSession session(true);
    std::mt19937_64 rng(3340);
    const std::pair<Geom, Geom> pairs[] = {
        {Geom::Cylinder, Geom::Box},     {Geom::Cylinder, Geom::Convex}, {Geom::Cylinder, Geom::Plane},
        {Geom::Cylinder, Geom::Cylinder}, {Geom::Capsule, Geom::Box},    {Geom::Capsule, Geom::Convex},
        {Geom::Capsule, Geom::Cylinder}, {Geom::Sphere, Geom::Convex},  {Geom::FlatCapsule, Geom::Box},
        {Geom::FlatCapsule, Geom::Cylinder}};
    for (const auto& [first, second] : pairs) {
        long total = 0, withContacts = 0;
        int worstProblems = 0;
        std::string problem;
        for (int i = 0; i < 300; ++i) {
            dGeomID a = makeGeom(first, rng), b = makeGeom(second, rng);
            for (dGeomID g : {a, b}) {
                if (dGeomGetClass(g) == dPlaneClass) continue;
                setPose(g, Pose{randomRotation(rng), Vec3(uniform(rng, -0.6, 0.6), uniform(rng, -0.6, 0.6), uniform(rng, -0.6, 0.6))});
            }
            for (int order = 0; order < 2; ++order) {
                dGeomID o1 = order ? b : a, o2 = order ? a : b;
                if (dGeomGetClass(o1) == dPlaneClass) continue;  // ODE takes a plane only second
                const auto contacts = collideThroughOde(o1, o2, 16);
                ++total;
                if (!contacts.empty()) ++withContacts;
                for (const dContactGeom& c : contacts) {
                    const Vec3 normal = toVec(c.normal), position = toVec(c.pos);
                    std::ostringstream out;
                    if (!position.allFinite() || !normal.allFinite() || !std::isfinite(c.depth))
                        out << "non-finite contact";
                    else if (std::abs(normal.norm() - 1) > realTolerance(1e-9))
                        out << "normal of length " << normal.norm();
                    else if (c.depth < 0)
                        out << "depth " << c.depth;
                    else if (c.g1 != o1 || c.g2 != o2)
                        out << "g1, g2 not the geoms as passed";
                    if (!out.str().empty()) {
                        if (worstProblems++ == 0)
                            problem = std::string(geomName(order ? second : first)) + "-" + geomName(order ? first : second) +
                                      ": " + out.str();
                    }
                }
            }
            dGeomDestroy(a);
            dGeomDestroy(b);
        }
        INFO(geomName(first) << "-" << geomName(second) << ": " << withContacts << " of " << total
                             << " queries with contacts; first problem: " << problem);
        CHECK(worstProblems == 0);
        CHECK(withContacts > total / 10);  // the poses do overlap often
    }
}

TEST_CASE("with gdcontact installed a standing cylinder's cap contacts on a box lie within the cylinder",
          "[curved][ode][contract]") {
    // ODE's own cylinder-box puts them on an octagon circumscribing the cap (up to 8 % of the
    // radius outside); gdcontact's lie on the cap's disc. Printed: how far outside each one's are.
    double outside[2] = {0, 0};
    int counts[2] = {0, 0};
    for (int installed = 0; installed < 2; ++installed) {
        OdeSession session(installed == 1);
        std::mt19937_64 rng(3341);
        for (int i = 0; i < 50; ++i) {
            const double radius = uniform(rng, 0.05, 1.0), length = uniform(rng, 0.1, 1.0);
            dGeomID cylinder = dCreateCylinder(0, radius, length);
            dGeomID box = dCreateBox(0, 6, 6, 1);
            dGeomSetPosition(box, 0, 0, -0.5);
            const Mat3 rotation = standingRotation(uniform(rng, 0, 0.005), uniform(rng, 0, 2 * M_PI)) *
                                  rotationAbout(Vec3::UnitZ(), uniform(rng, 0, 2 * M_PI));
            const Vec3 centre(uniform(rng, -1, 1), uniform(rng, -1, 1), 0.5 * length - 0.01 * radius);
            setPose(cylinder, Pose{rotation, centre});
            const auto contacts = collideThroughOde(cylinder, box, 16);
            counts[installed] = std::max(counts[installed], static_cast<int>(contacts.size()));
            const Vec3 axis = rotation * Vec3::UnitZ();
            for (const dContactGeom& c : contacts) {
                // The cylinder's surface point is pos ± depth/2·normal (pos lies midway): the nearer one.
                double least = INFINITY;
                for (double side : {-0.5, 0.5}) {
                    const Vec3 offset = toVec(c.pos) + side * c.depth * toVec(c.normal) - centre;
                    least = std::min(least, (offset - offset.dot(axis) * axis).norm());
                }
                outside[installed] = std::max(outside[installed], (least - radius) / radius);
            }
            if (installed == 1) {
                INFO("cylinder r " << radius << " length " << length << ": " << contacts.size() << " contacts");
                CHECK(contacts.size() >= 3);
            }
            dGeomDestroy(cylinder);
            dGeomDestroy(box);
        }
    }
    WARN("standing cylinder on a box, cap contacts' distance from the axis beyond the radius: gdcontact "
         << outside[1] << "·r (up to " << counts[1] << " contacts), ODE's own " << outside[0] << "·r (up to " << counts[0]
         << " contacts)");
    CHECK(outside[1] <= realTolerance(1e-6));
}

// The 10-high stack of unit cubes on a plane, built three ways, under dWorldStep or
// dWorldQuickStep: the scene of samples/ode_stack and of the ODE world tests (header-only so
// that both measure exactly the same thing).
#pragma once

#include <gdcontact/ode.hpp>

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace gdc::ode::scenes {

enum class StackCollider {
    OdeBoxes,   ///< dBox geoms, ODE's own dBoxBox / box–plane colliders
    OdeConvex,  ///< createConvex cubes, ODE's own convex colliders (libccd MPR for convex–convex)
    Gdcontact,  ///< createConvex cubes, gdcontact installed
};

enum class Solver { Step, QuickStep };

struct StackOptions {
    int height = 10;
    double seconds = 20.0;
    double timeStep = 0.01;
    int quickStepIterations = 20;
    int contactsPerPair = 4;
    /// Drift, twist and sag are measured from the poses at this time (the stack has settled).
    double settleSeconds = 2.0;
    /// Each cube starts sunk this far (m) into the one below. ODE's dWorldStep (Dantzig LCP)
    /// reports "LCP internal error" and lets a 10-stack collapse when every contact of the first
    /// step has depth exactly 0, whichever collider made them; a small overlap avoids that.
    double initialOverlap = 1e-4;
    /// Seed of ODE's random generator, which dWorldQuickStep uses to shuffle constraints.
    unsigned long randomSeed = 1;
};

struct StackResult {
    double driftMm = 0;   ///< largest horizontal displacement of a cube since it settled (mm)
    double twistDeg = 0;  ///< largest rotation of a cube about the vertical since it settled (deg)
    double sagMm = 0;     ///< largest vertical displacement of a cube since it settled (mm)
    bool standing = true; ///< every cube still above the one below (no cube fell off)
};

namespace detail {

struct StackWorld {
    dWorldID world;
    dJointGroupID contacts;
    int contactsPerPair;
};

inline void addContacts(void* data, dGeomID o1, dGeomID o2) {
    auto* scene = static_cast<StackWorld*>(data);
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    std::vector<dContact> records(static_cast<std::size_t>(scene->contactsPerPair));
    const int count = dCollide(o1, o2, scene->contactsPerPair, &records[0].geom, sizeof(dContact));
    for (int i = 0; i < count; ++i) {
        dContact& contact = records[static_cast<std::size_t>(i)];
        contact.surface.mode = dContactApprox1;  // friction pyramid scaled by the normal force
        contact.surface.mu = 0.8;
        dJointAttach(dJointCreateContact(scene->world, scene->contacts, &contact), b1, b2);
    }
}

// Rotation about the vertical of a body since `start` (radians, signed).
inline double yawSince(const dReal* start, const dReal* now) {
    // x axes (first columns of the 3x4 row-major matrices) projected onto the ground plane.
    const double startAngle = std::atan2(start[4], start[0]);
    const double nowAngle = std::atan2(now[4], now[0]);
    return std::remainder(nowAngle - startAngle, 2 * M_PI);
}

}  // namespace detail

/// Builds the stack in a fresh ODE session (dInitODE2 … dCloseODE), runs it and measures it.
/// Cube i (side 1 m, 1 kg) starts on cube i−1 (sunk options.initialOverlap into it), shifted by up
/// to 2 cm and turned by up to 5° about the vertical (a fixed pattern, so every run is the same);
/// ERP 0.2, CFM 1e-5, μ 0.8 (friction pyramid). Measures from options.settleSeconds to the end.
inline StackResult runStack(StackCollider collider, Solver solver, const StackOptions& options = {}) {
    dInitODE2(0);
    if (collider == StackCollider::Gdcontact) install();
    dRandSetSeed(options.randomSeed);  // QuickStep shuffles constraints with ODE's generator: same sequence every run
    detail::StackWorld scene{dWorldCreate(), dJointGroupCreate(0), options.contactsPerPair};
    dWorldSetGravity(scene.world, 0, 0, -9.81);
    dWorldSetERP(scene.world, 0.2);
    dWorldSetCFM(scene.world, 1e-5);
    dWorldSetQuickStepNumIterations(scene.world, options.quickStepIterations);
    dSpaceID space = dSimpleSpaceCreate(0);
    dCreatePlane(space, 0, 0, 1, 0);

    std::vector<dReal> corners;
    for (int i = 0; i < 8; ++i)
        for (int axis = 0; axis < 3; ++axis) corners.push_back((i >> axis & 1) ? 0.5 : -0.5);
    std::vector<dBodyID> bodies;
    for (int level = 0; level < options.height; ++level) {
        dBodyID body = dBodyCreate(scene.world);
        dMass mass;
        dMassSetBoxTotal(&mass, 1.0, 1, 1, 1);
        dBodySetMass(body, &mass);
        dBodySetPosition(body, 0.02 * std::sin(1.7 * level), 0.02 * std::cos(2.3 * level), 0.5 + level * (1.0 - options.initialOverlap));
        dMatrix3 rotation;
        dRFromAxisAndAngle(rotation, 0, 0, 1, 5.0 * M_PI / 180.0 * std::sin(0.9 * level));
        dBodySetRotation(body, rotation);
        dGeomID geom = collider == StackCollider::OdeBoxes ? dCreateBox(space, 1, 1, 1)
                                                           : createConvex(space, corners.data(), 8);
        dGeomSetBody(geom, body);
        bodies.push_back(body);
    }
    std::vector<std::vector<dReal>> startPositions, settledPositions, settledRotations;
    for (dBodyID body : bodies) startPositions.emplace_back(dBodyGetPosition(body), dBodyGetPosition(body) + 3);

    const int steps = static_cast<int>(std::lround(options.seconds / options.timeStep));
    const int settleSteps = static_cast<int>(std::lround(options.settleSeconds / options.timeStep));
    for (int step = 0; step < steps; ++step) {
        if (step == settleSteps)
            for (dBodyID body : bodies) {
                settledPositions.emplace_back(dBodyGetPosition(body), dBodyGetPosition(body) + 3);
                settledRotations.emplace_back(dBodyGetRotation(body), dBodyGetRotation(body) + 12);
            }
        dSpaceCollide(space, &scene, &detail::addContacts);
        if (solver == Solver::Step)
            dWorldStep(scene.world, options.timeStep);
        else
            dWorldQuickStep(scene.world, options.timeStep);
        dJointGroupEmpty(scene.contacts);
    }

    StackResult result;
    for (std::size_t i = 0; i < bodies.size() && !settledPositions.empty(); ++i) {
        const dReal* position = dBodyGetPosition(bodies[i]);
        const double horizontal = std::hypot(position[0] - settledPositions[i][0], position[1] - settledPositions[i][1]);
        result.driftMm = std::max(result.driftMm, 1000.0 * horizontal);
        result.sagMm = std::max(result.sagMm, 1000.0 * std::abs(position[2] - settledPositions[i][2]));
        const double yaw = detail::yawSince(settledRotations[i].data(), dBodyGetRotation(bodies[i]));
        result.twistDeg = std::max(result.twistDeg, std::abs(yaw) * 180.0 / M_PI);
        const double fromStart = std::hypot(position[0] - startPositions[i][0], position[1] - startPositions[i][1]);
        if (!std::isfinite(fromStart) || fromStart > 0.5 || position[2] < startPositions[i][2] - 0.5)
            result.standing = false;
    }
    dSpaceDestroy(space);  // destroys the geoms (and releases gdcontact's hulls)
    dJointGroupDestroy(scene.contacts);
    dWorldDestroy(scene.world);
    dCloseODE();
    return result;
}

}  // namespace gdc::ode::scenes

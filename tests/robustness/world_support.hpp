// ODE worlds for the robustness tests: a list of boxes on a ground plane, stepped with dWorldStep
// or dWorldQuickStep, with gdcontact installed or with ODE's own colliders (the dBox reference),
// measured with the quality measures of the design notes (drift, tilt, sag after settling).
#pragma once

#include <gdcontact/ode.hpp>

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace gdc::robustness {

enum class Collider {
    OdeBoxes,   ///< dBox geoms with ODE's own dBoxBox / box–plane (the reference)
    Gdcontact,  ///< the same dBox geoms with gdcontact installed
};
enum class Solver { Step, QuickStep };

struct BodySpec {
    Vec3 halfExtents;
    double mass;
    Pose pose;
    int restsOn = -1;  ///< index of the body it rests on (−1: the ground), for the tunnelling check
};

struct WorldOptions {
    double gravity = 9.81;      ///< m/s², scaled with the scene
    Vec3 planeOrigin = Vec3::Zero();  ///< a point of the ground plane (normal +z)
    double seconds = 10.0;
    double timeStep = 0.01;
    int quickStepIterations = 20;
    int contactsPerPair = 8;
    double settleSeconds = 2.0;  ///< measures are taken from here to the end
    unsigned long randomSeed = 1;  ///< ODE's generator (QuickStep shuffles constraints with it)
};

struct WorldResult {
    double drift = 0;     ///< largest horizontal displacement of a body since settling (m)
    double sag = 0;       ///< largest vertical displacement since settling (m)
    double tilt = 0;      ///< largest angle between a body axis and the vertical after settling (rad)
    double twist = 0;     ///< largest rotation about the vertical since settling (rad)
    double worstNormalAngle = 0;  ///< largest angle of a contact normal from the vertical after settling (rad)
    bool standing = true;  ///< no body moved more than half its height from where it started, no NaN
    bool ordered = true;   ///< every body stays above what it rests on (no tunnelling)
};

namespace detail {

struct WorldState {
    dWorldID world;
    dJointGroupID contacts;
    int contactsPerPair;
    bool measuring = false;
    double worstNormalAngle = 0;
};

inline void addContacts(void* data, dGeomID o1, dGeomID o2) {
    auto* state = static_cast<WorldState*>(data);
    std::vector<dContact> records(static_cast<std::size_t>(state->contactsPerPair));
    const int count = dCollide(o1, o2, state->contactsPerPair, &records[0].geom, sizeof(dContact));
    for (int i = 0; i < count; ++i) {
        dContact& contact = records[static_cast<std::size_t>(i)];
        if (state->measuring) {
            const Vec3 normal(contact.geom.normal[0], contact.geom.normal[1], contact.geom.normal[2]);
            state->worstNormalAngle = std::max(state->worstNormalAngle, std::atan2(normal.head<2>().norm(), std::abs(normal.z())));
        }
        contact.surface.mode = dContactApprox1;
        contact.surface.mu = 0.8;
        dJointAttach(dJointCreateContact(state->world, state->contacts, &contact), dGeomGetBody(o1), dGeomGetBody(o2));
    }
}

inline Mat3 rotationOf(dBodyID body) {
    const dReal* r = dBodyGetRotation(body);
    Mat3 m;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column) m(row, column) = r[4 * row + column];
    return m;
}

// Angle between the body axis closest to the vertical and the vertical.
inline double tiltOf(const Mat3& rotation) {
    double best = 0;
    for (int axis = 0; axis < 3; ++axis) best = std::max(best, std::abs(rotation(2, axis)));
    return std::acos(std::min(1.0, best));
}

}  // namespace detail

/// The settings runWorld installs: gdc::ode::defaultSettings(), its maxContacts replaced by
/// GDCONTACT_ROBUSTNESS_MAX_CONTACTS where that is set (install() refuses a value outside 1..16),
/// to see what another budget does to a world (docs/install.md, "Single precision: 8 points a
/// face"); the tests' limits are for the defaults.
inline gdc::Settings worldSettings() {
    gdc::Settings settings = gdc::ode::defaultSettings();
    if (const char* text = std::getenv("GDCONTACT_ROBUSTNESS_MAX_CONTACTS"); text && *text)
        settings.maxContacts = static_cast<int>(std::strtol(text, nullptr, 10));
    return settings;
}

/// Runs the bodies (each a box of the given half extents and mass at its start pose) on a ground
/// plane in a fresh ODE session (dInitODE2 … dCloseODE): ERP 0.2, CFM 1e-5, μ 0.8 (friction
/// pyramid), gravity −z.
inline WorldResult runWorld(const std::vector<BodySpec>& specs, Collider collider, Solver solver,
                            const WorldOptions& options = {}) {
    dInitODE2(0);
    if (collider == Collider::Gdcontact) gdc::ode::install(worldSettings());
    dRandSetSeed(options.randomSeed);
    detail::WorldState state{dWorldCreate(), dJointGroupCreate(0), options.contactsPerPair};
    dWorldSetGravity(state.world, 0, 0, -options.gravity);
    dWorldSetERP(state.world, 0.2);
    dWorldSetCFM(state.world, 1e-5);
    dWorldSetQuickStepNumIterations(state.world, options.quickStepIterations);
    dSpaceID space = dSimpleSpaceCreate(0);
    dCreatePlane(space, 0, 0, 1, options.planeOrigin.z());
    std::vector<dBodyID> bodies;
    for (const BodySpec& spec : specs) {
        dBodyID body = dBodyCreate(state.world);
        dMass mass;
        dMassSetBoxTotal(&mass, spec.mass, 2 * spec.halfExtents.x(), 2 * spec.halfExtents.y(), 2 * spec.halfExtents.z());
        dBodySetMass(body, &mass);
        dBodySetPosition(body, spec.pose.position.x(), spec.pose.position.y(), spec.pose.position.z());
        dMatrix3 rotation;
        for (int row = 0; row < 3; ++row) {
            for (int column = 0; column < 3; ++column) rotation[4 * row + column] = spec.pose.rotation(row, column);
            rotation[4 * row + 3] = 0;
        }
        dBodySetRotation(body, rotation);
        dGeomID geom = dCreateBox(space, 2 * spec.halfExtents.x(), 2 * spec.halfExtents.y(), 2 * spec.halfExtents.z());
        dGeomSetBody(geom, body);
        bodies.push_back(body);
    }
    std::vector<Vec3> settledPositions;
    std::vector<Mat3> settledRotations;
    WorldResult result;
    const int steps = static_cast<int>(std::lround(options.seconds / options.timeStep));
    const int settleSteps = static_cast<int>(std::lround(options.settleSeconds / options.timeStep));
    auto positionOf = [](dBodyID body) {
        const dReal* p = dBodyGetPosition(body);
        return Vec3(p[0], p[1], p[2]);
    };
    for (int step = 0; step < steps; ++step) {
        if (step == settleSteps) {
            state.measuring = true;
            for (dBodyID body : bodies) {
                settledPositions.push_back(positionOf(body));
                settledRotations.push_back(detail::rotationOf(body));
            }
        }
        dSpaceCollide(space, &state, &detail::addContacts);
        if (solver == Solver::Step)
            dWorldStep(state.world, options.timeStep);
        else
            dWorldQuickStep(state.world, options.timeStep);
        dJointGroupEmpty(state.contacts);
        if (state.measuring)
            for (std::size_t i = 0; i < bodies.size(); ++i) {
                const Vec3 p = positionOf(bodies[i]);
                const Mat3 r = detail::rotationOf(bodies[i]);
                result.drift = std::max(result.drift, (p - settledPositions[i]).head<2>().norm());
                result.sag = std::max(result.sag, std::abs(p.z() - settledPositions[i].z()));
                result.tilt = std::max(result.tilt, detail::tiltOf(r));
                const Mat3 turn = r * settledRotations[i].transpose();
                result.twist = std::max(result.twist, std::abs(std::atan2(turn(1, 0), turn(0, 0))));
                const double below = specs[i].restsOn < 0 ? options.planeOrigin.z()
                                                          : positionOf(bodies[static_cast<std::size_t>(specs[i].restsOn)]).z();
                if (!(p.z() > below)) result.ordered = false;
            }
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Vec3 p = positionOf(bodies[i]);
        const double height = specs[i].halfExtents.minCoeff() * 2;
        if (!p.allFinite() || (p - specs[i].pose.position).norm() > std::max(0.5 * height, 0.5 * specs[i].halfExtents.maxCoeff()))
            result.standing = false;
    }
    result.worstNormalAngle = state.worstNormalAngle;
    dSpaceDestroy(space);
    dJointGroupDestroy(state.contacts);
    dWorldDestroy(state.world);
    dCloseODE();
    return result;
}

/// A 10-high stack of cubes of side `side` (1 kg each), each shifted by up to 2 % of the side
/// and turned by up to 5° about the vertical (a fixed pattern), sunk 1e-4 of the side into the
/// one below (dWorldStep's LCP reports an internal error for a first step of depth-0 contacts),
/// standing on the plane through `origin`.
inline std::vector<BodySpec> cubeStack(double side, const Vec3& origin = Vec3::Zero(), int height = 10) {
    std::vector<BodySpec> specs;
    for (int level = 0; level < height; ++level) {
        const Vec3 offset(0.02 * side * std::sin(1.7 * level), 0.02 * side * std::cos(2.3 * level),
                          side * (0.5 + level * (1.0 - 1e-4)));
        const Mat3 yaw = Eigen::AngleAxisd(5.0 * M_PI / 180.0 * std::sin(0.9 * level), Vec3::UnitZ()).toRotationMatrix();
        specs.push_back({Vec3::Constant(0.5 * side), 1.0, Pose{yaw, origin + offset}, level - 1});
    }
    return specs;
}

}  // namespace gdc::robustness

// The order in which dWorldQuickStep meets a pair's contacts (Settings::contactOrder). ODE's
// dJointAttach puts each new joint at the head of its bodies' joint lists, and the island walk
// (ode/src/util.cpp, dxProcessIslands) follows those lists, so the solver meets a pair's contacts
// in the reverse of their creation order; the adapter writes its array accordingly.
#include "ode_precision.hpp"
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace gdc;
using namespace gdc::ode;
using namespace gdc::ode::test;

namespace {

// A box of sides 1 × 0.8 × 0.6 (a body), turned by the Euler angles `tilt` so that its four bottom
// corners lie at four depths (by default within 1.02 mm of each other: all four overlap from
// 1.02 mm on), its lowest corner `deepest` below z = 0, against: a plane z = 0,
// or a static box of sides 2 × 2 × 0.4 whose top face is z = 0. The depths in the order of the
// body's joint list (the order dWorldQuickStep meets them), after a joint per contact was created
// and attached in the array's order.
std::vector<double> depthsMetOn(const Settings& settings, bool onBox, double deepest,
                                std::array<double, 3> tilt = {0.0004, 0.0007, 0.3}) {
    OdeSession session(true, settings);
    dWorldID world = dWorldCreate();
    dJointGroupID group = dJointGroupCreate(0);
    dBodyID body = dBodyCreate(world);
    dGeomID box = dCreateBox(nullptr, 1, 0.8, 0.6);
    dGeomSetBody(box, body);
    dMatrix3 r;
    dRFromEulerAngles(r, tilt[0], tilt[1], tilt[2]);
    dBodySetRotation(body, r);
    double lowest = 0;  // the lowest corner's height above the centre: r's third row · the corner
    for (int corner = 0; corner < 8; ++corner) {
        const double local[3] = {corner & 1 ? 0.5 : -0.5, corner & 2 ? 0.4 : -0.4, corner & 4 ? 0.3 : -0.3};
        lowest = std::min(lowest, r[8] * local[0] + r[9] * local[1] + r[10] * local[2]);
    }
    dBodySetPosition(body, 0.1, -0.05, -deepest - lowest);
    dGeomID other = onBox ? dCreateBox(nullptr, 2, 2, 0.4) : dCreatePlane(nullptr, 0, 0, 1, 0);
    if (onBox) dGeomSetPosition(other, 0, 0, -0.2);
    dContact contacts[8] = {};
    const int count = dCollide(box, other, 8, &contacts[0].geom, sizeof(dContact));
    std::vector<dJointID> joints;
    for (int i = 0; i < count; ++i) {
        joints.push_back(dJointCreateContact(world, group, &contacts[i]));
        dJointAttach(joints.back(), body, nullptr);
    }
    std::vector<double> depths;
    REQUIRE(dBodyGetNumJoints(body) == count);
    for (int k = 0; k < count; ++k) {
        // The head of the list is the joint created last.
        CHECK(dBodyGetJoint(body, k) == joints[static_cast<std::size_t>(count - 1 - k)]);
        depths.push_back(contacts[count - 1 - k].geom.depth);
    }
    dGeomDestroy(other);
    dGeomDestroy(box);
    dJointGroupDestroy(group);
    dWorldDestroy(world);
    return depths;
}

}  // namespace

// DeepestFirstWhenLoaded, the rule spelled out: a pair whose deepest point is deeper than
// loadedDepthFraction times the larger of its two shapes' diameters (twice the bounding radius; a
// plane has none) is met deepest first, any other deepest last. The body's diameter is
// √(1 + 0.64 + 0.36) = 1.414, the static box's √(4 + 4 + 0.16) = 2.857: at a fraction of 0.001 the
// line is 2.857 mm on the box and 1.414 mm on the plane. 1.2 mm is below both, 2 mm between them
// (above the line the body's own diameter would give on the box), 3.5 mm above both. The least
// widths (the former measure: 0.6 mm on the box at this fraction) would count every depth here as
// loaded.
TEST_CASE("DeepestFirstWhenLoaded meets a loaded pair deepest first and a lightly loaded one deepest last",
          "[ode][order]") {
    CHECK(Settings{}.contactOrder == ContactOrder::DeepestFirstWhenLoaded);  // the default
    Settings settings;
    settings.loadedDepthFraction = 0.001;
    const double bodyDiameter = std::sqrt(1.0 + 0.64 + 0.36), staticDiameter = std::sqrt(4.0 + 4.0 + 0.16);
    for (const bool onBox : {true, false}) {
        const double line = settings.loadedDepthFraction * (onBox ? std::max(bodyDiameter, staticDiameter) : bodyDiameter);
        for (const double deepest : {0.0012, 0.002, 0.0035}) {
            INFO((onBox ? "on a box" : "on a plane") << ", deepest " << deepest << ", line " << line);
            const std::vector<double> met = depthsMetOn(settings, onBox, deepest);
            REQUIRE(met.size() == 4);
            const double deepestMet = *std::max_element(met.begin(), met.end());
            CHECK(deepestMet == Approx(deepest).margin(1e-6));
            CHECK(met.front() != met.back());
            if (deepestMet > line) CHECK(std::is_sorted(met.rbegin(), met.rend()));  // deepest first
            else CHECK(std::is_sorted(met.begin(), met.end()));                      // deepest last
            CHECK((deepest > line ? met.front() : met.back()) == deepestMet);
            if (deepest == 0.002) CHECK((deepest > line) == !onBox);  // between the two lines
        }
    }
    // The fraction moves the line: at 0.0005 (1.43 mm on the box) both deeper pairs are loaded, at
    // 0.002 (5.7 mm) neither.
    for (const double fraction : {0.0005, 0.002}) {
        settings.loadedDepthFraction = fraction;
        for (const double deepest : {0.002, 0.0035}) {
            INFO("fraction " << fraction << ", deepest " << deepest);
            const std::vector<double> met = depthsMetOn(settings, true, deepest);
            REQUIRE(met.size() == 4);
            CHECK((fraction < 0.001 ? met.front() : met.back()) == *std::max_element(met.begin(), met.end()));
        }
    }
}

TEST_CASE("The solver meets a pair's contacts by depth, as Settings::contactOrder says", "[ode][order]") {
    // Tilted further (bottom corners up to 2.8 cm apart), the lowest 3 cm deep: four depths.
    const auto depthsInJointListOrder = [](ContactOrder order) {
        Settings settings;
        settings.contactOrder = order;
        return depthsMetOn(settings, false, 0.03, {0.01, 0.02, 0.3});
    };
    const std::vector<double> first = depthsInJointListOrder(ContactOrder::DeepestFirst);
    REQUIRE(first.size() == 4);
    CHECK(std::is_sorted(first.rbegin(), first.rend()));  // deepest first
    CHECK(first.front() > first.back());
    const std::vector<double> last = depthsInJointListOrder(ContactOrder::DeepestLast);
    REQUIRE(last.size() == 4);
    CHECK(std::is_sorted(last.begin(), last.end()));  // deepest last
    CHECK(last.front() < last.back());
}

// A geom pair's touching points (depth within rounding of 0) are left out where it has
// overlapping ones: such a row has a zero right-hand side and, between bodies resting together, a
// zero relative velocity, a tie ODE's Dantzig LCP cannot break ("LCP internal error"). The core
// still reports them; only what the adapter hands ODE changes. With no overlapping point the
// touching ones stay (a box placed exactly on the floor keeps its four corners).
TEST_CASE("A pair's touching contacts are left out where it has overlapping ones", "[ode][order]") {
    OdeSession session(true, Settings{});
    int exercised = 0;  // tilted poses whose core answer has touching points beside overlapping ones
    for (const double tilt : {0.0, 1e-3, 0.02}) {
        for (const double yaw : {0.0, 0.4}) {
            dGeomID box = dCreateBox(nullptr, 1, 0.8, 0.6);
            dMatrix3 tiltAboutY, yawAboutZ, r;  // r = yaw · tilt: the two corners on one side sink
            dRFromAxisAndAngle(tiltAboutY, 0, 1, 0, tilt);
            dRFromAxisAndAngle(yawAboutZ, 0, 0, 1, yaw);
            dMultiply0_333(r, yawAboutZ, tiltAboutY);
            dGeomSetRotation(box, r);
            dGeomID plane = dCreatePlane(nullptr, 0, 0, 1, 0);
            // The higher bottom corners on the plane z = 0, the lower ones sin(tilt) deep: exactly
            // as far as dReal can place them. A single-precision ODE rounds the rotation and the
            // height to float, which can leave the higher corners a few 1e-9 below the plane —
            // overlapping, not touching, for the pose ODE holds — so there the height is raised by
            // a float ulp at a time until the core finds them at depth ≤ 0. One float ulp of the
            // height (3e-8) may then put them beyond the core's rounding of the plane: the core
            // reports the two lower corners alone, and that pose does not exercise the rule (it is
            // counted: some poses must). A double-precision ODE places them exactly: no step is taken.
            const int overlappingWanted = tilt == 0 ? 0 : 2;
            const auto overlappingOf = [](const Manifold& m) {
                return static_cast<int>(std::count_if(m.points.begin(), m.points.begin() + m.pointCount,
                                                      [](const ContactPoint& p) { return p.depth > 0; }));
            };
            dGeomSetPosition(box, 0.3, -0.2, 0.3 * std::cos(tilt) - 0.5 * std::sin(tilt));
            Manifold core = gdc::collide(*polytopeOf(box), poseOf(box), HalfSpace{Vec3(0, 0, 1), 0});
            for (int step = 0; step < 8 && !kOdeIsDouble && overlappingOf(core) > overlappingWanted; ++step) {
                const dReal* position = dGeomGetPosition(box);
                dGeomSetPosition(box, position[0], position[1], std::nextafter(position[2], dReal(1)));
                core = gdc::collide(*polytopeOf(box), poseOf(box), HalfSpace{Vec3(0, 0, 1), 0});
            }
            dContactGeom contacts[8] = {};
            const int count = dCollide(box, plane, 8, contacts, sizeof(dContactGeom));
            INFO("tilt " << tilt << " yaw " << yaw);
            REQUIRE(overlappingOf(core) == overlappingWanted);
            // The bottom face, every corner within rounding of the plane or below; or, in single
            // precision, the lower corners alone where the higher ones are a float ulp above.
            if (kOdeIsDouble || tilt == 0) REQUIRE(core.pointCount == 4);
            REQUIRE((core.pointCount == 4 || core.pointCount == 2));
            exercised += tilt != 0 && core.pointCount == 4;
            const double touching = realTolerance(1e-9) * polytopeOf(box)->radius();  // the adapter's rule
            for (int i = 0; i < core.pointCount; ++i) REQUIRE(core.points[i].depth >= -touching);
            if (tilt == 0) {
                CHECK(count == 4);
                for (int i = 0; i < count; ++i) CHECK(contacts[i].depth == 0);
            } else {
                CHECK(count == 2);
                // Float's rounding of the pose (a box of size 1) where dReal is float.
                const double slack = kOdeIsDouble ? 0.0 : realTolerance(1e-9);
                for (int i = 0; i < count; ++i)
                    CHECK(contacts[i].depth == Approx(std::sin(tilt)).epsilon(1e-9).margin(slack));
            }
            dGeomDestroy(plane);
            dGeomDestroy(box);
        }
    }
    std::printf("touching contacts beside overlapping ones: %d of 4 tilted poses exercise the rule\n", exercised);
    CHECK(exercised >= (kOdeIsDouble ? 4 : 1));
}

// The order in which dWorldQuickStep meets a pair's contacts (Settings::contactOrder). ODE's
// dJointAttach puts each new joint at the head of its bodies' joint lists, and the island walk
// (ode/src/util.cpp, dxProcessIslands) follows those lists, so the solver meets a pair's contacts
// in the reverse of their creation order; the adapter writes its array accordingly.
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

using namespace gdc;
using namespace gdc::ode;
using namespace gdc::ode::test;

namespace {

// A box tilted on a plane (four corners at four depths): the depths in the order of the body's
// joint list, after one joint per contact was created and attached in the array's order.
std::vector<double> depthsInJointListOrder(ContactOrder order) {
    Settings settings;
    settings.contactOrder = order;
    OdeSession session(true, settings);
    dWorldID world = dWorldCreate();
    dJointGroupID group = dJointGroupCreate(0);
    dBodyID body = dBodyCreate(world);
    dGeomID box = dCreateBox(nullptr, 1, 0.8, 0.6);
    dGeomSetBody(box, body);
    dMatrix3 r;
    dRFromEulerAngles(r, 0.01, 0.02, 0.3);
    dBodySetRotation(body, r);
    dBodySetPosition(body, 0, 0, 0.28);
    dGeomID plane = dCreatePlane(nullptr, 0, 0, 1, 0);
    dContact contacts[8] = {};
    const int count = dCollide(box, plane, 8, &contacts[0].geom, sizeof(dContact));
    std::vector<dJointID> joints;
    for (int i = 0; i < count; ++i) {
        joints.push_back(dJointCreateContact(world, group, &contacts[i]));
        dJointAttach(joints.back(), body, nullptr);
    }
    std::vector<double> depths;
    REQUIRE(dBodyGetNumJoints(body) == count);
    for (int k = 0; k < count; ++k) {
        dJointID joint = dBodyGetJoint(body, k);
        // The head of the list is the joint created last.
        CHECK(joint == joints[static_cast<std::size_t>(count - 1 - k)]);
        depths.push_back(contacts[count - 1 - k].geom.depth);
    }
    dGeomDestroy(plane);
    dGeomDestroy(box);
    dJointGroupDestroy(group);
    dWorldDestroy(world);
    return depths;
}

}  // namespace

TEST_CASE("The solver meets a pair's contacts by depth, as Settings::contactOrder says", "[ode][order]") {
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
    for (const double tilt : {0.0, 1e-3, 0.02}) {
        for (const double yaw : {0.0, 0.4}) {
            dGeomID box = dCreateBox(nullptr, 1, 0.8, 0.6);
            dMatrix3 tiltAboutY, yawAboutZ, r;  // r = yaw · tilt: the two corners on one side sink
            dRFromAxisAndAngle(tiltAboutY, 0, 1, 0, tilt);
            dRFromAxisAndAngle(yawAboutZ, 0, 0, 1, yaw);
            dMultiply0_333(r, yawAboutZ, tiltAboutY);
            dGeomSetRotation(box, r);
            // The higher bottom corners exactly on the plane z = 0, the lower ones sin(tilt)·0.5 deep.
            dGeomSetPosition(box, 0.3, -0.2, 0.3 * std::cos(tilt) - 0.5 * std::sin(tilt));
            dGeomID plane = dCreatePlane(nullptr, 0, 0, 1, 0);
            dContactGeom contacts[8] = {};
            const int count = dCollide(box, plane, 8, contacts, sizeof(dContactGeom));
            const Manifold core = gdc::collide(*polytopeOf(box), poseOf(box), HalfSpace{Vec3(0, 0, 1), 0});
            INFO("tilt " << tilt << " yaw " << yaw);
            REQUIRE(core.pointCount == 4);  // the bottom face, every corner within rounding of the plane or below
            if (tilt == 0) {
                CHECK(count == 4);
                for (int i = 0; i < count; ++i) CHECK(contacts[i].depth == 0);
            } else {
                CHECK(count == 2);
                for (int i = 0; i < count; ++i) CHECK(contacts[i].depth == Approx(std::sin(tilt)).epsilon(1e-9));
            }
            dGeomDestroy(plane);
            dGeomDestroy(box);
        }
    }
}

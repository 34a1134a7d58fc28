// Triangle meshes in ODE with gdcontact installed (docs/ode.md, "Triangle meshes"): a box and a
// hull resting on a triangulated floor get the contacts a dPlane at the same height gives; either
// order of the geoms gives mirrored contacts; a frictionless box slides across the floor's seams
// without a bump or a turn (ODE's own box–trimesh collider's figures printed beside, not asserted);
// the mesh is read afresh after its data changes; the triangle callbacks are honoured; a
// degenerate triangle is skipped; spaceCollide and the C API give dCollide's contacts.
#include <gdcontact/ode.h>
#include <gdcontact/ode.hpp>

#include "ode/ode_internals.hpp"  // detail::describeOdeColliders
#include "ode/trimesh_geoms.hpp"  // detail::cachedTrimeshCount
#include "ode_precision.hpp"
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace gdc;
using namespace gdc::ode::test;

namespace {

// A flat floor at height z of n × n square cells of side `cell`, centred on the origin, each cell
// two triangles (wound counter-clockwise seen from above: the front is up). ODE keeps pointers to
// the arrays, so they live with the data. The vertices are doubles (dGeomTriMeshDataBuildDouble)
// whatever dReal is, as a program with double data builds them in either ODE.
struct Floor {
    std::vector<double> vertices;
    std::vector<dTriIndex> indices;
    dTriMeshDataID data = nullptr;
    dGeomID geom = nullptr;
    Floor(dSpaceID space, int n, double cell, double z) {
        fill(n, cell, z);
        data = dGeomTriMeshDataCreate();
        build();
        geom = dCreateTriMesh(space, data, nullptr, nullptr, nullptr);
    }
    ~Floor() {
        if (geom) dGeomDestroy(geom);
        if (data) dGeomTriMeshDataDestroy(data);
    }
    Floor(const Floor&) = delete;
    Floor& operator=(const Floor&) = delete;
    void fill(int n, double cell, double z) {
        vertices.clear();
        indices.clear();
        const double half = 0.5 * n * cell;
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i)
                vertices.insert(vertices.end(), {-half + cell * i, -half + cell * j, z});
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const dTriIndex a = static_cast<dTriIndex>(j * (n + 1) + i), b = a + 1,
                                c = static_cast<dTriIndex>(a + n + 1), d = c + 1;
                indices.insert(indices.end(), {a, b, d, a, d, c});
            }
    }
    void build() {
        dGeomTriMeshDataBuildDouble(data, vertices.data(), 3 * sizeof(double), static_cast<int>(vertices.size() / 3),
                                    indices.data(), static_cast<int>(indices.size()), 3 * sizeof(dTriIndex));
    }
    int triangleCount() const { return static_cast<int>(indices.size() / 3); }
};

std::vector<dContactGeom> collideDirect(dGeomID o1, dGeomID o2, int maxContacts = 16) {
    std::vector<dContactGeom> contacts(static_cast<std::size_t>(maxContacts));
    const int count = gdc::ode::collide(o1, o2, maxContacts, contacts.data(), sizeof(dContactGeom));
    contacts.resize(static_cast<std::size_t>(std::max(count, 0)));
    return contacts;
}

// The area of the convex hull of the contacts' positions projected on the plane z = const.
double supportArea(const std::vector<dContactGeom>& contacts) {
    std::vector<Vec2> points;
    for (const auto& c : contacts) points.emplace_back(c.pos[0], c.pos[1]);
    return gdc::testing::convexHullArea(points);
}

std::string describe(const std::vector<dContactGeom>& contacts) {
    std::ostringstream text;
    for (const auto& c : contacts)
        text << "(" << c.pos[0] << ", " << c.pos[1] << ", " << c.pos[2] << "; depth " << c.depth << "; sides "
             << c.side1 << " " << c.side2 << ") ";
    return text.str();
}

double deepest(const std::vector<dContactGeom>& contacts) {
    double depth = -1;
    for (const auto& c : contacts) depth = std::max(depth, static_cast<double>(c.depth));
    return depth;
}

// A random hull with a flat quadrilateral bottom at local z = −0.2 (its resting face) and random
// points above it.
std::vector<dReal> randomHullPoints(std::mt19937_64& random) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<dReal> points;
    const double angles[4] = {0.3, 1.9, 3.4, 4.9};
    for (double angle : angles) {
        const double radius = 0.3 + 0.05 * unit(random);
        points.insert(points.end(), {dReal(radius * std::cos(angle + 0.2 * unit(random))),
                                     dReal(radius * std::sin(angle + 0.2 * unit(random))), dReal(-0.2)});
    }
    for (int i = 0; i < 12; ++i)
        points.insert(points.end(),
                      {dReal(0.25 * unit(random)), dReal(0.25 * unit(random)), dReal(0.05 + 0.15 * (1 + unit(random)))});
    return points;
}

// The geom's lowest point in the world along z (its vertices at its pose).
double lowestZ(const std::vector<dReal>& localPoints, dGeomID geom) {
    const dReal* p = dGeomGetPosition(geom);
    const dReal* r = dGeomGetRotation(geom);
    double lowest = INFINITY;
    for (std::size_t i = 0; i < localPoints.size(); i += 3)
        lowest = std::min<double>(lowest, p[2] + r[8] * localPoints[i] + r[9] * localPoints[i + 1] + r[10] * localPoints[i + 2]);
    return lowest;
}

}  // namespace

TEST_CASE("a box and a hull resting on a triangulated floor get the contacts of a plane at its height",
          "[trimesh][ode]") {
    OdeSession session(true);
    constexpr double kHeight = 0.25, kSink = 1e-3;
    Floor floor(nullptr, 8, 0.5, kHeight);  // 128 triangles over [-2, 2]²
    REQUIRE(floor.triangleCount() == 128);
    dGeomID plane = dCreatePlane(nullptr, 0, 0, 1, kHeight);
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int compared = 0;
    for (int trial = 0; trial < 20; ++trial) {
        dGeomID body;
        std::vector<dReal> points;
        if (trial % 2 == 0) {
            body = dCreateBox(nullptr, 0.6, 0.4, 0.3);
            points = boxCorners(Vec3(0.3, 0.2, 0.15));
        } else {
            points = randomHullPoints(random);
            body = gdc::ode::createConvex(nullptr, points.data(), static_cast<unsigned>(points.size() / 3));
        }
        // Anywhere over the floor (often across seams), turned about the vertical, sunk kSink.
        setRotation(body, rotationAbout(Vec3::UnitZ(), M_PI * unit(random)));
        dGeomSetPosition(body, 1.2 * unit(random), 1.2 * unit(random), 1.0);
        const double lowest = lowestZ(points, body);
        dGeomSetPosition(body, dGeomGetPosition(body)[0], dGeomGetPosition(body)[1], 1.0 - (lowest - kHeight) - kSink);
        INFO("trial " << trial);
        for (int order = 0; order < 2; ++order) {
            const auto onMesh = order ? collideThroughOde(floor.geom, body, 16) : collideThroughOde(body, floor.geom, 16);
            const auto onPlane = collideThroughOde(body, plane, 16);
            REQUIRE(!onMesh.empty());
            REQUIRE(!onPlane.empty());
            const double sign = order ? -1.0 : 1.0;  // the normal points from o2 into o1
            for (const auto& c : onMesh) {
                CHECK(std::abs(c.normal[0]) < realTolerance(1e-9));
                CHECK(std::abs(c.normal[1]) < realTolerance(1e-9));
                CHECK(std::abs(c.normal[2] - sign) < realTolerance(1e-9));
                CHECK(std::abs(c.pos[2] - (kHeight - 0.5 * c.depth)) < realTolerance(1e-9));
            }
            INFO("on the mesh: " << describe(onMesh) << "\non the plane: " << describe(onPlane));
            CHECK(std::abs(deepest(onMesh) - deepest(onPlane)) < realTolerance(1e-9));
            CHECK(std::abs(supportArea(onMesh) - supportArea(onPlane)) < 1e-6);
            ++compared;
        }
        dGeomDestroy(body);
    }
    CHECK(compared == 40);
    dGeomDestroy(plane);
}

// The largest distance between two contacts' positions: a line support's length.
double span(const std::vector<dContactGeom>& contacts) {
    double longest = 0;
    for (const auto& a : contacts)
        for (const auto& b : contacts)
            longest = std::max<double>(longest, std::hypot(a.pos[0] - b.pos[0], a.pos[1] - b.pos[1], a.pos[2] - b.pos[2]));
    return longest;
}

TEST_CASE("capsules and cylinders resting on a triangulated floor get the plane's normal, depth and support",
          "[trimesh][ode]") {
    OdeSession session(true);
    constexpr double kHeight = 0.25, kSink = 1e-3;
    Floor floor(nullptr, 8, 0.5, kHeight);
    dGeomID plane = dCreatePlane(nullptr, 0, 0, 1, kHeight);
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 30; ++trial) {
        // A lying capsule, a lying cylinder and a standing cylinder in turn, anywhere over the floor
        // (across seams and vertices), turned about the vertical.
        const int kind = trial % 3;
        const double radius = 0.15 + 0.05 * unit(random), length = 0.6 + 0.3 * unit(random);
        dGeomID body = kind == 0 ? dCreateCapsule(nullptr, radius, length) : dCreateCylinder(nullptr, radius, length);
        const Mat3 turn = rotationAbout(Vec3::UnitZ(), M_PI * unit(random));
        setRotation(body, kind == 2 ? turn : Mat3(turn * rotationAbout(Vec3::UnitX(), M_PI / 2)));
        const double lowest = kind == 2 ? 0.5 * length : radius;  // below the centre
        dGeomSetPosition(body, 1.2 * unit(random), 1.2 * unit(random), kHeight + lowest - kSink);
        INFO("trial " << trial << " kind " << kind);
        const auto onMesh = collideThroughOde(body, floor.geom, 16);
        const auto onPlane = collideThroughOde(body, plane, 16);
        INFO("on the mesh: " << describe(onMesh) << "\non the plane: " << describe(onPlane));
        REQUIRE(!onPlane.empty());
        REQUIRE(onMesh.size() >= (kind == 2 ? 3u : 2u));
        for (const auto& c : onMesh) {
            CHECK(std::abs(c.normal[0]) < realTolerance(1e-9));
            CHECK(std::abs(c.normal[1]) < realTolerance(1e-9));
            CHECK(std::abs(c.normal[2] - 1) < realTolerance(1e-9));
            CHECK(std::abs(c.depth - kSink) < realTolerance(1e-9));  // level: every point as deep as the lowest line
        }
        CHECK(std::abs(deepest(onMesh) - deepest(onPlane)) < realTolerance(1e-9));
        if (kind < 2) {
            CHECK(std::abs(span(onMesh) - span(onPlane)) < realTolerance(1e-9));  // the whole line, end to end
        } else {
            const dReal* centre = dGeomGetPosition(body);
            for (const auto& c : onMesh)  // on the rim of the lower cap
                CHECK(std::abs(std::hypot(c.pos[0] - centre[0], c.pos[1] - centre[1]) - radius) < realTolerance(1e-9));
        }
        dGeomDestroy(body);
    }
    dGeomDestroy(plane);
}

TEST_CASE("either order of a trimesh pair gives mirrored contacts", "[trimesh][ode]") {
    OdeSession session(true);
    Floor floor(nullptr, 8, 0.5, 0.0);
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int nonEmpty = 0;
    for (int trial = 0; trial < 30; ++trial) {
        const std::vector<dReal> points = randomHullPoints(random);
        dGeomID body = trial % 2 ? dCreateBox(nullptr, 0.5, 0.3, 0.2)
                                 : gdc::ode::createConvex(nullptr, points.data(), static_cast<unsigned>(points.size() / 3));
        setRotation(body, randomRotation(random));
        dGeomSetPosition(body, 1.5 * unit(random), 1.5 * unit(random), 0.1 + 0.05 * unit(random));
        INFO("trial " << trial);
        const auto forward = collideDirect(body, floor.geom), backward = collideDirect(floor.geom, body);
        const auto forwardOde = collideThroughOde(body, floor.geom, 16), backwardOde = collideThroughOde(floor.geom, body, 16);
        REQUIRE(forward.size() == backward.size());
        REQUIRE(forwardOde.size() == forward.size());
        REQUIRE(backwardOde.size() == forward.size());
        for (std::size_t i = 0; i < forward.size(); ++i) {
            const dContactGeom &f = forward[i], &b = backward[i];
            for (int axis = 0; axis < 3; ++axis) {
                CHECK(f.pos[axis] == b.pos[axis]);
                CHECK(f.normal[axis] == -b.normal[axis]);
                CHECK(forwardOde[i].pos[axis] == f.pos[axis]);
                CHECK(backwardOde[i].normal[axis] == b.normal[axis]);
            }
            CHECK(f.depth == b.depth);
            CHECK(f.depth >= 0);
            CHECK((f.g1 == body && f.g2 == floor.geom && b.g1 == floor.geom && b.g2 == body));
            // The triangle's index on the trimesh's side, as ODE's trimesh colliders give it.
            CHECK((f.side1 == -1 && f.side2 >= 0 && f.side2 < 128 && b.side1 == f.side2 && b.side2 == -1));
            CHECK((backwardOde[i].side1 == b.side1 && forwardOde[i].side2 == f.side2));
            CHECK(std::abs(Vec3(f.normal[0], f.normal[1], f.normal[2]).norm() - 1.0) < realTolerance(1e-12));
        }
        nonEmpty += forward.empty() ? 0 : 1;
        dGeomDestroy(body);
    }
    CHECK(nonEmpty >= 10);
}

TEST_CASE("ODE's own box-trimesh puts the triangle index where the adapter does", "[trimesh][ode]") {
    OdeSession session(false);  // ODE's colliders
    Floor floor(nullptr, 8, 0.5, 0.0);
    dGeomID box = dCreateBox(nullptr, 0.6, 0.4, 0.3);
    dGeomSetPosition(box, 0.1, 0.2, 0.14);
    const auto meshFirst = collideThroughOde(floor.geom, box, 16), boxFirst = collideThroughOde(box, floor.geom, 16);
    REQUIRE(!meshFirst.empty());
    REQUIRE(!boxFirst.empty());
    for (const auto& c : meshFirst) CHECK((c.g1 == floor.geom && c.side1 >= 0 && c.side2 == -1));
    for (const auto& c : boxFirst) CHECK((c.g2 == floor.geom && c.side2 >= 0 && c.side1 == -1));
    dGeomDestroy(box);
}

namespace {

// A body's yaw (rotation about z) from its rotation matrix.
double yawOf(dBodyID body) {
    const dReal* r = dBodyGetRotation(body);
    return std::atan2(r[4], r[0]);
}

struct Slide {
    double maxVerticalSpeed = 0;  // after settling
    double yawTurn = 0;           // |yaw(end) − yaw(start)|, radians
    double travelled = 0;         // along x
    double lowest = INFINITY;     // the box's centre height, least after settling
};

void slideNear(void* data, dGeomID o1, dGeomID o2) {
    auto* world = static_cast<std::pair<dWorldID, dJointGroupID>*>(data);
    const dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    dContact records[16];
    const int count = dCollide(o1, o2, 16, &records[0].geom, sizeof(dContact));
    for (int i = 0; i < count; ++i) {
        records[i].surface.mode = dContactApprox0;  // frictionless
        records[i].surface.mu = 0;
        dJointAttach(dJointCreateContact(world->first, world->second, &records[i]), b1, b2);
    }
}

// A 0.6 × 0.4 × 0.3 box, 1 kg, dropped 1 mm onto the 8 × 8-cell floor (cells of 1 m, so it crosses
// cell edges and diagonals) and pushed along x at 1.5 m/s, frictionless, 2 s of dWorldQuickStep.
Slide slideAcrossSeams(bool installGdcontact) {
    OdeSession session(installGdcontact);
    dWorldID world = dWorldCreate();
    dSpaceID space = dSimpleSpaceCreate(nullptr);
    dJointGroupID joints = dJointGroupCreate(0);
    dWorldSetGravity(world, 0, 0, -9.81);
    dWorldSetERP(world, 0.2);
    dWorldSetCFM(world, 1e-5);
    dWorldSetQuickStepNumIterations(world, 20);
    Slide slide;
    {
        Floor floor(space, 8, 1.0, 0.0);
        dBodyID body = dBodyCreate(world);
        dMass mass;
        dMassSetBoxTotal(&mass, 1.0, 0.6, 0.4, 0.3);
        dBodySetMass(body, &mass);
        dGeomID box = dCreateBox(space, 0.6, 0.4, 0.3);
        dGeomSetBody(box, body);
        dBodySetPosition(body, -3.0, 0.3, 0.151);
        dBodySetLinearVel(body, 1.5, 0, 0);
        std::pair<dWorldID, dJointGroupID> data{world, joints};
        const double startYaw = yawOf(body);
        for (int step = 0; step < 200; ++step) {
            dSpaceCollide(space, &data, &slideNear);
            dWorldQuickStep(world, 0.01);
            dJointGroupEmpty(joints);
            if (step >= 20) {  // settled after 0.2 s
                slide.maxVerticalSpeed = std::max<double>(slide.maxVerticalSpeed, std::abs(dBodyGetLinearVel(body)[2]));
                slide.lowest = std::min(slide.lowest, static_cast<double>(dBodyGetPosition(body)[2]));
            }
        }
        slide.yawTurn = std::abs(yawOf(body) - startYaw);
        slide.travelled = dBodyGetPosition(body)[0] + 3.0;
        dGeomDestroy(box);
        dBodyDestroy(body);
    }
    dJointGroupDestroy(joints);
    dSpaceDestroy(space);
    dWorldDestroy(world);
    return slide;
}

}  // namespace

TEST_CASE("a frictionless box slides across the seams of a triangulated floor without a bump or a turn",
          "[trimesh][ode][slide]") {
    const Slide ode = slideAcrossSeams(false);
    const Slide ours = slideAcrossSeams(true);
    WARN("box sliding 2 s across trimesh seams (QuickStep): gdcontact max |vz| " << ours.maxVerticalSpeed
         << " m/s, yaw turn " << ours.yawTurn * 180 / M_PI << " deg, travelled " << ours.travelled
         << " m, lowest centre " << ours.lowest << " m; ODE's own box-trimesh: max |vz| " << ode.maxVerticalSpeed
         << " m/s, yaw turn " << ode.yawTurn * 180 / M_PI << " deg, travelled " << ode.travelled
         << " m, lowest centre " << ode.lowest << " m");
    CHECK(ours.maxVerticalSpeed < 1e-3);
    CHECK(ours.yawTurn < M_PI / 180);
    CHECK(ours.travelled > 2.5);   // it slid across the seams (3 m without friction)
    CHECK(ours.lowest > 0.149);   // on the floor, not through it
}

namespace {

std::vector<dContactGeom> boxOn(dGeomID mesh, double x, double y, double z) {
    dGeomID box = dCreateBox(nullptr, 0.6, 0.4, 0.3);
    dGeomSetPosition(box, x, y, z);
    auto contacts = collideThroughOde(box, mesh, 16);
    dGeomDestroy(box);
    return contacts;
}

int rejectEvery(dGeomID, dGeomID, int) { return 0; }
int acceptEven(dGeomID, dGeomID, int triangle) { return triangle % 2 == 0; }
std::vector<int> arrayCallbackTriangles;  // the last dTriArrayCallback's (this test's thread only)
void recordTriangles(dGeomID, dGeomID, const int* triangles, int count) {
    arrayCallbackTriangles.assign(triangles, triangles + count);
}

}  // namespace

TEST_CASE("a trimesh whose data is destroyed and rebuilt, or updated, is read afresh", "[trimesh][ode]") {
    OdeSession session(true);
    Floor floor(nullptr, 8, 0.5, 0.0);
    const std::size_t cachedBefore = gdc::ode::detail::cachedTrimeshCount();
    auto contacts = boxOn(floor.geom, 0.1, 0.2, 0.149);
    REQUIRE(!contacts.empty());
    CHECK(std::abs(deepest(contacts) - 1e-3) < realTolerance(1e-9));
    CHECK(gdc::ode::detail::cachedTrimeshCount() == cachedBefore + 1);

    // Destroyed (the free hook forgets its mesh) and another data, 0.375 higher with 4 × 4 cells,
    // built — most likely at the same address — and given to the geom. (Heights exact in float:
    // ODE hands a trimesh's vertices out rounded to float, as its own colliders see them.)
    dGeomTriMeshDataDestroy(floor.data);
    CHECK(gdc::ode::detail::cachedTrimeshCount() == cachedBefore);
    floor.fill(4, 1.0, 0.375);
    floor.data = dGeomTriMeshDataCreate();
    floor.build();
    dGeomTriMeshSetData(floor.geom, floor.data);
    contacts = boxOn(floor.geom, 0.1, 0.2, 0.524);
    REQUIRE(!contacts.empty());
    CHECK(std::abs(deepest(contacts) - 1e-3) < realTolerance(1e-9));
    for (const auto& c : contacts) CHECK(c.side2 < 32);
    // 0.125 deep in the new floor, its centre still in front of it (a centre behind a one-sided
    // surface gets nothing: tests/mesh_test.cpp).
    contacts = boxOn(floor.geom, 0.1, 0.2, 0.4);
    REQUIRE(!contacts.empty());
    CHECK(std::abs(deepest(contacts) - 0.125) < realTolerance(1e-9));

    // The vertices changed in place, announced with dGeomTriMeshDataUpdate: 0.125 lower.
    for (std::size_t i = 2; i < floor.vertices.size(); i += 3) floor.vertices[i] -= 0.125;
    dGeomTriMeshDataUpdate(floor.data);
    contacts = boxOn(floor.geom, 0.1, 0.2, 0.399);
    REQUIRE(!contacts.empty());
    CHECK(std::abs(deepest(contacts) - 1e-3) < realTolerance(1e-9));
    CHECK(boxOn(floor.geom, 0.1, 0.2, 0.401).empty());
}

TEST_CASE("a trimesh's triangle callbacks are honoured", "[trimesh][ode]") {
    OdeSession session(true);
    Floor floor(nullptr, 8, 0.5, 0.0);
    REQUIRE(boxOn(floor.geom, 0.1, 0.2, 0.149).size() > 0);
    dGeomTriMeshSetCallback(floor.geom, &rejectEvery);
    CHECK(boxOn(floor.geom, 0.1, 0.2, 0.149).empty());
    dGeomTriMeshSetCallback(floor.geom, &acceptEven);
    auto contacts = boxOn(floor.geom, 0.1, 0.2, 0.149);
    REQUIRE(!contacts.empty());
    for (const auto& c : contacts) CHECK(c.side2 % 2 == 0);
    dGeomTriMeshSetCallback(floor.geom, nullptr);

    dGeomTriMeshSetArrayCallback(floor.geom, &recordTriangles);
    arrayCallbackTriangles.clear();
    contacts = boxOn(floor.geom, 0.1, 0.2, 0.149);
    REQUIRE(!contacts.empty());
    REQUIRE(!arrayCallbackTriangles.empty());
    const std::set<int> touched(arrayCallbackTriangles.begin(), arrayCallbackTriangles.end());
    for (const auto& c : contacts) CHECK(touched.count(c.side2) == 1);
    CHECK(touched.size() < 128u);  // the triangles under the box, not the whole floor
    arrayCallbackTriangles.clear();
    CHECK(boxOn(floor.geom, 0.1, 0.2, 1.0).empty());  // far above: no triangle is offered
    CHECK(arrayCallbackTriangles.empty());
}

TEST_CASE("a degenerate triangle in a trimesh's data is skipped", "[trimesh][ode]") {
    OdeSession session(true);
    // A 2 × 2 m square of two triangles at z = 0 and, between them in the index list, a triangle
    // with a repeated index and one with three collinear vertices.
    // Single-precision vertices (dGeomTriMeshDataBuildSingle).
    static const float vertices[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, 0, -1, 0};
    static const dTriIndex indices[] = {0, 1, 2, 1, 1, 2, 0, 4, 1, 0, 2, 3};
    dTriMeshDataID data = dGeomTriMeshDataCreate();
    dGeomTriMeshDataBuildSingle(data, vertices, 3 * sizeof(float), 5, indices, 12, 3 * sizeof(dTriIndex));
    dGeomID mesh = dCreateTriMesh(nullptr, data, nullptr, nullptr, nullptr);
    const auto contacts = boxOn(mesh, 0.1, 0.2, 0.149);
    REQUIRE(contacts.size() >= 4);
    for (const auto& c : contacts) {
        CHECK((c.side2 == 0 || c.side2 == 3));
        CHECK(std::abs(c.normal[2] - 1.0) < realTolerance(1e-9));
    }
    CHECK(std::abs(deepest(contacts) - 1e-3) < realTolerance(1e-9));
    dGeomDestroy(mesh);
    dGeomTriMeshDataDestroy(data);
}

TEST_CASE("spaceCollide and the C API give a trimesh pair dCollide's contacts", "[trimesh][ode]") {
    OdeSession session(true);
    dSpaceID space = dHashSpaceCreate(nullptr);
    {
        Floor floor(space, 8, 0.5, 0.0);
        std::vector<dGeomID> bodies;
        const std::vector<dReal> corners = boxCorners(Vec3(0.2, 0.15, 0.1));
        for (int i = 0; i < 6; ++i) {
            dGeomID geom = i % 2 ? dCreateBox(space, 0.4, 0.3, 0.2)
                                 : gdc::ode::createConvex(space, corners.data(), 8);
            dGeomSetPosition(geom, -1.5 + 0.6 * i, 0.3 * (i % 3), 0.099 - 0.001 * i);
            bodies.push_back(geom);
        }
        struct Seen {
            int pairs = 0, mismatched = 0;
        } seen;
        gdc::ode::spaceCollide(space, 16, &seen, [](void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
            auto& s = *static_cast<Seen*>(data);
            ++s.pairs;
            const auto direct = collideThroughOde(o1, o2, 16);
            if (static_cast<int>(direct.size()) != count) ++s.mismatched;
            for (int i = 0; i < std::min(count, static_cast<int>(direct.size())); ++i)
                if (direct[i].pos[0] != contacts[i].pos[0] || direct[i].normal[2] != contacts[i].normal[2] ||
                    direct[i].depth != contacts[i].depth || direct[i].side1 != contacts[i].side1 ||
                    direct[i].side2 != contacts[i].side2)
                    ++s.mismatched;
        });
        CHECK(seen.pairs == 6);
        CHECK(seen.mismatched == 0);
        for (dGeomID geom : bodies) {
            dContactGeom c[8], d[8];
            const int viaC = gdcCollide(geom, floor.geom, 8, c, sizeof(dContactGeom));
            const int viaOde = dCollide(geom, floor.geom, 8, d, sizeof(dContactGeom));
            CHECK(viaC > 0);
            REQUIRE(viaC == viaOde);
            for (int i = 0; i < viaC; ++i) CHECK((c[i].depth == d[i].depth && c[i].pos[1] == d[i].pos[1]));
        }
        CHECK(gdc::ode::handles(dTriMeshClass, dBoxClass));
        CHECK(gdc::ode::handles(dConvexClass, dTriMeshClass));
        CHECK(!gdc::ode::handles(dSphereClass, dTriMeshClass));
        for (dGeomID geom : bodies) dGeomDestroy(geom);
    }
    dSpaceDestroy(space);
}

TEST_CASE("a plain dCreateConvex on a trimesh keeps ODE's own contacts after install()", "[trimesh][ode]") {
    static const dReal planes[] = {1, 0, 0, 0.5, -1, 0, 0, 0.5, 0, 1, 0, 0.5, 0, -1, 0, 0.5, 0, 0, 1, 0.5, 0, 0, -1, 0.5};
    static const dReal points[] = {-0.5, -0.5, -0.5, 0.5, -0.5, -0.5, 0.5, 0.5, -0.5, -0.5, 0.5, -0.5,
                                   -0.5, -0.5, 0.5,  0.5, -0.5, 0.5,  0.5, 0.5, 0.5,  -0.5, 0.5, 0.5};
    static const unsigned polygons[] = {4, 1, 2, 6, 5, 4, 0, 4, 7, 3, 4, 3, 7, 6, 2,
                                        4, 0, 1, 5, 4, 4, 4, 5, 6, 7, 4, 0, 3, 2, 1};
    std::vector<dContactGeom> before, after;
    for (int installed = 0; installed < 2; ++installed) {
        OdeSession session(installed == 1);
        Floor floor(nullptr, 8, 0.5, 0.0);
        dGeomTriMeshDataPreprocess2(floor.data, 1U << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES, nullptr);
        dGeomID convex = dCreateConvex(nullptr, planes, 6, points, 8, polygons);
        dGeomSetPosition(convex, 0.1, 0.2, 0.45);
        (installed ? after : before) = collideThroughOde(convex, floor.geom, 8);
        dGeomDestroy(convex);
    }
    INFO("ODE " << dGetConfiguration() << "; " << gdc::ode::detail::describeOdeColliders());
    // As for the other pairs of a plain convex (convex_test.cpp): an ODE whose convex–trimesh gives
    // nothing (built without libccd) gives nothing after install() either; one whose collider the
    // adapter cannot reach (a static ODE) gives none, with its one message; otherwise ODE's
    // contacts, at most Settings::maxContacts (6) of them.
    using gdc::ode::detail::OdeFallback;
    const OdeFallback fallback = gdc::ode::detail::odeColliders().convexTrimesh.fallback;
    if (fallback == OdeFallback::OdeGivesNone) {
        CHECK(before.empty());
        CHECK(after.empty());
        return;
    }
    REQUIRE(!before.empty());
    if (fallback == OdeFallback::Unreachable) {
        CHECK(after.empty());
        return;
    }
    REQUIRE(after.size() == std::min<std::size_t>(before.size(), 6));
    for (std::size_t i = 0; i < after.size(); ++i) {
        CHECK(after[i].depth == before[i].depth);
        CHECK(after[i].normal[2] == before[i].normal[2]);
    }
}

// createConvex takes what dCreateConvex takes: data rounded to 6 significant digits, planes
// flipped or listed in another order, non-planar or missing faces — the hull of the points, with
// one dMessage where the planes and polygons disagree with the points. createConvexStrict refuses
// the same data, naming the fault.
#include <gdcontact/ode.hpp>

#include "ode_precision.hpp"
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

using namespace gdc;
using namespace gdc::ode::test;

namespace {

std::string messages;
void captureMessage(int, const char* format, va_list arguments) {
    char buffer[4096];
    std::vsnprintf(buffer, sizeof buffer, format, arguments);
    messages += buffer;
    messages += '\n';
}
int messageCount() {
    return static_cast<int>(std::count(messages.begin(), messages.end(), '\n'));
}
struct CapturedMessages {
    dMessageFunction* previous = dGetMessageHandler();
    CapturedMessages() {
        messages.clear();
        dSetMessageHandler(&captureMessage);
    }
    ~CapturedMessages() { dSetMessageHandler(previous); }
};

// A value as a program would have it after printing it with 6 significant digits ("%g").
double rounded(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", value);
    return std::strtod(text, nullptr);
}

// dCreateConvex's layout of a polytope, every number rounded to 6 significant digits.
struct OdeData {
    std::vector<dReal> planes, points;
    std::vector<unsigned> polygons;
    unsigned planeCount() const { return static_cast<unsigned>(planes.size() / 4); }
    unsigned pointCount() const { return static_cast<unsigned>(points.size() / 3); }
    dGeomID create() const {
        return gdc::ode::createConvex(0, planes.data(), planeCount(), points.data(), pointCount(), polygons.data());
    }
    dGeomID createStrict() const {
        return gdc::ode::createConvexStrict(0, planes.data(), planeCount(), points.data(), pointCount(),
                                            polygons.data());
    }
    // The polygons one by one (offset of each in `polygons`).
    std::vector<std::vector<unsigned>> polygonList() const {
        std::vector<std::vector<unsigned>> list;
        for (std::size_t at = 0; at < polygons.size(); at += polygons[at] + 1)
            list.emplace_back(polygons.begin() + static_cast<long>(at) + 1,
                              polygons.begin() + static_cast<long>(at + 1 + polygons[at]));
        return list;
    }
    void setPolygons(const std::vector<std::vector<unsigned>>& list) {
        polygons.clear();
        for (const auto& polygon : list) {
            polygons.push_back(static_cast<unsigned>(polygon.size()));
            polygons.insert(polygons.end(), polygon.begin(), polygon.end());
        }
    }
};

OdeData roundedData(const Polytope& hull) {
    OdeData data;
    for (const Vec3& vertex : hull.vertices())
        for (int axis = 0; axis < 3; ++axis) data.points.push_back(rounded(vertex[axis]));
    for (const Polytope::Face& face : hull.faces()) {
        for (int axis = 0; axis < 3; ++axis) data.planes.push_back(rounded(face.normal[axis]));
        data.planes.push_back(rounded(face.offset));
        data.polygons.push_back(static_cast<unsigned>(face.count));
        for (int k = 0; k < face.count; ++k)
            data.polygons.push_back(static_cast<unsigned>(hull.faceVertices()[face.first + k]));
    }
    return data;
}

// A random convex hull: 6 to 40 points in an ellipsoid of random axes, at a random scale.
Polytope randomHull(std::mt19937& random) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> count(6, 40);
    const double scale = std::pow(10.0, std::uniform_real_distribution<double>(-2, 2)(random));
    const Vec3 axes(scale * (0.3 + 0.7 * std::abs(unit(random))), scale * (0.3 + 0.7 * std::abs(unit(random))),
                    scale * (0.3 + 0.7 * std::abs(unit(random))));
    std::vector<Vec3> cloud;
    const int n = count(random);
    while (static_cast<int>(cloud.size()) < n) {
        const Vec3 p(unit(random), unit(random), unit(random));
        if (p.norm() <= 1.0) cloud.push_back(p.cwiseProduct(axes) + Vec3(0.1, -0.2, 0.3) * scale);
    }
    return Polytope::fromPoints(cloud);
}

// Every contact of `geom` resting 1 % of its size into a ground plane below it is valid.
void checkRestsOnGround(dGeomID geom, const Polytope& hull) {
    dGeomID ground = dCreatePlane(0, 0, 0, 1, 0);
    double lowest = INFINITY;
    for (const Vec3& v : hull.vertices()) lowest = std::min(lowest, v.z());
    const double sink = 0.01 * hull.radius();
    dGeomSetPosition(geom, 0, 0, -lowest - sink);
    const auto contacts = collideThroughOde(geom, ground, 8);
    REQUIRE(!contacts.empty());
    for (const dContactGeom& contact : contacts) {
        CHECK(toVec(contact.normal).norm() == Approx(1.0).margin(realTolerance(1e-9)));
        CHECK(contact.normal[2] == Approx(1.0).margin(1e-6));
        CHECK(contact.depth >= 0);
        CHECK(contact.depth <= sink * (1 + 1e-3) + 1e-5 * hull.radius());
        CHECK(toVec(contact.pos).allFinite());
    }
    dGeomDestroy(ground);
}

}  // namespace

TEST_CASE("rounded hulls of random point clouds are taken silently, as given, and rest on a plane",
          "[ode][convex][data]") {
    OdeSession session;
    CapturedMessages captured;
    std::mt19937 random(12);
    for (int trial = 0; trial < 40; ++trial) {
        INFO("trial " << trial);
        const Polytope exact = randomHull(random);
        const OdeData data = roundedData(exact);
        dGeomID geom = data.create();
        const auto hull = gdc::ode::polytopeOf(geom);
        REQUIRE(hull);
        CHECK(hull->volume() == Approx(exact.volume()).epsilon(1e-4));
        checkRestsOnGround(geom, *hull);
        dGeomDestroy(geom);
        dGeomDestroy(data.createStrict());  // strict takes correct data rounded to 6 digits too
    }
    CHECK(messages.empty());
}

TEST_CASE("a large rounded mesh (hundreds of faces) is taken silently", "[ode][convex][data]") {
    OdeSession session;
    CapturedMessages captured;
    // 400 points on an ellipsoid (a Fibonacci lattice): about 800 triangles.
    std::vector<Vec3> cloud;
    const int n = 400;
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1 - z * z), phi = 2.399963229728653 * i;
        cloud.emplace_back(2.0 * r * std::cos(phi), 1.3 * r * std::sin(phi), 0.8 * z);
    }
    const Polytope exact = Polytope::fromPoints(cloud);
    REQUIRE(exact.faces().size() >= 300);
    const OdeData data = roundedData(exact);
    dGeomID geom = data.create();
    const auto hull = gdc::ode::polytopeOf(geom);
    REQUIRE(hull);
    CHECK(hull->volume() == Approx(exact.volume()).epsilon(1e-5));
    checkRestsOnGround(geom, *hull);
    // A box dropped onto it gets valid contacts.
    dGeomID box = dCreateBox(0, 0.5, 0.5, 0.5);
    dGeomSetPosition(geom, 0, 0, 0);
    dGeomSetPosition(box, 0.1, 0.05, 0.8 + 0.25 - 0.01);
    const auto contacts = collideThroughOde(box, geom, 8);
    REQUIRE(!contacts.empty());
    for (const dContactGeom& contact : contacts) {
        CHECK(toVec(contact.normal).norm() == Approx(1.0).margin(realTolerance(1e-9)));
        CHECK(contact.normal[2] > 0.9);  // from the mesh (o2) into the box (o1): up
        CHECK(contact.depth >= 0);
        CHECK(contact.depth < 0.02);
    }
    dGeomDestroy(box);
    dGeomDestroy(geom);
    CHECK(messages.empty());
}

TEST_CASE("planes and polygons that disagree with the points: the hull of the points, one message, strict refuses",
          "[ode][convex][data]") {
    OdeSession session;
    // Each kind of disagreement on every trial (Catch's SECTIONs inside the loop ran one kind on
    // the first trial only, and left the other trials' data consistent).
    const char* const kinds[] = {"flipped normals", "planes listed in another order than their polygons",
                                 "polygons wound the other way", "a missing face",
                                 "a non-planar face: one point moved off its faces by 2 % of the size"};
    std::mt19937 random(7);
    for (int run = 0; run < 5 * 10; ++run) {
        const int kind = run / 10, trial = run % 10;
        const Polytope exact = randomHull(random);
        OdeData data = roundedData(exact);
        const unsigned planes = data.planeCount();
        std::string expected;
        if (kind == 0) {  // flipped normals
            for (unsigned p = 0; p < planes; p += 2)
                for (int k = 0; k < 4; ++k) data.planes[4 * p + k] = -data.planes[4 * p + k];
            expected = "plane 0";
        }
        if (kind == 1) {  // planes listed in another order than their polygons
            std::vector<unsigned> order(planes);
            for (unsigned p = 0; p < planes; ++p) order[p] = p;
            std::rotate(order.begin(), order.begin() + 1, order.end());
            std::vector<dReal> shuffled;
            for (unsigned p : order) shuffled.insert(shuffled.end(), data.planes.begin() + 4 * p, data.planes.begin() + 4 * p + 4);
            data.planes = shuffled;
            expected = "does not pass through its polygon";
        }
        if (kind == 2) {  // polygons wound the other way
            auto list = data.polygonList();
            for (auto& polygon : list) std::reverse(polygon.begin(), polygon.end());
            data.setPolygons(list);
            expected = "clockwise";
        }
        if (kind == 3) {  // a missing face
            auto list = data.polygonList();
            list.pop_back();
            data.setPolygons(list);
            data.planes.resize(data.planes.size() - 4);
            expected = "closed surface";
        }
        if (kind == 4) {  // a non-planar face: one point moved off its faces by 2 % of the size
            const int vertex = exact.faceVertices()[exact.faces()[0].first];
            for (int axis = 0; axis < 3; ++axis)
                data.points[3 * vertex + axis] += 0.02 * exact.radius() * exact.faces()[0].normal[axis];
            expected = "plane";
        }
        INFO(kinds[kind] << ", trial " << trial);
        CapturedMessages captured;
        dGeomID geom = data.create();
        const auto hull = gdc::ode::polytopeOf(geom);
        REQUIRE(hull);
        std::vector<Vec3> cloud;
        for (unsigned i = 0; i < data.pointCount(); ++i)
            cloud.emplace_back(data.points[3 * i], data.points[3 * i + 1], data.points[3 * i + 2]);
        CHECK(hull->volume() == Approx(Polytope::fromPoints(cloud).volume()).epsilon(1e-9));
        CHECK(messageCount() == 1);
        CHECK_THAT(messages, Catch::Contains(expected) && Catch::Contains("convex hull") &&
                                 Catch::Contains("createConvexStrict"));
        checkRestsOnGround(geom, *hull);
        // ODE was given the hull's planes: its own (plane-based) sphere collider agrees with it.
        dGeomSetPosition(geom, 0, 0, 0);
        Vec3 centre = hull->vertices()[0];  // the hull's top vertex: on its surface
        for (const Vec3& v : hull->vertices())
            if (v.z() > centre.z()) centre = v;
        dGeomID sphere = dCreateSphere(0, 0.1 * hull->radius());
        dGeomSetPosition(sphere, centre.x(), centre.y(), centre.z());
        const auto sphereContacts = collideThroughOde(sphere, geom, 4);
        CHECK(!sphereContacts.empty());  // the sphere's centre is on or in the hull
        for (const dContactGeom& contact : sphereContacts) CHECK(contact.depth >= 0);
        dGeomDestroy(sphere);
        dGeomDestroy(geom);
        CHECK_THROWS_WITH(data.createStrict(), Catch::Contains(expected));
    }
}

TEST_CASE("points no polygon names (inside, or outside by rounding) are taken silently, and the geom stays gdcontact's",
          "[ode][convex][data]") {
    OdeSession session;
    CapturedMessages captured;
    OdeData cube = roundedData(Polytope::box(Vec3(0.5, 0.5, 0.5)));
    cube.points.insert(cube.points.end(), {0.0, 0.0, 0.0});        // the centre
    cube.points.insert(cube.points.end(), {0.5 + 4e-6, 0.1, 0.2});  // outside +x by rounding
    dGeomID geom = cube.create();
    const auto hull = gdc::ode::polytopeOf(geom);
    REQUIRE(hull);
    CHECK(hull->volume() == Approx(1.0).epsilon(1e-5));
    // Tilted and moved: the AABB ODE computes from all 10 points is the hull's, so gdcontact
    // keeps the geom and says nothing (no "dGeomSetConvex" message).
    dGeomID ground = dCreatePlane(0, 0, 0, 1, 0);
    setRotation(geom, rotationAbout(Vec3(0.2, 1, 0.1), 0.3));
    dGeomSetPosition(geom, 0.3, -0.2, 0.6);
    const auto contacts = collideThroughOde(geom, ground, 8);
    CHECK(!contacts.empty());
    CHECK(gdc::ode::polytopeOf(geom) == hull);
    CHECK(messages.empty());
    dGeomDestroy(ground);
    dGeomDestroy(geom);
}

// Issue 21: dCreateConvex data with features down to 1e-7 of the shape's size (a corner cut off a
// box, a roof of two faces 1e-6 rad apart) is what scanned and CAD meshes hold: createConvex takes
// it, in dCreateConvex's own layout and as a point cloud, and the geom rests on a plane.
TEST_CASE("dCreateConvex data with tiny features (cut corners, nearly coplanar faces) is taken", "[ode][convex][data]") {
    OdeSession session;
    for (double cut : {1e-2, 1e-4, 1e-6, 1e-7})
        for (double scale : {1e-3, 1.0, 1e3}) {
            INFO("cut " << cut << ", scale " << scale);
            std::vector<Vec3> points;
            for (int i = 0; i < 8; ++i) {
                const Vec3 c(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 0.5 : -0.5);
                if (i != 7) {
                    points.push_back(scale * c);
                    continue;
                }
                for (const Vec3& towards : {Vec3(-1, 1, 0.5), Vec3(1, -1, 0.5), Vec3(1, 1, -0.5)})
                    points.push_back(scale * (c + cut * (towards - c)));
            }
            points.push_back(scale * Vec3(0, -1, 0.5 + 1e-6));  // a ridge 1e-6 rad high across the top
            points.push_back(scale * Vec3(0, 1, 0.5 + 1e-6));
            const Polytope exact = Polytope::fromPoints(points);
            OdeData data;  // full precision: the layout as a program would pass its own mesh
            for (const Vec3& vertex : exact.vertices())
                for (int axis = 0; axis < 3; ++axis) data.points.push_back(vertex[axis]);
            for (const Polytope::Face& face : exact.faces()) {
                for (int axis = 0; axis < 3; ++axis) data.planes.push_back(face.normal[axis]);
                data.planes.push_back(face.offset);
                data.polygons.push_back(static_cast<unsigned>(face.count));
                for (int k = 0; k < face.count; ++k)
                    data.polygons.push_back(static_cast<unsigned>(exact.faceVertices()[face.first + k]));
            }
            dGeomID geom = data.create();
            REQUIRE(geom);
            const auto hull = gdc::ode::polytopeOf(geom);
            REQUIRE(hull);
            CHECK(hull->volume() == Approx(exact.volume()).epsilon(1e-6));
            checkRestsOnGround(geom, *hull);
            dGeomDestroy(geom);
            dGeomID cloud = gdc::ode::createConvex(0, data.points.data(), data.pointCount());
            REQUIRE(cloud);
            dGeomDestroy(cloud);
        }
}

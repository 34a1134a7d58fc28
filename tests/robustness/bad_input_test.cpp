// Bad input: each kind gets a clear error where it enters — an InvalidInput at creation, or a
// message through ODE's message handler and 0 contacts from the collider — never a crash, NaN or
// garbage contact.
#include "robustness_support.hpp"

#include <gdcontact/ode.hpp>

#include <ode/ode.h>

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

using namespace gdc;
using namespace gdc::robustness;

namespace {

// ODE's message handler has no user pointer, so the messages of the current test are collected
// here (tests run one at a time).
std::vector<std::string>& odeMessages() {
    static std::vector<std::string> messages;
    return messages;
}

void collectMessage(int, const char* format, va_list arguments) {
    char text[1024];
    std::vsnprintf(text, sizeof text, format, arguments);
    odeMessages().push_back(text);
}

struct OdeSession {
    OdeSession() {
        dInitODE2(0);
        gdc::ode::install();
        odeMessages().clear();
        dSetMessageHandler(&collectMessage);
    }
    ~OdeSession() {
        dSetMessageHandler(nullptr);
        dCloseODE();
    }
};

bool anyMessageContains(const std::string& fragment) {
    for (const std::string& message : odeMessages())
        if (message.find(fragment) != std::string::npos) return true;
    return false;
}

int collideCount(dGeomID a, dGeomID b) {
    dContactGeom contacts[8];
    return dCollide(a, b, 8, contacts, sizeof(dContactGeom));
}

void setRotation(dGeomID geom, const Mat3& rotation) {
    dMatrix3 matrix;
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) matrix[4 * row + column] = rotation(row, column);
        matrix[4 * row + 3] = 0;
    }
    dGeomSetRotation(geom, matrix);
}

std::vector<dReal> flatten(const std::vector<Vec3>& points) {
    std::vector<dReal> out;
    for (const Vec3& p : points) out.insert(out.end(), {p.x(), p.y(), p.z()});
    return out;
}

}  // namespace

TEST_CASE("core: non-finite poses are refused with a message naming the body", "[robustness][bad]") {
    const Polytope cube = Polytope::box(Vec3::Constant(0.5));
    for (double bad : {NAN, INFINITY, -INFINITY}) {
        Pose position{Mat3::Identity(), Vec3(0, bad, 0)};
        Pose rotation{Mat3::Identity(), Vec3::Zero()};
        rotation.rotation(1, 2) = bad;
        for (const Pose& pose : {position, rotation}) {
            CHECK_THROWS_WITH(collide(cube, pose, cube, Pose{}), Catch::Contains("pose of A is not finite"));
            CHECK_THROWS_WITH(collide(cube, Pose{}, cube, pose), Catch::Contains("pose of B is not finite"));
            CHECK_THROWS_WITH(collide(cube, pose, HalfSpace{}), Catch::Contains("pose of A is not finite"));
        }
    }
}

TEST_CASE("core: zero, negative and non-finite box sizes and degenerate half-spaces are refused", "[robustness][bad]") {
    for (const Vec3& half : {Vec3(0, 1, 1), Vec3(1, -1, 1), Vec3(1, 1, NAN), Vec3(INFINITY, 1, 1)})
        CHECK_THROWS_WITH(Polytope::box(half), Catch::Contains("half extents must be finite and positive"));
    const Polytope cube = Polytope::box(Vec3::Constant(0.5));
    CHECK_THROWS_WITH(collide(cube, Pose{}, HalfSpace{Vec3::Zero(), 0}), Catch::Contains("non-zero"));
    CHECK_THROWS_WITH(collide(cube, Pose{}, HalfSpace{Vec3(NAN, 0, 1), 0}), Catch::Contains("finite"));
    CHECK_THROWS_WITH(collide(cube, Pose{}, HalfSpace{Vec3::UnitZ(), INFINITY}), Catch::Contains("finite"));
    // Finite normals whose plain norm would overflow or underflow (found by the fuzzer: the
    // normal came out zero) are normalised exactly.
    for (double scale : {1e300, 1e-300}) {
        const Manifold m = collide(cube, Pose{Mat3::Identity(), Vec3(0, 0, 0.4)}, HalfSpace{Vec3(0, 0, scale), 0.0});
        REQUIRE(m.pointCount == 4);
        CHECK((m.normal + Vec3::UnitZ()).norm() < 1e-15);
        for (int i = 0; i < 4; ++i) CHECK(m.points[i].depth == Approx(0.1).margin(1e-15));
    }
    // An offset that overflows once the normal is normalised, or a contact beyond the range of
    // doubles (also found by the fuzzer: an infinite position), is refused rather than returned.
    CHECK_THROWS_WITH(collide(cube, Pose{}, HalfSpace{Vec3(0, 0, 1e-10), 1e300}), Catch::Contains("overflows"));
    CHECK_THROWS_WITH(collide(cube, Pose{Mat3::Identity(), Vec3(0, 0, -1.7e308)}, HalfSpace{Vec3(0, 0, 1), 1.7e308}),
                      Catch::Contains("overflows"));
}

TEST_CASE("core: empty, collinear, coplanar, coincident and non-finite point sets are refused", "[robustness][bad]") {
    CHECK_THROWS_WITH(Polytope::fromPoints({}), Catch::Contains("at least 4 points"));
    CHECK_THROWS_WITH(Polytope::fromPoints({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}), Catch::Contains("at least 4 points"));
    std::vector<Vec3> collinear, coplanar, coincident(6, Vec3(1, 2, 3));
    for (int i = 0; i < 6; ++i) collinear.emplace_back(i, 2 * i, -i);
    for (int i = 0; i < 6; ++i) coplanar.emplace_back(std::cos(i), std::sin(i), 0.5);
    for (const auto* points : {&collinear, &coplanar, &coincident})
        CHECK_THROWS_WITH(Polytope::fromPoints(*points), Catch::Contains("no 3-D hull"));
    std::vector<Vec3> withNaN = boxCorners(Vec3::Constant(1));
    withNaN[5].y() = NAN;
    CHECK_THROWS_WITH(Polytope::fromPoints(withNaN), Catch::Contains("point 5 is not finite"));
}

TEST_CASE("core: non-convex and wrongly wound face lists are refused, naming the fault", "[robustness][bad]") {
    const std::vector<Vec3> corners = boxCorners(Vec3::Constant(0.5));
    const std::vector<std::vector<int>> faces = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                                 {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    REQUIRE_NOTHROW(Polytope::fromFaces(corners, faces));
    // Every face reversed (clockwise seen from outside): consistent, but inside out.
    std::vector<std::vector<int>> inverted = faces;
    for (auto& face : inverted) std::reverse(face.begin(), face.end());
    CHECK_THROWS_WITH(Polytope::fromFaces(corners, inverted), Catch::Contains("clockwise"));
    // One face reversed: its edges run the same way as its neighbours'.
    std::vector<std::vector<int>> oneReversed = faces;
    std::reverse(oneReversed[2].begin(), oneReversed[2].end());
    CHECK_THROWS_WITH(Polytope::fromFaces(corners, oneReversed), Catch::Contains("consistently wound"));
    // A dented corner: the faces around it are no longer convex.
    std::vector<Vec3> dented = corners;
    dented[7] = Vec3(0.2, 0.2, 0.2);
    std::vector<std::vector<int>> triangles;
    for (const auto& q : faces) triangles.push_back({q[0], q[1], q[2]}), triangles.push_back({q[0], q[2], q[3]});
    CHECK_THROWS_WITH(Polytope::fromFaces(dented, triangles), Catch::Contains("convex"));
}

TEST_CASE("ODE: non-finite poses give a message through ODE's handler and 0 contacts", "[robustness][bad][ode]") {
    OdeSession session;
    const std::vector<dReal> corners = flatten(boxCorners(Vec3::Constant(0.5)));
    dGeomID box = dCreateBox(0, 1, 1, 1);
    dGeomID convex = gdc::ode::createConvex(0, corners.data(), 8);
    dGeomID other = dCreateBox(0, 1, 1, 1);
    dGeomID plane = dCreatePlane(0, 0, 0, 1, 0);
    for (dGeomID geom : {box, convex}) {
        for (double bad : {NAN, INFINITY}) {
            odeMessages().clear();
            dGeomSetPosition(geom, 0, bad, 0);
            CHECK(collideCount(geom, other) == 0);
            CHECK(collideCount(other, geom) == 0);
            CHECK(collideCount(geom, plane) == 0);
            CHECK(anyMessageContains("not finite"));
            odeMessages().clear();
            dGeomSetPosition(geom, 0, 0, 0.3);
            setRotation(geom, Mat3::Constant(bad));
            CHECK(collideCount(geom, other) == 0);
            CHECK(anyMessageContains("not finite"));
            setRotation(geom, Mat3::Identity());
        }
        REQUIRE(collideCount(geom, other) > 0);  // healthy again once the pose is
    }
    // In a space, through dSpaceCollide (ODE computes NaN bounding boxes): still no contacts.
    dSpaceID space = dSimpleSpaceCreate(0);
    dGeomID a = dCreateBox(space, 1, 1, 1), b = dCreateBox(space, 1, 1, 1);
    dGeomSetPosition(a, NAN, 0, 0);
    int contacts = 0;
    dSpaceCollide(space, &contacts, [](void* data, dGeomID o1, dGeomID o2) {
        dContactGeom out[8];
        *static_cast<int*>(data) += dCollide(o1, o2, 8, out, sizeof(dContactGeom));
    });
    CHECK(contacts == 0);
    (void)b;
    dSpaceDestroy(space);
    for (dGeomID geom : {box, convex, other, plane}) dGeomDestroy(geom);
}

TEST_CASE("ODE: a zero-size box gives a message and 0 contacts, a negative one is refused by ODE (or, without ODE's debug checks, by gdcontact)",
          "[robustness][bad][ode]") {
    {
        OdeSession session;
        dGeomID flat = dCreateBox(0, 1, 0, 1), cube = dCreateBox(0, 1, 1, 1), plane = dCreatePlane(0, 0, 0, 1, 0);
        CHECK(collideCount(flat, cube) == 0);
        CHECK(collideCount(flat, plane) == 0);
        CHECK(anyMessageContains("half extents must be finite and positive"));
        for (dGeomID geom : {flat, cube, plane}) dGeomDestroy(geom);
    }
    // An ODE built without its debug checks (dNODEBUG: ODE's own CMake Release build, unlike
    // Debian's) takes a negative size as it is: then gdcontact refuses it as it does a zero one.
    if (dCheckConfiguration("ODE_EXT_no_debug")) {
        OdeSession session;
        dGeomID negative = dCreateBox(0, -1, 1, 1), cube = dCreateBox(0, 1, 1, 1);
        CHECK(collideCount(negative, cube) == 0);
        CHECK(anyMessageContains("half extents must be finite and positive"));
        for (dGeomID geom : {negative, cube}) dGeomDestroy(geom);
        return;
    }
    // ODE checks box sizes itself (dAASSERT: its debug handler, then abort), before gdcontact
    // could see them: run in a child process and read the message it reports.
    int channel[2];
    REQUIRE(pipe(channel) == 0);
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        static int output;
        output = channel[1];
        dInitODE2(0);
        gdc::ode::install();
        dSetDebugHandler([](int, const char* format, va_list arguments) {
            char text[512];
            const int length = std::vsnprintf(text, sizeof text, format, arguments);
            if (write(output, text, static_cast<std::size_t>(std::max(0, length))) < 0) _exit(4);
            _exit(3);
        });
        dCreateBox(0, -1, 1, 1);
        _exit(0);  // not reached when ODE refuses the size
    }
    close(channel[1]);
    char text[512] = {};
    const ssize_t length = read(channel[0], text, sizeof text - 1);
    close(channel[0]);
    int status = 0;
    waitpid(child, &status, 0);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 3);
    CHECK(length > 0);
    CHECK(std::string(text).find("Bad argument") != std::string::npos);
}

TEST_CASE("ODE: createConvex refuses empty, collinear and coplanar point sets with a clear exception",
          "[robustness][bad][ode]") {
    OdeSession session;
    const std::size_t before = gdc::ode::liveConvexCount();
    const dReal none[1] = {0};
    CHECK_THROWS_WITH(gdc::ode::createConvex(0, none, 0), Catch::Contains("at least 4 points"));
    std::vector<Vec3> collinear, coplanar;
    for (int i = 0; i < 6; ++i) collinear.emplace_back(i, i, i), coplanar.emplace_back(std::cos(i), std::sin(i), 0);
    CHECK_THROWS_WITH(gdc::ode::createConvex(0, flatten(collinear).data(), 6), Catch::Contains("no 3-D hull"));
    CHECK_THROWS_WITH(gdc::ode::createConvex(0, flatten(coplanar).data(), 6), Catch::Contains("no 3-D hull"));
    std::vector<dReal> withInfinity = flatten(boxCorners(Vec3::Constant(1)));
    withInfinity[7] = INFINITY;
    CHECK_THROWS_WITH(gdc::ode::createConvex(0, withInfinity.data(), 8), Catch::Contains("not finite"));
    CHECK(gdc::ode::liveConvexCount() == before);  // nothing half-made is left behind
}

TEST_CASE("ODE: createConvexStrict refuses non-convex and wrongly wound polygons, naming the plane, createConvex takes the hull",
          "[robustness][bad][ode]") {
    OdeSession session;
    // A cube of half size 1 in dCreateConvex's layout; vertex i has the signs of bits x:1, y:2, z:4.
    std::vector<dReal> points = flatten(boxCorners(Vec3::Constant(1)));
    std::vector<dReal> planes = {-1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 0, 1, 0, 1, 0, 1, 0, 0, -1, 1, 0, 0, 1, 1};
    std::vector<unsigned> polygons = {4, 0, 4, 6, 2, 4, 1, 3, 7, 5, 4, 0, 1, 5, 4,
                                      4, 2, 6, 7, 3, 4, 0, 2, 3, 1, 4, 4, 5, 7, 6};
    auto create = [&] { return gdc::ode::createConvexStrict(0, planes.data(), 6, points.data(), 8, polygons.data()); };
    // dCreateConvex takes such data (its libccd collider uses only the points), so createConvex
    // does too: the hull of the points, with a dMessage.
    auto takeHull = [&] {
        dGeomID geom = gdc::ode::createConvex(0, planes.data(), 6, points.data(), 8, polygons.data());
        REQUIRE(gdc::ode::polytopeOf(geom));
        std::vector<Vec3> cloud;
        for (int i = 0; i < 8; ++i) cloud.emplace_back(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
        CHECK(gdc::ode::polytopeOf(geom)->volume() == Approx(Polytope::fromPoints(cloud).volume()));
        dGeomDestroy(geom);
    };
    dGeomID good = create();
    REQUIRE(good);
    dGeomDestroy(good);
    SECTION("a polygon wound clockwise") {
        std::swap(polygons[17], polygons[19]);  // the +y polygon 2,6,7,3 → 2,3,7,6
        CHECK_THROWS_WITH(create(), Catch::Contains("plane 3") && Catch::Contains("clockwise"));
        takeHull();
    }
    SECTION("a dented point: not convex") {
        points[3 * 7 + 0] = points[3 * 7 + 1] = points[3 * 7 + 2] = 0.5;  // the +x+y+z corner pushed in
        CHECK_THROWS_AS(create(), InvalidInput);
        takeHull();
    }
}

TEST_CASE("ODE: a plane with a zero normal is made a valid plane by ODE itself, contacts stay valid",
          "[robustness][bad][ode]") {
    // dCreatePlane and dGeomPlaneSetParams replace a zero normal by (1, 0, 0) without a message
    // (ODE's make_sure_plane_normal_has_unit_length), so gdcontact only ever sees a unit normal;
    // at the core level a zero normal is refused (above).
    OdeSession session;
    dGeomID plane = dCreatePlane(0, 0, 0, 0, 0);
    dVector4 parameters;
    dGeomPlaneGetParams(plane, parameters);
    CHECK(Vec3(parameters[0], parameters[1], parameters[2]).norm() == Approx(1));
    dGeomID box = dCreateBox(0, 1, 1, 1);
    dContactGeom contacts[8];
    const int count = dCollide(box, plane, 8, contacts, sizeof(dContactGeom));
    REQUIRE(count > 0);
    for (int i = 0; i < count; ++i) {
        const Vec3 normal(contacts[i].normal[0], contacts[i].normal[1], contacts[i].normal[2]);
        CHECK(normal.allFinite());
        CHECK(normal.norm() == Approx(1).margin(1e-12));
        CHECK(contacts[i].depth >= 0);
    }
    dGeomDestroy(box);
    dGeomDestroy(plane);
}

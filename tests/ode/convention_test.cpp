// ODE's contact convention, for every pair gdcontact takes over and in both argument orders:
// normal from o2 into o1 (unit), depth ≥ 0, pos in the overlap, g1/g2 as received,
// side1 = side2 = -1, count ≤ maxc, stride honoured, mirrored answers.
#include <gdcontact/ode.hpp>

#include "ode_precision.hpp"
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <string>

using namespace gdc;
using namespace gdc::ode::test;

namespace {

enum class ShapeKind { Box, Convex, Plane };

const char* nameOf(ShapeKind kind) {
    switch (kind) {
        case ShapeKind::Box: return "box";
        case ShapeKind::Convex: return "convex";
        default: return "plane";
    }
}

// A unit cube (dBox or createConvex) or the ground plane z ≤ 0.
dGeomID makeShape(ShapeKind kind) {
    switch (kind) {
        case ShapeKind::Box: return dCreateBox(0, 1, 1, 1);
        case ShapeKind::Convex: {
            const auto corners = boxCorners(Vec3::Constant(0.5));
            return gdc::ode::createConvex(0, corners.data(), 8);
        }
        default: return dCreatePlane(0, 0, 0, 1, 0);
    }
}

// The scene of every convention test: a "lower" shape whose top face is z = 0 (a cube centred at
// z = -0.5, or the plane) and an upper unit cube sunk 0.01 into it, shifted by 0.3 in x and turned
// 30° about z. The exact answer: normal ±z, depth 0.01, contact points on the overlap of the two
// squares (cube on cube) or on the upper cube's bottom face (cube on plane).
struct Scene {
    dGeomID lower, upper;
    static constexpr double kDepth = 0.01;
    Scene(ShapeKind lowerKind, ShapeKind upperKind) : lower(makeShape(lowerKind)), upper(makeShape(upperKind)) {
        if (lowerKind != ShapeKind::Plane) dGeomSetPosition(lower, 0, 0, -0.5);
        dGeomSetPosition(upper, 0.3, 0, 0.5 - kDepth);
        setRotation(upper, rotationAbout(Vec3::UnitZ(), 30.0 * M_PI / 180.0));
    }
    ~Scene() {
        dGeomDestroy(lower);
        dGeomDestroy(upper);
    }
};

// Is p (in the xy plane) inside the upper cube's footprint and, if the lower one is a cube, its?
bool insideFootprints(const Vec3& p, bool lowerIsCube) {
    const Mat3 turn = rotationAbout(Vec3::UnitZ(), 30.0 * M_PI / 180.0);
    const Vec3 local = turn.transpose() * (p - Vec3(0.3, 0, 0));
    const double slack = realTolerance(1e-9);
    if (std::abs(local.x()) > 0.5 + slack || std::abs(local.y()) > 0.5 + slack) return false;
    if (lowerIsCube && (std::abs(p.x()) > 0.5 + slack || std::abs(p.y()) > 0.5 + slack)) return false;
    return true;
}

void checkConvention(const std::vector<dContactGeom>& contacts, dGeomID o1, dGeomID o2,
                     double expectedNormalZ, bool lowerIsCube, int maxContacts) {
    REQUIRE(!contacts.empty());
    REQUIRE(static_cast<int>(contacts.size()) <= maxContacts);
    for (const dContactGeom& contact : contacts) {
        CHECK(contact.g1 == o1);
        CHECK(contact.g2 == o2);
        CHECK(contact.side1 == -1);
        CHECK(contact.side2 == -1);
        const Vec3 normal = toVec(contact.normal);
        CHECK(normal.norm() == Approx(1.0).margin(realTolerance(1e-12)));
        CHECK(normal.z() == Approx(expectedNormalZ).margin(realTolerance(1e-9)));
        CHECK(contact.depth >= 0.0);
        CHECK(contact.depth == Approx(Scene::kDepth).margin(realTolerance(1e-9)));
        const Vec3 position = toVec(contact.pos);
        // Between the upper cube's bottom (z = -0.01) and the lower top (z = 0), inside both.
        CHECK(position.z() >= -Scene::kDepth - realTolerance(1e-9));
        CHECK(position.z() <= realTolerance(1e-9));
        CHECK(insideFootprints(position, lowerIsCube));
    }
}

}  // namespace

TEST_CASE("every supported pair follows ODE's contact convention in both orders", "[ode][convention]") {
    OdeSession session;
    const ShapeKind lowers[] = {ShapeKind::Box, ShapeKind::Convex, ShapeKind::Plane};
    const ShapeKind uppers[] = {ShapeKind::Box, ShapeKind::Convex};
    for (ShapeKind lowerKind : lowers)
        for (ShapeKind upperKind : uppers)
            for (int maxContacts : {1, 2, 3, 4, 8, 16}) {
                DYNAMIC_SECTION(nameOf(upperKind) << " on " << nameOf(lowerKind) << ", maxc " << maxContacts) {
                    Scene scene(lowerKind, upperKind);
                    const bool lowerIsCube = lowerKind != ShapeKind::Plane;
                    // Upper as o1: the normal from o2 (lower) into o1 (upper) points up.
                    const auto upFirst = collideThroughOde(scene.upper, scene.lower, maxContacts);
                    checkConvention(upFirst, scene.upper, scene.lower, +1.0, lowerIsCube, maxContacts);
                    const auto downFirst = collideThroughOde(scene.lower, scene.upper, maxContacts);
                    checkConvention(downFirst, scene.lower, scene.upper, -1.0, lowerIsCube, maxContacts);
                    // Mirrored: the same points and depths, opposite normals.
                    REQUIRE(upFirst.size() == downFirst.size());
                    for (std::size_t i = 0; i < upFirst.size(); ++i) {
                        CHECK(toVec(upFirst[i].pos) == toVec(downFirst[i].pos));
                        CHECK(upFirst[i].depth == downFirst[i].depth);
                        CHECK(toVec(upFirst[i].normal) == -toVec(downFirst[i].normal));
                    }
                    // The same through a direct call (no ODE dispatch, no reversal by ODE).
                    std::vector<dContactGeom> direct(static_cast<std::size_t>(maxContacts));
                    const int count = gdc::ode::collide(scene.upper, scene.lower, maxContacts, direct.data(),
                                                        sizeof(dContactGeom));
                    direct.resize(static_cast<std::size_t>(count));
                    checkConvention(direct, scene.upper, scene.lower, +1.0, lowerIsCube, maxContacts);
                }
            }
}

TEST_CASE("a cube overlapping a cube face gets the four corners of the overlap rectangle", "[ode][convention]") {
    OdeSession session;
    for (ShapeKind kind : {ShapeKind::Box, ShapeKind::Convex}) {
        dGeomID lower = makeShape(kind), upper = makeShape(kind);
        dGeomSetPosition(lower, 0, 0, -0.5);
        dGeomSetPosition(upper, 0.3, -0.2, 0.49);  // axis-aligned: the overlap is [-0.2,0.5]×[-0.5,0.3]
        const auto contacts = collideThroughOde(upper, lower, 8);
        REQUIRE(contacts.size() == 4);
        for (double x : {-0.2, 0.5})
            for (double y : {-0.5, 0.3}) {
                const bool found = std::any_of(contacts.begin(), contacts.end(), [&](const dContactGeom& c) {
                    return std::abs(c.pos[0] - x) < realTolerance(1e-9) && std::abs(c.pos[1] - y) < realTolerance(1e-9);
                });
                CHECK(found);
            }
        dGeomDestroy(lower);
        dGeomDestroy(upper);
    }
}

TEST_CASE("contacts are written at the caller's stride and nothing beyond the count", "[ode][convention]") {
    OdeSession session;
    Scene scene(ShapeKind::Box, ShapeKind::Convex);
    std::vector<dContact> records(6);
    std::memset(records.data(), 0x5a, records.size() * sizeof(dContact));
    std::vector<unsigned char> pristine(reinterpret_cast<unsigned char*>(records.data()),
                                        reinterpret_cast<unsigned char*>(records.data()) + records.size() * sizeof(dContact));
    const int maxContacts = 3;
    const int count = dCollide(scene.upper, scene.lower, maxContacts, &records[0].geom, sizeof(dContact));
    REQUIRE(count >= 1);
    REQUIRE(count <= maxContacts);
    const auto* bytes = reinterpret_cast<const unsigned char*>(records.data());
    for (std::size_t i = 0; i < records.size(); ++i) {
        const std::size_t begin = i * sizeof(dContact);
        const std::size_t geomBegin = begin + offsetof(dContact, geom);
        for (std::size_t byte = begin; byte < begin + sizeof(dContact); ++byte) {
            const bool insideWrittenGeom = static_cast<int>(i) < count && byte >= geomBegin &&
                                           byte < geomBegin + sizeof(dContactGeom);
            if (!insideWrittenGeom) REQUIRE(bytes[byte] == pristine[byte]);  // surface, fdir1, later records
        }
        if (static_cast<int>(i) < count) {
            CHECK(records[i].geom.g1 == scene.upper);
            CHECK(records[i].geom.depth == Approx(Scene::kDepth));
        }
    }
}

TEST_CASE("maxc of zero writes nothing and separated shapes give no contacts", "[ode][convention]") {
    OdeSession session;
    Scene scene(ShapeKind::Convex, ShapeKind::Box);
    dContactGeom untouched;
    std::memset(&untouched, 0x33, sizeof untouched);
    dContactGeom probe = untouched;
    CHECK(gdc::ode::collide(scene.upper, scene.lower, 0, &probe, sizeof probe) == 0);
    CHECK(std::memcmp(&probe, &untouched, sizeof probe) == 0);
    dGeomSetPosition(scene.upper, 0.3, 0, 0.5 + 1e-6);  // lifted just clear of the lower cube
    CHECK(collideThroughOde(scene.upper, scene.lower, 4).empty());
    CHECK(collideThroughOde(scene.lower, scene.upper, 4).empty());
}

TEST_CASE("CONTACTS_UNIMPORTANT still gives valid contacts", "[ode][convention]") {
    OdeSession session;
    for (ShapeKind lowerKind : {ShapeKind::Box, ShapeKind::Convex, ShapeKind::Plane}) {
        Scene scene(lowerKind, ShapeKind::Box);
        const auto contacts = collideThroughOde(scene.upper, scene.lower, 4, CONTACTS_UNIMPORTANT);
        checkConvention(contacts, scene.upper, scene.lower, +1.0, lowerKind != ShapeKind::Plane, 4);
    }
}

TEST_CASE("install's contact limit caps what dCollide returns", "[ode][convention]") {
    Settings settings;
    settings.maxContacts = 2;
    OdeSession session(true, settings);
    Scene scene(ShapeKind::Box, ShapeKind::Box);
    const auto contacts = collideThroughOde(scene.upper, scene.lower, 8);
    CHECK(contacts.size() == 2);
    checkConvention(contacts, scene.upper, scene.lower, +1.0, true, 2);
}

TEST_CASE("install rejects settings out of range", "[ode][convention]") {
    OdeSession session(false);
    Settings settings;
    settings.maxContacts = 0;
    CHECK_THROWS_AS(gdc::ode::install(settings), InvalidInput);
    settings = Settings{};
    settings.angularTolerance = -1;
    CHECK_THROWS_WITH(gdc::ode::install(settings), Catch::Contains("angularTolerance"));
}

TEST_CASE("a tilted plane gives its own normal in ODE's direction", "[ode][convention]") {
    OdeSession session;
    const Vec3 up = Vec3(1, 2, 5).normalized();
    dGeomID plane = dCreatePlane(0, up.x(), up.y(), up.z(), 0.7);
    dGeomID box = dCreateBox(0, 1, 2, 0.5);
    setRotation(box, rotationAbout(Vec3(3, -1, 2), 0.7));
    dGeomSetPosition(box, up.x() * 0.9, up.y() * 0.9, up.z() * 0.9);  // centre 0.2 above the plane
    for (auto [o1, o2, sign] : {std::tuple{box, plane, 1.0}, std::tuple{plane, box, -1.0}}) {
        const auto contacts = collideThroughOde(o1, o2, 8);
        REQUIRE(!contacts.empty());
        // Exact depth of the deepest box corner below the plane.
        const Pose pose = gdc::ode::poseOf(box);
        double deepest = 0;
        for (const Vec3& corner : gdc::ode::polytopeOf(box)->vertices())
            deepest = std::max(deepest, 0.7 - up.dot(pose.apply(corner)));
        double reportedDeepest = 0;
        for (const dContactGeom& contact : contacts) {
            CHECK((toVec(contact.normal) - sign * up).norm() < realTolerance(1e-12));
            reportedDeepest = std::max(reportedDeepest, static_cast<double>(contact.depth));
            CHECK(contact.g1 == o1);
        }
        CHECK(reportedDeepest == Approx(deepest).margin(realTolerance(1e-9)));
    }
    dGeomDestroy(plane);
    dGeomDestroy(box);
}

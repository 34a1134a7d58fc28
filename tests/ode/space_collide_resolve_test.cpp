// gdc::ode::spaceCollide resolves each of its pairs once, on the broad phase's thread (classes,
// polytopes, poses, plane: src/ode/resolved_pair.hpp), and collides the resolved pair on the pool.
// These scenes check that this gives, bit for bit, what dCollide gives pair by pair (which resolves
// and collides in one call), for every pair class and thread count — including scenes with more
// box sizes than a thread's box cache keeps and more planes than its plane cache keeps, where a
// pair resolved early must not see a cache slot refilled by a pair resolved later.
#include <gdcontact/ode.hpp>

#include "ode/ode_internals.hpp"
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace gdc;
using namespace gdc::ode::test;

namespace {

constexpr int kMaxContacts = 16;

struct Reported {
    dGeomID o1, o2;
    std::vector<unsigned char> bytes;  // every contact's meaningful fields
    bool operator==(const Reported& other) const { return o1 == other.o1 && o2 == other.o2 && bytes == other.bytes; }
};

void append(std::vector<unsigned char>& bytes, const void* data, std::size_t size) {
    const auto* begin = static_cast<const unsigned char*>(data);
    bytes.insert(bytes.end(), begin, begin + size);
}

void record(std::vector<Reported>& out, dGeomID o1, dGeomID o2, const dContactGeom* contacts, int count) {
    Reported reported{o1, o2, {}};
    for (int i = 0; i < count; ++i) {
        const dContactGeom& c = contacts[i];
        append(reported.bytes, c.pos, 3 * sizeof(dReal));  // pos[3], normal[3]: padding ODE leaves unset
        append(reported.bytes, c.normal, 3 * sizeof(dReal));
        append(reported.bytes, &c.depth, sizeof c.depth);
        append(reported.bytes, &c.g1, sizeof c.g1);
        append(reported.bytes, &c.g2, sizeof c.g2);
        append(reported.bytes, &c.side1, sizeof c.side1);
        append(reported.bytes, &c.side2, sizeof c.side2);
    }
    out.push_back(std::move(reported));
}

void recordHandler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
    record(*static_cast<std::vector<Reported>*>(data), o1, o2, contacts, count);
}

void recordNearCallback(void* data, dGeomID o1, dGeomID o2) {
    dContactGeom contacts[kMaxContacts];
    const int count = dCollide(o1, o2, kMaxContacts, contacts, sizeof(dContactGeom));
    if (count > 0) record(*static_cast<std::vector<Reported>*>(data), o1, o2, contacts, count);
}

std::string classOf(dGeomID geom) {
    switch (dGeomGetClass(geom)) {
        case dBoxClass: return "box";
        case dPlaneClass: return "plane";
        case dSphereClass: return "sphere";
        case dConvexClass: return gdc::ode::polytopeOf(geom) ? "hull" : "plain convex";
        default: return "other";
    }
}

std::string pairClass(dGeomID o1, dGeomID o2) {
    std::string a = classOf(o1), b = classOf(o2);
    if (b < a) std::swap(a, b);
    return a + "-" + b;
}

// A random heap near the origin: boxes of many sizes, createConvex hulls, a plain dCreateConvex,
// spheres, each on its own moving body, over several tilted planes.
struct Scene {
    dWorldID world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(0);
    std::vector<dReal> plainPoints, plainPlanes;
    std::vector<unsigned> plainPolygons;

    Scene(std::mt19937_64& random, int boxSizes, int planes) {
        std::uniform_real_distribution<double> unit(-1.0, 1.0), size(0.2, 0.6), tilt(-0.15, 0.15);
        for (int i = 0; i < planes; ++i) dCreatePlane(space, tilt(random), tilt(random), 1.0, 0.05 * i - 0.1);
        auto place = [&](dGeomID geom) {
            dBodyID body = dBodyCreate(world);
            dGeomSetBody(geom, body);
            dBodySetPosition(body, 0.9 * unit(random), 0.9 * unit(random), 0.3 + 0.4 * (unit(random) + 1.0));
            const Mat3 rotation = randomRotation(random);
            dMatrix3 r;
            for (int row = 0; row < 3; ++row) {
                for (int column = 0; column < 3; ++column) r[4 * row + column] = rotation(row, column);
                r[4 * row + 3] = 0;
            }
            dBodySetRotation(body, r);
        };
        for (int i = 0; i < 2 * boxSizes; ++i) {
            const int sizeIndex = i % boxSizes;
            const double h = 0.25 + 0.03 * sizeIndex;
            place(dCreateBox(space, 2 * h, 1.6 * h, 1.2 * h));
        }
        for (int i = 0; i < 10; ++i) {
            std::vector<dReal> points;
            const double scale = size(random);
            for (int k = 0; k < 20; ++k) {  // on an ellipsoid: 20 points leave the origin inside (ODE checks)
                const Vec3 direction = Vec3(unit(random), unit(random), unit(random)).normalized();
                points.push_back(scale * direction.x());
                points.push_back(0.8 * scale * direction.y());
                points.push_back(0.7 * scale * direction.z());
            }
            place(gdc::ode::createConvex(space, points.data(), 20));
        }
        // A plain dCreateConvex geom (ODE's own collider) and spheres: pairs gdcontact leaves to ODE.
        // ODE's demo cube in dCreateConvex's layout (half size 0.25).
        plainPlanes = {1, 0, 0, 0.25, 0, 1, 0, 0.25, 0, 0, 1, 0.25, -1, 0, 0, 0.25, 0, -1, 0, 0.25, 0, 0, -1, 0.25};
        plainPoints = {0.25, 0.25,  0.25,  -0.25, 0.25, 0.25,  0.25,  -0.25, 0.25,  -0.25, -0.25, 0.25,
                       0.25, 0.25,  -0.25, -0.25, 0.25, -0.25, 0.25, -0.25, -0.25, -0.25, -0.25, -0.25};
        plainPolygons = {4, 0, 2, 6, 4, 4, 1, 0, 4, 5, 4, 0, 1, 3, 2, 4, 3, 1, 5, 7, 4, 2, 3, 7, 6, 4, 5, 4, 6, 7};
        place(dCreateConvex(space, plainPlanes.data(), 6, plainPoints.data(), 8, plainPolygons.data()));
        for (int i = 0; i < 3; ++i) place(dCreateSphere(space, 0.3));
    }
    ~Scene() {
        dSpaceDestroy(space);
        dWorldDestroy(world);
    }
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;
};

}  // namespace

TEST_CASE("spaceCollide's once-resolved pairs give dCollide's contacts bit for bit, every pair class, 1 to 3 threads",
          "[ode][threads][spaceCollide]") {
    // No per-body-pair budget: it reduces a body's contacts with several planes together, which
    // dCollide pair by pair does not (tests/big covers it).
    Settings settings;
    settings.maxBodyPairContacts = 0;
    OdeSession session(true, settings);
    gdc::ode::setPairCacheEnabled(false);  // every answer computed, none repeated from a cache
    std::mt19937_64 random(20261126);
    std::map<std::string, int> touching;  // pairs with contacts, by class
    std::size_t compared = 0;
    for (int sceneIndex = 0; sceneIndex < 30; ++sceneIndex) {
        // Alternately few and many box sizes (a thread keeps 8) and planes (it keeps 4).
        const bool many = sceneIndex % 2 == 1;
        Scene scene(random, many ? 20 : 3, many ? 7 : 1);
        std::vector<Reported> reference;
        dSpaceCollide(scene.space, &reference, &recordNearCallback);
        for (const Reported& pair : reference) ++touching[pairClass(pair.o1, pair.o2)];
        for (int threads : {1, 2, 3}) {
            gdc::ode::setThreadCount(threads);
            std::vector<Reported> reported;
            gdc::ode::spaceCollide(scene.space, kMaxContacts, &reported, &recordHandler);
            INFO("scene " << sceneIndex << ", " << threads << " threads");
            REQUIRE(reported.size() == reference.size());
            for (std::size_t i = 0; i < reported.size(); ++i) {
                INFO("pair " << i << " (" << pairClass(reference[i].o1, reference[i].o2) << ")");
                REQUIRE(reported[i] == reference[i]);
            }
            compared += reported.size();
        }
    }
    gdc::ode::setThreadCount(0);
    gdc::ode::setPairCacheEnabled(true);
    // Every class of pair gdcontact handles, and those it leaves to ODE, did touch — the plain
    // convex's where ODE's own collider gives contacts and can be reached (docs/ode.md, "Plain
    // dCreateConvex geoms"), else none: never other contacts than ODE's.
    using gdc::ode::detail::OdeFallback;
    const gdc::ode::detail::OdeColliders& ode = gdc::ode::detail::odeColliders();
    INFO(gdc::ode::detail::describeOdeColliders());
    for (const char* wanted : {"box-box", "box-hull", "hull-hull", "box-plane", "hull-plane", "box-sphere"}) {
        INFO(wanted);
        CHECK(touching[wanted] >= 5);
    }
    for (auto [wanted, collider] : {std::pair{"box-plain convex", &ode.convexBox},
                                    std::pair{"hull-plain convex", &ode.convexConvex}}) {
        INFO(wanted);
        if (collider->fallback == OdeFallback::OdeCollider)
            CHECK(touching[wanted] >= 5);
        else
            CHECK(touching[wanted] == 0);
    }
    CHECK(compared >= 3000);
}

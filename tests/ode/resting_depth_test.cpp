// Depths of a resting face–face contact lie on one plane. Two flat faces that touch give a
// penetration that is an affine function of the position in the contact plane, so the depths of
// all contacts of one manifold must agree with it; a contact whose depth comes from somewhere else
// (before commit 77949c8, the depth confirmation's ray cast, which overshot on the thin facet of
// A − B that two nearly parallel faces make) breaks it. The pose is the composites scene's at
// t = 2.32 s (tooth 5 of the larger gear, a createConvex box, on the cross's second arm, a dBox),
// read from the scene with dGeomGetPosition/dGeomGetRotation: there the old code reported the
// deepest of the four contacts 5.962e-7 m deep instead of 5.885e-7 m, 1.5e-9 m beyond the pair's
// penetration along the normal. That 8 nm changed the scene's trajectory (docs/results.md,
// "Composites").
#include <gdcontact/ode.hpp>
#include <gdcontact/polytope.hpp>

#include "ode_precision.hpp"
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <vector>

using namespace gdc;
using namespace gdc::ode::test;

namespace {

void setExact(dGeomID geom, const std::array<double, 3>& position, const std::array<double, 12>& rotation) {
    dGeomSetPosition(geom, position[0], position[1], position[2]);
    dMatrix3 matrix;
    for (int k = 0; k < 12; ++k) matrix[k] = rotation[static_cast<std::size_t>(k)];
    dGeomSetRotation(geom, matrix);
}

}  // namespace

TEST_CASE("a resting face pair's contact depths lie on one plane (composites, gear tooth on cross arm)", "[ode][depth]") {
    OdeSession session(false);
    // The scene's shapes: the tooth is Polytope::box's corners through createConvex, the arm a dBox.
    const Polytope tooth = Polytope::box(Vec3(0.05, 0.03, 0.04));
    std::vector<dReal> points;
    for (const Vec3& v : tooth.vertices()) points.insert(points.end(), {v.x(), v.y(), v.z()});
    dGeomID toothGeom = gdc::ode::createConvex(0, points.data(), static_cast<unsigned>(tooth.vertices().size()));
    dGeomID armGeom = dCreateBox(0, 0.08, 0.4, 0.08);
    setExact(toothGeom, {-0x1.98abde80a4048p-3, 0x1.9069669e5b763p-4, 0x1.33313ac33c3a4p-2},
             {0x1.5980bbc63b0b9p-1, -0x1.79d9fd200101bp-1, -0x1.5c0974a53aa0cp-20, 0, 0x1.79d9fd2002d98p-1,
              0x1.5980bbc634a96p-1, 0x1.184f783f47131p-19, 0, -0x1.65bfaf02069efp-21, -0x1.3d94996d44dedp-19,
              0x1.fffffffff95b2p-1, 0});
    setExact(armGeom, {-0x1.2a60398dfcedcp-2, 0x1.34d7967c274ap-6, 0x1.851c9b6843675p-2},
             {0x1.6be80f259f9eep-2, 0x1.de93ffc2ff99dp-1, -0x1.96750746f6ef2p-20, 0, -0x1.de93ffc2fa38fp-1,
              0x1.6be80f25ab666p-2, 0x1.2af43640b59ap-19, 0, 0x1.5fa975881648fp-19, 0x1.4ee236eea8039p-21,
              0x1.fffffffff8064p-1, 0});

    // As the scene asks: the explicit-settings overload, 4 contacts.
    Settings settings;
    settings.maxContacts = 4;
    std::array<dContactGeom, 4> contacts{};
    const int count = gdc::ode::collide(toothGeom, armGeom, 4, contacts.data(), sizeof(dContactGeom), settings);
    REQUIRE(count == 4);
    const Vec3 normal = toVec(contacts[0].normal);
    for (int i = 1; i < count; ++i) REQUIRE(toVec(contacts[static_cast<std::size_t>(i)].normal) == normal);
    REQUIRE(normal.z() < -0.999);  // the arm lies on the tooth: normal from the arm down into the tooth

    // Coordinates in the contact plane; each depth predicted from the other three by the plane
    // through them (the depth is affine there) must match to far below the old 7.7e-9 m error.
    const Vec3 u = normal.unitOrthogonal(), v = normal.cross(u);
    double largestMiss = 0.0;
    for (int out = 0; out < count; ++out) {
        Eigen::Matrix3d m;
        Vec3 depths;
        int row = 0;
        for (int i = 0; i < count; ++i) {
            if (i == out) continue;
            const Vec3 p = toVec(contacts[static_cast<std::size_t>(i)].pos);
            m.row(row) << p.dot(u), p.dot(v), 1.0;
            depths[row++] = contacts[static_cast<std::size_t>(i)].depth;
        }
        const Vec3 plane = m.fullPivLu().solve(depths);
        const Vec3 p = toVec(contacts[static_cast<std::size_t>(out)].pos);
        const double predicted = plane.dot(Vec3(p.dot(u), p.dot(v), 1.0));
        largestMiss = std::max(largestMiss, std::abs(contacts[static_cast<std::size_t>(out)].depth - predicted));
    }
    INFO("largest difference from the plane of the other three depths: " << largestMiss << " m");
    CHECK(largestMiss < realTolerance(1e-12));
    // The deepest is the exact one the certificate keeps (5.885e-7 m), not the cast's 5.962e-7 m.
    double deepest = 0.0;
    for (int i = 0; i < count; ++i) deepest = std::max(deepest, static_cast<double>(contacts[static_cast<std::size_t>(i)].depth));
    CHECK(deepest == Approx(5.8853e-7).margin(realTolerance(1e-11)));

    dGeomDestroy(toothGeom);
    dGeomDestroy(armGeom);
}

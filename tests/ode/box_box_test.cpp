// Box–box through gdcontact on thousands of random poses: ODE's own contact property, checked
// against an exact separating-axis oracle, and agreement with ODE's dBoxBox on face contacts.
#include <gdcontact/ode.h>
#include <gdcontact/ode.hpp>

#include "box_sat.hpp"
#include "ode_precision.hpp"
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <random>

using namespace gdc;
using namespace gdc::ode::test;

namespace {

OrientedBox orientedBoxOf(dGeomID box) {
    dVector3 lengths;
    dGeomBoxGetLengths(box, lengths);
    return OrientedBox{gdc::ode::poseOf(box), 0.5 * toVec(lengths)};
}

// A random overlapping pose: random sizes (up to 7:1 elongation) and orientations; A is moved in
// from a random direction until the oracle says it touches B, then pushed further in by 0.1 %–5 %
// of B's smallest half extent.
void randomOverlap(std::mt19937_64& random, OrientedBox& a, OrientedBox& b) {
    std::uniform_real_distribution<double> extent(0.15, 1.0), push(0.001, 0.05);
    std::normal_distribution<double> gauss;
    a.halfExtents = Vec3(extent(random), extent(random), extent(random));
    b.halfExtents = Vec3(extent(random), extent(random), extent(random));
    a.pose.rotation = randomRotation(random);
    b.pose.rotation = randomRotation(random);
    b.pose.position = Vec3(gauss(random), gauss(random), gauss(random));
    const Vec3 direction = Vec3(gauss(random), gauss(random), gauss(random)).normalized();
    double inside = 0.0, outside = 10.0;  // A at B's centre touches; 10 away it does not
    for (int i = 0; i < 200 && outside - inside > 1e-13; ++i) {
        const double middle = 0.5 * (inside + outside);
        a.pose.position = b.pose.position + middle * direction;
        (boxesTouch(a, b) ? inside : outside) = middle;
    }
    a.pose.position = b.pose.position + (inside - push(random) * b.halfExtents.minCoeff()) * direction;
}

dGeomID makeBox(const OrientedBox& box) {
    dGeomID geom = dCreateBox(0, 2 * box.halfExtents.x(), 2 * box.halfExtents.y(), 2 * box.halfExtents.z());
    setPose(geom, box.pose);
    return geom;
}

}  // namespace

TEST_CASE("random box–box: moving o1 by 0.96·depth along the normal keeps touching, by 1.04·depth separates",
          "[ode][box-box]") {
    OdeSession session;
    std::mt19937_64 random(20100701);
    constexpr int kPoses = 3000;
    int posesWithContacts = 0;
    for (int pose = 0; pose < kPoses; ++pose) {
        OrientedBox a, b;
        randomOverlap(random, a, b);
        REQUIRE(boxesTouch(a, b));
        dGeomID geomA = makeBox(a), geomB = makeBox(b);
        const auto contacts = collideThroughOde(geomA, geomB, 8);
        INFO("pose " << pose);
        REQUIRE(!contacts.empty());  // they overlap, so there must be contacts
        ++posesWithContacts;
        const Vec3 normal = toVec(contacts[0].normal);
        double depth = 0.0;
        for (const dContactGeom& contact : contacts) {
            REQUIRE(toVec(contact.normal) == normal);  // one normal per manifold
            REQUIRE(contact.depth >= 0.0);
            depth = std::max(depth, static_cast<double>(contact.depth));
        }
        REQUIRE(std::abs(normal.norm() - 1.0) < realTolerance(1e-12));
        OrientedBox moved = a;
        moved.pose.position = a.pose.position + 0.96 * depth * normal;
        CHECK(boxesTouch(moved, b));
        moved.pose.position = a.pose.position + 1.04 * depth * normal;
        CHECK_FALSE(boxesTouch(moved, b));
        dGeomDestroy(geomA);
        dGeomDestroy(geomB);
    }
    CHECK(posesWithContacts == kPoses);
}

namespace {

// Signed permutation matrices with determinant +1: the 24 rotations that map a box's face
// normals onto the coordinate axes.
std::vector<Mat3> cubeSymmetries() {
    std::vector<Mat3> result;
    const std::array<std::array<int, 3>, 6> permutations{{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    for (const auto& permutation : permutations)
        for (int signs = 0; signs < 8; ++signs) {
            Mat3 m = Mat3::Zero();
            for (int row = 0; row < 3; ++row) m(row, permutation[row]) = (signs >> row & 1) ? -1.0 : 1.0;
            if (m.determinant() > 0) result.push_back(m);
        }
    return result;
}

// Is every point of `inner` inside the convex hull of `outer`, all projected onto the plane ⟂ n?
bool hullCovers(const std::vector<Vec3>& outer, const std::vector<Vec3>& inner, const Vec3& normal,
                double tolerance) {
    const Vec3 u = normal.unitOrthogonal(), v = normal.cross(u);
    auto project = [&](const Vec3& p) { return Vec2(p.dot(u), p.dot(v)); };
    std::vector<Vec2> points;
    for (const Vec3& p : outer) points.push_back(project(p));
    // Andrew's monotone chain: the hull counter-clockwise.
    std::sort(points.begin(), points.end(), [](const Vec2& l, const Vec2& r) {
        return l.x() < r.x() || (l.x() == r.x() && l.y() < r.y());
    });
    auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
        return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
    };
    std::vector<Vec2> hull;
    for (int pass = 0; pass < 2; ++pass) {
        const std::size_t base = hull.size();
        for (const Vec2& p : points) {
            while (hull.size() >= base + 2 && cross(hull[hull.size() - 2], hull.back(), p) <= 0) hull.pop_back();
            hull.push_back(p);
        }
        hull.pop_back();
        std::reverse(points.begin(), points.end());
    }
    for (const Vec3& point : inner) {
        const Vec2 p = project(point);
        if (hull.size() < 3) {  // a point or segment: distance to it
            double nearest = 1e300;
            for (std::size_t i = 0; i < hull.size(); ++i) {
                const Vec2 a = hull[i], b = hull[(i + 1) % hull.size()];
                const double t = (b - a).squaredNorm() > 0 ? std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0) : 0.0;
                nearest = std::min(nearest, (a + t * (b - a) - p).norm());
            }
            if (nearest > tolerance) return false;
            continue;
        }
        for (std::size_t i = 0; i < hull.size(); ++i) {
            const Vec2 a = hull[i], b = hull[(i + 1) % hull.size()];
            if (cross(a, b, p) / (b - a).norm() < -tolerance) return false;
        }
    }
    return true;
}

}  // namespace

TEST_CASE("install() without settings keeps defaultSettings()' budget: 6 of an octagon in double precision, 8 in single",
          "[ode][box-box][settings]") {
    // A unit cube turned 0.1 rad on another, 1 mm into it: the face pair meets in an octagon.
    // A single-precision ODE's Dantzig LCP meets fewer ties with the octagon whole
    // (docs/install.md, "Single precision: 8 points a face").
    const int expected = kOdeIsDouble ? 6 : 8;
    CHECK(gdc::ode::defaultSettings().maxContacts == expected);
    Settings others = gdc::ode::defaultSettings();  // every other field is gdc::Settings' own
    others.maxContacts = Settings{}.maxContacts;
    CHECK(others == Settings{});
    // The installed settings outlive dCloseODE (a later session's collide() uses them), so both
    // ways in install explicitly: C++ without settings, C with NULL.
    for (bool fromC : {false, true}) {
        INFO((fromC ? "gdcInstall(NULL)" : "gdc::ode::install()"));
        OdeSession session(false);
        if (fromC) REQUIRE(gdcInstall(nullptr) == GDC_OK);
        else gdc::ode::install();
        dGeomID lower = dCreateBox(nullptr, 1, 1, 1), upper = dCreateBox(nullptr, 1, 1, 1);
        dGeomSetPosition(lower, 0, 0, -0.5);
        dGeomSetPosition(upper, 0, 0, 0.499);
        dMatrix3 turn;
        dRFromAxisAndAngle(turn, 0, 0, 1, 0.1);
        dGeomSetRotation(upper, turn);
        std::array<dContactGeom, 16> contacts{};
        const int count = dCollide(upper, lower, 16, contacts.data(), sizeof(dContactGeom));
        CHECK(count == expected);
        for (int i = 0; i < count; ++i) CHECK(contacts[static_cast<std::size_t>(i)].depth > 0);
        dGeomDestroy(lower);
        dGeomDestroy(upper);
    }
}

TEST_CASE("on face contacts gdcontact's normal is dBoxBox's and its points cover dBoxBox's", "[ode][box-box]") {
    // dBoxBox returns every point of the face pair's polygon (up to 8): a budget of 8 keeps them
    // all, so our hull must cover its points (the default budget, 6, may drop two).
    Settings eight;
    eight.maxContacts = 8;
    OdeSession session(true, eight);
    std::mt19937_64 random(1977);
    std::uniform_real_distribution<double> extent(0.15, 1.0), unit(0.0, 1.0), angle(-M_PI, M_PI);
    const std::vector<Mat3> symmetries = cubeSymmetries();
    constexpr int kPoses = 1000;
    int faceContacts = 0;
    for (int pose = 0; pose < kPoses; ++pose) {
        // A rests on a random face of B with parallel faces: B's rotation, times a quarter-turn
        // symmetry, times a random turn about the shared face normal.
        OrientedBox a, b;
        a.halfExtents = Vec3(extent(random), extent(random), extent(random));
        b.halfExtents = Vec3(extent(random), extent(random), extent(random));
        b.pose.rotation = randomRotation(random);
        const int faceAxis = static_cast<int>(unit(random) * 3) % 3;
        const double side = unit(random) < 0.5 ? -1.0 : 1.0;
        const Vec3 faceNormalLocal = side * Vec3::Unit(faceAxis);
        const Mat3 aInB = rotationAbout(faceNormalLocal, angle(random)) *
                          symmetries[static_cast<std::size_t>(unit(random) * symmetries.size()) % symmetries.size()];
        a.pose.rotation = b.pose.rotation * aInB;
        const double aHalfAlongNormal = projectedRadius(OrientedBox{Pose{aInB, Vec3::Zero()}, a.halfExtents}, faceNormalLocal);
        const double push = (0.001 + 0.02 * unit(random)) * std::min(a.halfExtents.minCoeff(), b.halfExtents.minCoeff());
        // Lateral offset: A's centre within B's face, so the footprints overlap broadly.
        Vec3 local = (b.halfExtents[faceAxis] + aHalfAlongNormal - push) * faceNormalLocal;
        for (int axis = 0; axis < 3; ++axis)
            if (axis != faceAxis) local[axis] = (2 * unit(random) - 1) * 0.8 * b.halfExtents[axis];
        b.pose.position = Vec3(unit(random), unit(random), unit(random));
        a.pose.position = b.pose.apply(local);

        dGeomID geomA = makeBox(a), geomB = makeBox(b);
        dVector3 pA, pB, sideA, sideB, odeNormal;
        dMatrix3 rA, rB;
        for (int i = 0; i < 3; ++i) {
            pA[i] = a.pose.position[i];
            pB[i] = b.pose.position[i];
            sideA[i] = 2 * a.halfExtents[i];
            sideB[i] = 2 * b.halfExtents[i];
        }
        std::copy(dGeomGetRotation(geomA), dGeomGetRotation(geomA) + 12, rA);
        std::copy(dGeomGetRotation(geomB), dGeomGetRotation(geomB) + 12, rB);
        dContactGeom odeContacts[8];
        dReal odeDepth;
        int returnCode = 0;
        const int odeCount = dBoxBox(pA, rA, sideA, pB, rB, sideB, odeNormal, &odeDepth, &returnCode, 8,
                                     odeContacts, sizeof(dContactGeom));
        const auto ours = collideThroughOde(geomA, geomB, 8);
        INFO("pose " << pose << ", dBoxBox code " << returnCode);
        REQUIRE(!ours.empty());
        if (odeCount > 0 && returnCode >= 1 && returnCode <= 6) {
            ++faceContacts;
            // dBoxBox's normal points from box 1 into box 2; ODE's convention is the opposite.
            const Vec3 expected = -toVec(odeNormal).normalized();
            const Vec3 normal = toVec(ours[0].normal);
            CHECK(std::atan2(normal.cross(expected).norm(), normal.dot(expected)) < 1e-6);
            std::vector<Vec3> ourPoints, odePoints;
            for (const dContactGeom& c : ours) ourPoints.push_back(toVec(c.pos));
            for (int i = 0; i < odeCount; ++i) odePoints.push_back(toVec(odeContacts[i].pos));
            CHECK(hullCovers(ourPoints, odePoints, expected, realTolerance(1e-9)));
        }
        dGeomDestroy(geomA);
        dGeomDestroy(geomB);
    }
    // Most poses must be face contacts for ODE too, or the comparison says little.
    CHECK(faceContacts > kPoses * 9 / 10);
}

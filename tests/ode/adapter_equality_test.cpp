// The adapter's answer is the core's, bit for bit: on 10^5 random poses of every pair type it
// serves (box–box, box–plane, convex–plane, hull–hull), gdc::ode::collide's contacts equal those
// made from gdc::collide's manifold by ODE's convention as the adapter documents it (collide.cpp,
// writeContacts): the normal from o2 into o1, points shallower than touching dropped, at most
// the caller's limit of the core's best points (the core reduced to that limit), ordered by depth
// (equal depths in the core's order of importance), depth clamped at 0. The adapter computes the
// box–box and box–plane answers in place (detail::collideBoxBoxInto, collideHalfSpaceInto) and
// skips the normal's square root where its squared length is exactly 1; this pins those shortcuts
// to gdc::collide's own path — and the half-space path's face points, which the adapter has the
// core rank only among equal depths (resting poses with exact ties among them), and likewise the
// box–box and general pair paths' points (stacked boxes and box-shaped hulls, ties to the bit).
// The largest difference found is printed (and required to be 0).
#include <gdcontact/ode.hpp>

#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace gdc;
using namespace gdc::ode::test;

namespace {

constexpr int kPosesPerType = 100000;

// The contacts the adapter's convention makes of the core's answer for (o1, o2).
std::vector<dContactGeom> expectedContacts(dGeomID o1, dGeomID o2, int limit, const Settings& installed) {
    const int maxContacts = std::min({limit, installed.maxContacts, kMaxManifoldPoints});
    Settings settings = installed;
    settings.maxContacts = maxContacts;
    const bool planeFirst = dGeomGetClass(o1) == dPlaneClass;
    const bool planeSecond = dGeomGetClass(o2) == dPlaneClass;
    Manifold manifold;
    bool flip;  // the core's A is o2
    double size;
    if (planeFirst || planeSecond) {
        dGeomID body = planeFirst ? o2 : o1, plane = planeFirst ? o1 : o2;
        dVector4 p;
        dGeomPlaneGetParams(plane, p);
        const std::shared_ptr<const Polytope> polytope = gdc::ode::polytopeOf(body);
        manifold = gdc::collide(*polytope, gdc::ode::poseOf(body),
                                HalfSpace{Vec3(p[0], p[1], p[2]).normalized(), p[3]}, settings);
        flip = planeFirst;
        size = polytope->radius();
    } else {
        const Pose pose1 = gdc::ode::poseOf(o1), pose2 = gdc::ode::poseOf(o2);
        const Vec3 &p = pose2.position, &q = pose1.position;
        // The adapter's fixed order of a pair (comesFirst): by position, then by address.
        flip = p.x() != q.x()   ? p.x() < q.x()
               : p.y() != q.y() ? p.y() < q.y()
               : p.z() != q.z() ? p.z() < q.z()
                                : std::less<const void*>{}(o2, o1);
        const std::shared_ptr<const Polytope> a = gdc::ode::polytopeOf(flip ? o2 : o1);
        const std::shared_ptr<const Polytope> b = gdc::ode::polytopeOf(flip ? o1 : o2);
        manifold = gdc::collide(*a, flip ? pose2 : pose1, *b, flip ? pose1 : pose2, settings);
        size = a->radius() + b->radius();
    }
    std::vector<dContactGeom> out;
    if (manifold.empty()) return out;
    Vec3 normal = flip ? manifold.normal : Vec3(-manifold.normal);
    normal /= normal.norm();
    std::vector<int> kept;
    for (int i = 0; i < manifold.pointCount; ++i)
        if (manifold.points[i].depth >= -1e-9 * size && manifold.points[i].position.allFinite()) kept.push_back(i);
    std::stable_sort(kept.begin(), kept.end(),
                     [&](int i, int j) { return manifold.points[i].depth > manifold.points[j].depth; });
    kept.resize(std::min<std::size_t>(kept.size(), static_cast<std::size_t>(maxContacts)));
    if (installed.contactOrder == ContactOrder::DeepestFirst) std::reverse(kept.begin(), kept.end());
    for (int i : kept) {
        dContactGeom c{};
        for (int k = 0; k < 3; ++k) c.pos[k] = manifold.points[i].position[k], c.normal[k] = normal[k];
        c.depth = std::max(manifold.points[i].depth, 0.0);
        c.g1 = o1;
        c.g2 = o2;
        c.side1 = c.side2 = -1;
        out.push_back(c);
    }
    return out;
}

struct Comparison {
    long long calls = 0, contacts = 0, mismatches = 0;
    long long tied = 0;  // calls whose overlapping contacts include two of equal depth (to the bit)
    double largest = 0;  // over positions, normals and depths
};

void compare(dGeomID o1, dGeomID o2, int limit, const Settings& installed, Comparison& result) {
    std::vector<dContact> records(16);
    const int count = gdc::ode::collide(o1, o2, limit, &records[0].geom, sizeof(dContact));
    const std::vector<dContactGeom> expected = expectedContacts(o1, o2, limit, installed);
    ++result.calls;
    result.contacts += count;
    bool tied = false;
    for (std::size_t i = 0; i < expected.size(); ++i)
        for (std::size_t j = i + 1; j < expected.size(); ++j)
            tied = tied || (expected[i].depth > 0 && expected[i].depth == expected[j].depth);
    result.tied += tied;
    if (count != static_cast<int>(expected.size())) {
        ++result.mismatches;
        return;
    }
    for (int i = 0; i < count; ++i) {
        const dContactGeom &got = records[static_cast<std::size_t>(i)].geom, &want = expected[static_cast<std::size_t>(i)];
        double difference = std::abs(got.depth - want.depth);
        for (int k = 0; k < 4; ++k)
            difference = std::max({difference, std::abs(got.pos[k] - want.pos[k]), std::abs(got.normal[k] - want.normal[k])});
        const bool same = difference == 0 && got.g1 == want.g1 && got.g2 == want.g2 && got.side1 == -1 &&
                          got.side2 == -1 && std::signbit(got.depth) == std::signbit(want.depth);
        if (!same) ++result.mismatches;
        result.largest = std::max(result.largest, difference);
    }
}

// Random poses of one pair type: `place` poses the geoms for pose i; each pose is collided in both
// argument orders with a random contact limit.
Comparison run(const std::function<void(std::mt19937_64&, int)>& place, dGeomID g1, dGeomID g2,
               const Settings& installed, std::uint64_t seed) {
    std::mt19937_64 random(seed);
    const int limits[] = {16, 8, 4, 3, 2, 1};
    std::uniform_int_distribution<int> pick(0, 5);
    Comparison result;
    for (int i = 0; i < kPosesPerType; ++i) {
        place(random, i);
        compare(g1, g2, limits[pick(random)], installed, result);
        compare(g2, g1, limits[pick(random)], installed, result);
    }
    return result;
}

Pose randomPose(std::mt19937_64& random, double spread) {
    std::uniform_real_distribution<double> offset(-spread, spread);
    return Pose{randomRotation(random), Vec3(offset(random), offset(random), offset(random))};
}

// A slightly tilted pose (resting faces: many depths within rounding of each other).
Pose nearlyAligned(std::mt19937_64& random, const Vec3& position) {
    std::uniform_real_distribution<double> tilt(-1e-3, 1e-3);
    return Pose{rotationAbout(Vec3(tilt(random), tilt(random), 1).normalized(), tilt(random) * 100), position};
}

// A resting pose whose face's corners tie in depth to the bit (the adapter asks the core to rank
// a face's points only among equal depths, collide.cpp's queryInto): flat on the ground (four
// equal depths), or tilted about one of A's own axes (two pairs of equal depths); the other poses
// nearly aligned (every depth different).
Pose restingWithTies(std::mt19937_64& random, int i, double height) {
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    const Vec3 position(unit(random), unit(random), height + 0.01 * unit(random));
    switch (i % 4) {
        case 1: return Pose{Mat3::Identity(), position};
        case 2: return Pose{rotationAbout(Vec3::UnitX(), 0.002 * unit(random)), position};
        case 3: return Pose{rotationAbout(Vec3::UnitY(), 0.002 * unit(random)), position};
        default: return nearlyAligned(random, position);
    }
}

// Two bodies stacked, the upper's face resting on the lower's, whose contact points tie in depth
// to the bit (the adapter asks the core to rank a pair's points only among equal depths,
// collide.cpp's queryInto): flat (every depth equal), the upper tilted about one of the lower's
// face axes (pairs of equal depths), turned about the vertical (a polygon of equal depths); every
// fourth pose any pose at all (general, every depth different). `lower`, `upper`: half heights.
void placeStacked(std::mt19937_64& random, int i, dGeomID lowerGeom, double lower, dGeomID upperGeom, double upper) {
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    const Vec3 position(0.4 * unit(random), 0.4 * unit(random), lower + upper - 0.005 - 0.01 * unit(random));
    switch (i % 5) {
        case 0:
            setPose(lowerGeom, randomPose(random, 0.6));
            setPose(upperGeom, randomPose(random, 0.6));
            return;
        case 1: setPose(upperGeom, Pose{Mat3::Identity(), position}); break;
        case 2: setPose(upperGeom, Pose{rotationAbout(Vec3::UnitX(), 0.004 * unit(random)), position}); break;
        case 3: setPose(upperGeom, Pose{rotationAbout(Vec3::UnitY(), 0.004 * unit(random)), position}); break;
        default: setPose(upperGeom, Pose{rotationAbout(Vec3::UnitZ(), 2 * unit(random)), position}); break;
    }
    setPose(lowerGeom, Pose{Mat3::Identity(), Vec3::Zero()});
}

void report(const char* type, const Comparison& c) {
    std::printf("adapter = core, %s: %lld calls, %.2f contacts per call, %lld with tied depths, %lld mismatches, "
                "largest difference %g\n",
                type, c.calls, static_cast<double>(c.contacts) / static_cast<double>(c.calls), c.tied, c.mismatches,
                c.largest);
}

void checkEveryPairType(const Settings& installed) {
    OdeSession session(true, installed);
    gdc::ode::setPairCacheEnabled(false);  // every call a query through the path under test
    std::mt19937_64 shapes(7);
    std::uniform_real_distribution<double> extent(0.1, 0.8), unit(-0.5, 0.5);
    dGeomID box1 = dCreateBox(0, 1.0, 0.8, 0.6), box2 = dCreateBox(0, 0.7, 1.4, 0.3);
    std::vector<dReal> cloud;
    for (int i = 0; i < 3 * 20; ++i) cloud.push_back(unit(shapes));
    const std::vector<dReal> corners = boxCorners(Vec3(0.45, 0.35, 0.3));
    dGeomID boxHull = gdc::ode::createConvex(0, corners.data(), 8);
    dGeomID cloudHull = gdc::ode::createConvex(0, cloud.data(), 20);
    dGeomID plane = dCreatePlane(0, 0.1, -0.2, 1.0, 0.05), ground = dCreatePlane(0, 0, 0, 1, 0);

    // Box–box: random poses, and every fourth a face resting on a face, nearly aligned.
    const Comparison boxBox = run(
        [&](std::mt19937_64& random, int i) {
            if (i % 4 == 0) {
                setPose(box1, nearlyAligned(random, Vec3::Zero()));
                setPose(box2, nearlyAligned(random, Vec3(unit(random) * 0.5, unit(random) * 0.5, 0.449 + 1e-3 * unit(random))));
            } else {
                setPose(box1, randomPose(random, 0.6));
                setPose(box2, randomPose(random, 0.6));
            }
        },
        box1, box2, installed, 1);
    report("box-box", boxBox);
    // Box–plane: the tilted plane and the ground, the box near them in any orientation or resting.
    const Comparison boxPlane = run(
        [&](std::mt19937_64& random, int i) {
            const Pose pose = i % 3 == 0 ? nearlyAligned(random, Vec3(unit(random), unit(random), 0.3 + 0.01 * unit(random)))
                                         : randomPose(random, 0.7);
            setPose(box1, pose);
        },
        box1, plane, installed, 2);
    const Comparison boxGround = run([&](std::mt19937_64& random, int i) { setPose(box2, restingWithTies(random, i, 0.15)); },
                                     box2, ground, installed, 3);
    report("box-plane (tilted plane)", boxPlane);
    report("box-plane (ground, resting)", boxGround);
    // Convex–plane: the box-shaped hull and a 20-point cloud's hull.
    const Comparison convexPlane = run(
        [&](std::mt19937_64& random, int i) {
            setPose(boxHull, i % 3 == 0 ? nearlyAligned(random, Vec3(unit(random), unit(random), 0.3 + 0.01 * unit(random)))
                                        : randomPose(random, 0.7));
        },
        boxHull, plane, installed, 4);
    const Comparison cloudPlane = run([&](std::mt19937_64& random, int) { setPose(cloudHull, randomPose(random, 0.5)); },
                                      cloudHull, ground, installed, 5);
    const Comparison boxHullGround = run([&](std::mt19937_64& random, int i) { setPose(boxHull, restingWithTies(random, i, 0.3)); },
                                         boxHull, ground, installed, 8);
    report("convex-plane (box hull)", convexPlane);
    report("convex-plane (box hull, ground, resting)", boxHullGround);
    report("convex-plane (cloud hull)", cloudPlane);
    // Hull–hull: the box-shaped hull against the cloud's hull, and box against hull.
    const Comparison hullHull = run(
        [&](std::mt19937_64& random, int) {
            setPose(boxHull, randomPose(random, 0.5));
            setPose(cloudHull, randomPose(random, 0.5));
        },
        boxHull, cloudHull, installed, 6);
    const Comparison boxHullPair = run(
        [&](std::mt19937_64& random, int) {
            setPose(box1, randomPose(random, 0.6));
            setPose(boxHull, randomPose(random, 0.6));
        },
        box1, boxHull, installed, 7);
    report("hull-hull", hullHull);
    report("box-convex", boxHullPair);
    // Stacks with exact depth ties (and general poses): box on box, box-shaped hull on box, box on
    // box-shaped hull, box-shaped hull on box-shaped hull.
    dGeomID boxHull2 = gdc::ode::createConvex(0, boxCorners(Vec3(0.3, 0.5, 0.2)).data(), 8);
    const Comparison boxStack = run([&](std::mt19937_64& random, int i) { placeStacked(random, i, box1, 0.3, box2, 0.15); },
                                    box1, box2, installed, 9);
    const Comparison hullOnBox = run(
        [&](std::mt19937_64& random, int i) { placeStacked(random, i, box1, 0.3, boxHull, 0.3); }, box1, boxHull,
        installed, 10);
    const Comparison boxOnHull = run(
        [&](std::mt19937_64& random, int i) { placeStacked(random, i, boxHull, 0.3, box2, 0.15); }, boxHull, box2,
        installed, 11);
    const Comparison hullStack = run(
        [&](std::mt19937_64& random, int i) { placeStacked(random, i, boxHull, 0.3, boxHull2, 0.2); }, boxHull,
        boxHull2, installed, 12);
    report("box-box (stacked, resting)", boxStack);
    report("box-convex (hull on box, resting)", hullOnBox);
    report("box-convex (box on hull, resting)", boxOnHull);
    report("convex-convex (stacked, resting)", hullStack);
    for (const Comparison* c : {&boxStack, &hullOnBox, &boxOnHull, &hullStack})
        CHECK(c->tied > c->calls / 4);  // the ties the shortcut must leave to the ranking are there
    dGeomDestroy(boxHull2);

    for (const Comparison* c : {&boxBox, &boxPlane, &boxGround, &convexPlane, &boxHullGround, &cloudPlane, &hullHull,
                                &boxHullPair, &boxStack, &hullOnBox, &boxOnHull, &hullStack}) {
        CHECK(c->calls == 2 * kPosesPerType);
        CHECK(c->contacts > c->calls / 2);  // the poses mostly touch: the comparison has contacts to compare
        CHECK(c->mismatches == 0);
        CHECK(c->largest == 0.0);
    }
    for (dGeomID g : {box1, box2, boxHull, cloudHull, plane, ground}) dGeomDestroy(g);
    gdc::ode::setPairCacheEnabled(true);
}

}  // namespace

TEST_CASE("adapter: contacts equal the core's answer bit for bit on 1e5 poses of every pair type",
          "[ode][equality]") {
    checkEveryPairType(Settings{});
}

TEST_CASE("adapter: contacts equal the core's answer with DeepestFirst and a margin", "[ode][equality]") {
    Settings settings;
    settings.contactOrder = ContactOrder::DeepestFirst;
    settings.margin = 0.01;
    checkEveryPairType(settings);
}

TEST_CASE("adapter: a hull on a plane follows each install()'s angular tolerance on the same thread", "[ode][equality]") {
    // The adapter keeps the hull–plane query's AngularTolerance per thread (issue 23); switching
    // the installed tolerance back and forth must give gdc::collide's answer for the new one
    // each time, not the kept one. The pose is chosen where the two tolerances disagree: a
    // box-shaped hull tilted 0.1 rad onto an edge and sunk so that its whole face is below the
    // plane (the face, within 0.2 rad: four contacts; the edge, not within 0.05: two).
    OdeSession session(true, Settings{});
    gdc::ode::setPairCacheEnabled(false);
    const std::vector<dReal> corners = boxCorners(Vec3(0.45, 0.35, 0.3));
    dGeomID hull = gdc::ode::createConvex(0, corners.data(), 8);
    dGeomID ground = dCreatePlane(0, 0, 0, 1, 0);
    const double tilt = 0.1;
    const double lowest = 0.35 * std::sin(tilt) + 0.3 * std::cos(tilt);  // the lower edge's height below the centre
    setPose(hull, Pose{rotationAbout(Vec3::UnitX(), tilt), Vec3(0, 0, lowest - 0.1)});
    Settings narrow, wide;
    narrow.angularTolerance = 0.05;
    wide.angularTolerance = 0.2;
    REQUIRE(expectedContacts(hull, ground, 16, narrow).size() != expectedContacts(hull, ground, 16, wide).size());
    Comparison result;
    for (const Settings* settings : {&narrow, &wide, &narrow, &wide, &wide, &narrow}) {
        gdc::ode::install(*settings);
        compare(hull, ground, 16, *settings, result);
        compare(ground, hull, 16, *settings, result);
    }
    CHECK(result.calls == 12);
    CHECK(result.mismatches == 0);
    CHECK(result.largest == 0.0);
    for (dGeomID g : {hull, ground}) dGeomDestroy(g);
    gdc::ode::setPairCacheEnabled(true);
}

// The adapter's answer is the core's, bit for bit: on 10^5 random poses of every pair type it
// serves (box–box, box–plane, convex–plane, hull–hull), gdc::ode::collide's contacts equal those
// made from gdc::collide's manifold by ODE's convention as the adapter documents it (collide.cpp,
// writeContacts): the normal from o2 into o1, points shallower than touching dropped (touching:
// within 1e-9 of the pair's size, float's rounding with a single-precision ODE), touching points
// dropped where an overlapping one is there, at most the caller's limit of the core's best
// points (the core reduced to that limit), ordered by depth
// (equal depths in the core's order of importance), depth clamped at 0. The adapter computes its
// answers in place (detail::collidePair, with the plane normalised once per plane) and
// skips the normal's square root where its squared length is exactly 1; this pins those shortcuts
// to gdc::collide's own path — and the half-space path's face points, which the adapter has the
// core rank only among equal depths (resting poses with exact ties among them), and likewise the
// box–box and general pair paths' points (stacked boxes and box-shaped hulls, ties to the bit).
// The largest difference found is printed (and required to be 0).
#include <gdcontact/ode.hpp>

#include "ode/write_contacts.hpp"  // src/: the adapter's write of a manifold
#include "ode_precision.hpp"
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <limits>
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
    double diameter;  // the larger of the shapes' diameters (a plane has none)
    if (planeFirst || planeSecond) {
        dGeomID body = planeFirst ? o2 : o1, plane = planeFirst ? o1 : o2;
        dVector4 p;
        dGeomPlaneGetParams(plane, p);
        const std::shared_ptr<const Polytope> polytope = gdc::ode::polytopeOf(body);
        manifold = gdc::collide(*polytope, gdc::ode::poseOf(body),
                                HalfSpace{Vec3(p[0], p[1], p[2]).normalized(), p[3]}, settings);
        flip = planeFirst;
        size = polytope->radius();
        diameter = 2 * polytope->radius();
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
        diameter = 2 * std::max(a->radius(), b->radius());
    }
    std::vector<dContactGeom> out;
    if (manifold.empty()) return out;
    Vec3 normal = flip ? manifold.normal : Vec3(-manifold.normal);
    normal /= normal.norm();
    // Touching: within 1e-9 of the pair's size below 0 (float's rounding where dReal is float).
    const double touching = realTolerance(1e-9) * size;
    std::vector<int> kept;
    for (int i = 0; i < manifold.pointCount; ++i)
        if (manifold.points[i].depth >= -touching && manifold.points[i].position.allFinite()) kept.push_back(i);
    std::stable_sort(kept.begin(), kept.end(),
                     [&](int i, int j) { return manifold.points[i].depth > manifold.points[j].depth; });
    // The touching tail (depth ≤ 0) left out where the pair has an overlapping point.
    if (!kept.empty() && manifold.points[kept.front()].depth > 0)
        while (!(manifold.points[kept.back()].depth > 0)) kept.pop_back();
    kept.resize(std::min<std::size_t>(kept.size(), static_cast<std::size_t>(maxContacts)));
    const bool loaded = !kept.empty() && manifold.points[kept.front()].depth > installed.loadedDepthFraction * diameter;
    if (installed.contactOrder == ContactOrder::DeepestFirst ||
        (installed.contactOrder == ContactOrder::DeepestFirstWhenLoaded && loaded))
        std::reverse(kept.begin(), kept.end());
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
        double difference = std::abs(static_cast<double>(got.depth) - want.depth);
        for (int k = 0; k < 4; ++k)
            difference = std::max({difference, static_cast<double>(std::abs(got.pos[k] - want.pos[k])),
                                     static_cast<double>(std::abs(got.normal[k] - want.normal[k]))});
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

TEST_CASE("adapter: contacts equal the core's answer with DeepestFirstWhenLoaded", "[ode][equality]") {
    Settings settings;
    settings.contactOrder = ContactOrder::DeepestFirstWhenLoaded;
    settings.loadedDepthFraction = 0.01;  // the test's poses: some pairs deeper, some shallower
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

namespace {

// ---- writeContacts against ODE's convention, written plainly ----
//
// The write of a manifold as dContactGeoms (src/ode/write_contacts.hpp) against the convention it
// documents, spelled out with a stable sort: the points at least touching (depth ≥ −1e-9 of the
// pair's size, widened to float's rounding where dReal is float: realTolerance) with a finite
// position, deepest first with equal depths in the core's order, the touching tail dropped where a
// point overlaps, the first maxContacts of them, reversed for DeepestFirst; the normal from o2
// into o1 made unit (refused with no contact where it is off unit by more than 1e-6, or float's
// rounding where dReal is float), the depth clamped at 0, g1 = o1, g2 = o2, sides −1. Every
// manifold of 10^5 random poses of each pair type is written into arrays filled alike with random bytes: the slots
// past the count and the bytes between contacts at a dContact stride must stay as they were. Each
// call's other inputs are drawn too: either order of the pair, the contact limit, the stride
// (dContactGeom or dContact), DeepestLast, DeepestFirst or DeepestFirstWhenLoaded (reversed where
// the deepest kept point is deeper than the threshold), a core answer or a carried one (then
// some positions not finite); the points shuffled in half the calls, and some depths made equal,
// negative, −0 or 0.

struct WriteComparison {
    long long calls = 0, contacts = 0, mismatches = 0, invalidNormals = 0;
    double largest = 0;  // over the doubles of the written contacts
};

void ignoreMessage(int, const char*, va_list) {}

// The touching tolerance of writeContacts: 1e-9 of the pair's size, or float's rounding where
// dReal is float (a resting depth from float poses is off by ~1e-7; src/ode/write_contacts.hpp).
double touchingToleranceOf(double sizeOfPair) { return realTolerance(1e-9) * sizeOfPair; }

// How far a written normal may be from the convention's: the last bit of a dReal (the division
// by the length, or none where it is 1, each rounded to dReal).
const double kNormalRounding = std::max(1e-15, static_cast<double>(std::numeric_limits<dReal>::epsilon()));

void compareWrites(Manifold manifold, double sizeOfPair, std::mt19937_64& random, WriteComparison& result) {
    std::uniform_int_distribution<int> limitOf(1, kMaxManifoldPoints), coin(0, 1), kindOf(0, 9);
    const bool flip = coin(random) == 1;
    const int maxContacts = limitOf(random);
    std::uniform_int_distribution<int> orderOf(0, 2);
    const ContactOrder order = static_cast<ContactOrder>(orderOf(random));
    // DeepestFirstWhenLoaded's threshold: at one of the manifold's depths (a tie: not loaded), or
    // between them.
    std::uniform_real_distribution<double> fraction(0.0, 1.0);
    const double deepestInManifold =
        manifold.pointCount ? std::max_element(manifold.points.begin(), manifold.points.begin() + manifold.pointCount,
                                               [](const ContactPoint& x, const ContactPoint& y) { return x.depth < y.depth; })
                                  ->depth
                            : 0.0;
    const double loadedDepth = coin(random) ? deepestInManifold : 1.5 * fraction(random) * deepestInManifold;
    const int skip = coin(random) ? static_cast<int>(sizeof(dContact)) : static_cast<int>(sizeof(dContactGeom));
    const bool checkedFinite = kindOf(random) < 7;
    if (coin(random)) std::shuffle(manifold.points.begin(), manifold.points.begin() + manifold.pointCount, random);
    std::uniform_int_distribution<int> pointOf(0, std::max(manifold.pointCount - 1, 0));
    for (int i = 0; i < manifold.pointCount; ++i) {
        ContactPoint& point = manifold.points[static_cast<std::size_t>(i)];
        switch (kindOf(random)) {
            case 0: point.depth = manifold.points[static_cast<std::size_t>(pointOf(random))].depth; break;  // a tie
            case 1: point.depth = -2 * touchingToleranceOf(sizeOfPair); break;    // below touching: dropped
            case 2: point.depth = -0.5 * touchingToleranceOf(sizeOfPair); break;  // touching
            case 3: point.depth = kindOf(random) < 5 ? 0.0 : -0.0; break;
            case 4:
                if (!checkedFinite)  // only a carried answer has them
                    point.position[coin(random) ? 0 : 2] =
                        coin(random) ? std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::infinity();
                break;
            default: break;
        }
    }
    switch (kindOf(random)) {  // the normal: a unit axis (squared length exactly 1), or off unit
        case 0: manifold.normal = Vec3::UnitZ() * (coin(random) ? 1.0 : -1.0); break;
        case 1: manifold.normal *= 1 + 1e-7; break;   // normalised again
        case 2: manifold.normal *= 1 + 2 * realTolerance(1e-6); ++result.invalidNormals; break;  // refused: no contacts
        default: break;
    }
    const dGeomID o1 = reinterpret_cast<dGeomID>(std::uintptr_t{0x1000} + static_cast<std::uintptr_t>(kindOf(random)) * 16);
    const dGeomID o2 = reinterpret_cast<dGeomID>(std::uintptr_t{0x2000});
    std::vector<unsigned char> before(kMaxManifoldPoints * sizeof(dContact));
    for (unsigned char& byte : before) byte = static_cast<unsigned char>(random());
    std::vector<unsigned char> got = before, want = before;
    const int gotCount = gdc::ode::detail::writeContacts(manifold, flip, sizeOfPair, maxContacts, order, loadedDepth, o1, o2,
                                                         reinterpret_cast<dContactGeom*>(got.data()), skip, checkedFinite);
    // The convention, plainly.
    Vec3 normal = flip ? manifold.normal : Vec3(-manifold.normal);
    int wantCount = 0;
    if (std::isfinite(normal.norm()) && std::abs(normal.norm() - 1.0) <= realTolerance(1e-6)) {
        normal /= normal.norm();
        std::vector<const ContactPoint*> kept;
        for (int i = 0; i < manifold.pointCount; ++i) {
            const ContactPoint& point = manifold.points[static_cast<std::size_t>(i)];
            if (point.depth >= -touchingToleranceOf(sizeOfPair) && point.position.allFinite()) kept.push_back(&point);
        }
        std::stable_sort(kept.begin(), kept.end(), [](const ContactPoint* x, const ContactPoint* y) { return x->depth > y->depth; });
        if (!kept.empty() && kept.front()->depth > 0)
            while (!(kept.back()->depth > 0)) kept.pop_back();
        if (static_cast<int>(kept.size()) > maxContacts) kept.resize(static_cast<std::size_t>(maxContacts));
        const bool loaded = !kept.empty() && kept.front()->depth > loadedDepth;
        if (order == ContactOrder::DeepestFirst || (order == ContactOrder::DeepestFirstWhenLoaded && loaded))
            std::reverse(kept.begin(), kept.end());
        wantCount = static_cast<int>(kept.size());
        for (int i = 0; i < wantCount; ++i) {
            // Its bytes as they were first: a single-precision dContactGeom has 4 bytes of padding
            // before g1, which writeContacts leaves as they were (it writes field by field there).
            dContactGeom geom;
            std::memcpy(&geom, want.data() + static_cast<std::ptrdiff_t>(i) * skip, sizeof geom);
            const ContactPoint& point = *kept[static_cast<std::size_t>(i)];
            for (int k = 0; k < 3; ++k) geom.pos[k] = point.position[k], geom.normal[k] = normal[k];
            geom.pos[3] = geom.normal[3] = 0;
            geom.depth = std::max(point.depth, 0.0);
            geom.g1 = o1;
            geom.g2 = o2;
            geom.side1 = geom.side2 = -1;
            std::memcpy(want.data() + static_cast<std::ptrdiff_t>(i) * skip, &geom, sizeof geom);
        }
    }
    ++result.calls;
    result.contacts += wantCount;
    // Normals may differ in the last bit (the division by the length, or none where it is 1).
    bool same = gotCount == wantCount;
    for (int i = 0; same && i < gotCount; ++i) {
        dContactGeom a, b;
        std::memcpy(&a, got.data() + static_cast<std::ptrdiff_t>(i) * skip, sizeof a);
        std::memcpy(&b, want.data() + static_cast<std::ptrdiff_t>(i) * skip, sizeof b);
        for (int k = 0; k < 3; ++k) same = same && std::abs(a.normal[k] - b.normal[k]) <= kNormalRounding;
        std::memcpy(a.normal, b.normal, sizeof a.normal);
        same = same && std::memcmp(&a, &b, sizeof a) == 0;
    }
    // Beyond each contact (at a dContact stride) and past the count: untouched.
    for (std::size_t byte = 0; same && byte < got.size(); ++byte) {
        const std::size_t slot = byte / static_cast<std::size_t>(skip), within = byte % static_cast<std::size_t>(skip);
        if (slot < static_cast<std::size_t>(gotCount) && within < sizeof(dContactGeom)) continue;
        same = got[byte] == before[byte];
    }
    if (!same) ++result.mismatches;
    for (int i = 0; i < std::min(gotCount, wantCount); ++i) {
        dContactGeom a, b;
        std::memcpy(&a, got.data() + static_cast<std::ptrdiff_t>(i) * skip, sizeof a);
        std::memcpy(&b, want.data() + static_cast<std::ptrdiff_t>(i) * skip, sizeof b);
        double difference = std::abs(static_cast<double>(a.depth) - b.depth);
        for (int k = 0; k < 4; ++k)
            difference = std::max({difference, static_cast<double>(std::abs(a.pos[k] - b.pos[k])),
                                     static_cast<double>(std::abs(a.normal[k] - b.normal[k]))});
        if (!(difference <= result.largest)) result.largest = difference;  // a NaN difference stays visible
    }
}

}  // namespace

TEST_CASE("adapter: writeContacts follows ODE's convention on 1e5 manifolds of every pair type",
          "[ode][equality]") {
    OdeSession session(false);
    dMessageFunction* previous = dGetMessageHandler();
    dSetMessageHandler(&ignoreMessage);  // the refused normals' message
    std::mt19937_64 random(17);
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    const Polytope box1 = Polytope::box(Vec3(0.5, 0.4, 0.3)), box2 = Polytope::box(Vec3(0.35, 0.7, 0.15));
    std::vector<Vec3> cloud;
    for (int i = 0; i < 20; ++i) cloud.emplace_back(unit(random), unit(random), unit(random));
    const Polytope cloudHull = Polytope::fromPoints(cloud);
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 0.45 : -0.45, i & 2 ? 0.35 : -0.35, i & 4 ? 0.3 : -0.3);
    const Polytope boxHull = Polytope::fromPoints(corners);
    const HalfSpace ground{Vec3::UnitZ(), 0.0}, tilted{Vec3(0.1, -0.2, 1.0).normalized(), 0.05};
    const auto randomPose = [&](double spread) {
        return Pose{randomRotation(random), Vec3(spread * unit(random), spread * unit(random), spread * unit(random))};
    };
    // Resting poses (flat: equal depths to the bit; tilted about an axis: pairs of them) and others.
    const auto restingPose = [&](int i, double height) {
        const Vec3 position(0.4 * unit(random), 0.4 * unit(random), height + 0.01 * unit(random));
        switch (i % 4) {
            case 0: return Pose{Mat3::Identity(), position};
            case 1: return Pose{rotationAbout(Vec3::UnitX(), 0.004 * unit(random)), position};
            case 2: return Pose{rotationAbout(Vec3::UnitZ(), 2 * unit(random)), position};
            default: return randomPose(1.2);
        }
    };
    struct PairType {
        const char* name;
        std::function<std::pair<Manifold, double>(int)> manifoldOf;  // a manifold and the pair's size
    };
    const std::vector<PairType> types = {
        {"box-box",
         [&](int i) {
             return std::make_pair(gdc::collide(box1, Pose{Mat3::Identity(), Vec3::Zero()}, box2, restingPose(i, 0.449)),
                                   box1.radius() + box2.radius());
         }},
        {"box-plane",
         [&](int i) {
             return std::make_pair(gdc::collide(box1, restingPose(i, 0.29), i % 8 < 4 ? ground : tilted), box1.radius());
         }},
        {"convex-plane",
         [&](int i) {
             const Polytope& hull = i % 2 ? boxHull : cloudHull;
             return std::make_pair(gdc::collide(hull, restingPose(i / 2, 0.29), ground), hull.radius());
         }},
        {"hull-hull",
         [&](int) {
             return std::make_pair(gdc::collide(boxHull, randomPose(1.0), cloudHull, randomPose(1.0)),
                                   boxHull.radius() + cloudHull.radius());
         }},
        {"box-convex",
         [&](int i) {
             return std::make_pair(gdc::collide(box2, Pose{Mat3::Identity(), Vec3::Zero()}, boxHull, restingPose(i, 0.449)),
                                   box2.radius() + boxHull.radius());
         }},
    };
    for (const PairType& type : types) {
        WriteComparison result;
        int poses = 0;
        for (; result.calls < kPosesPerType && poses < 4 * kPosesPerType; ++poses) {
            const std::pair<Manifold, double> answer = type.manifoldOf(poses);
            if (answer.first.empty()) continue;  // the adapter writes nothing then
            compareWrites(answer.first, answer.second, random, result);
        }
        std::printf("writeContacts vs the convention, %s: %lld manifolds, %.2f contacts per call, %lld refused normals, "
                    "%lld mismatches, largest difference %g\n",
                    type.name, result.calls, static_cast<double>(result.contacts) / static_cast<double>(result.calls),
                    result.invalidNormals, result.mismatches, result.largest);
        CHECK(result.calls == kPosesPerType);
        CHECK(result.contacts > result.calls / 2);  // the comparison has contacts to compare
        CHECK(result.mismatches == 0);
        CHECK(result.largest <= kNormalRounding);
    }
    dSetMessageHandler(previous);
}

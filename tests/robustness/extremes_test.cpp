// Issue 7 at the collider level: scale, distance from the origin, thin and elongated shapes,
// near-parallel faces, exact touching, deep overlap, large and noisy hulls, and the overhang that
// misleads the paper's growth-distance normal. Each case asserts against an analytic answer or the
// brute-force oracles of robustness_support.hpp.
#include "robustness_support.hpp"

#include "geometry/growth_distance.hpp"  // the paper's stage-1 normal alone, for the overhang case

#include <catch2/catch.hpp>

using namespace gdc;
using namespace gdc::robustness;

namespace {

Settings allContacts() {
    Settings settings;
    settings.maxContacts = kMaxManifoldPoints;
    return settings;
}

Pose translated(const Pose& pose, const Vec3& shift) { return Pose{pose.rotation, pose.position + shift}; }
Pose scaled(const Pose& pose, double scale) { return Pose{pose.rotation, scale * pose.position}; }

Polytope scaledHull(const Polytope& polytope, double scale) {
    std::vector<Vec3> points;
    for (const Vec3& v : polytope.vertices()) points.push_back(scale * v);
    return polytope.isBox() ? Polytope::box(scale * polytope.boxHalfExtents()) : Polytope::fromPoints(points);
}

// Every point of `actual` matches a point of `expected` (position and depth) within `tolerance`,
// and the counts agree.
bool sameContacts(const Manifold& actual, const Manifold& expected, double tolerance,
                  const Vec3& shift = Vec3::Zero(), double scale = 1.0) {
    if (actual.pointCount != expected.pointCount) return false;
    for (int i = 0; i < actual.pointCount; ++i) {
        bool matched = false;
        for (int j = 0; j < expected.pointCount && !matched; ++j)
            matched = ((actual.points[i].position - shift) / scale - expected.points[j].position).norm() <= tolerance &&
                      std::abs(actual.points[i].depth / scale - expected.points[j].depth) <= tolerance;
        if (!matched) return false;
    }
    return true;
}

// Each contact's point on A lies on A's surface and its point on B on B's (feature contacts).
void requireOnSurfaces(const Manifold& m, const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       double tolerance) {
    for (int i = 0; i < m.pointCount; ++i) {
        const ContactPoint& p = m.points[i];
        CHECK(std::abs(signedDistance(a, poseA, p.position + 0.5 * p.depth * m.normal)) <= tolerance);
        CHECK(std::abs(signedDistance(b, poseB, p.position - 0.5 * p.depth * m.normal)) <= tolerance);
    }
}

// ODE's property: B moved along n by 0.96·depth still touches A, by 1.04·depth it is clear.
void requireSeparatingDepth(const Manifold& m, const Polytope& a, const Pose& poseA, const Polytope& b,
                            const Pose& poseB, double tolerance) {
    REQUIRE_FALSE(m.empty());
    const double depth = m.maxDepth();
    REQUIRE(std::isfinite(depth));
    CHECK(satOverlap(a, poseA, b, translated(poseB, 0.96 * depth * m.normal)) >= -tolerance);
    CHECK(satOverlap(a, poseA, b, translated(poseB, 1.04 * depth * m.normal)) <= tolerance);
}

}  // namespace

TEST_CASE("scale: the same scenes at 1e-3 m and 1e3 m give the same manifold, relative to size",
          "[robustness][scale]") {
    std::mt19937_64 random(1001);
    std::uniform_real_distribution<double> push(0.0, 0.03);
    int compared = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Polytope a = randomHull(random), b = randomHull(random);
        Pose poseA, poseB;
        randomContactPose(random, a, b, push(random), poseA, poseB);
        const Manifold reference = collide(a, poseA, b, poseB, allContacts());
        REQUIRE_FALSE(reference.empty());
        const double size = a.radius() + b.radius();
        for (double scale : {1e-3, 1e3}) {
            const Polytope sa = scaledHull(a, scale), sb = scaledHull(b, scale);
            const Manifold m = collide(sa, scaled(poseA, scale), sb, scaled(poseB, scale), allContacts());
            INFO("trial " << trial << ", scale " << scale);
            CHECK((m.normal - reference.normal).norm() < 1e-9);
            CHECK(sameContacts(m, reference, 1e-9 * size, Vec3::Zero(), scale));
        }
        ++compared;
    }
    // A box resting on a plane, scaled: the same four corners and depth.
    for (double scale : {1e-3, 1.0, 1e3}) {
        const Polytope box = Polytope::box(scale * Vec3(0.5, 0.3, 0.2));
        const Pose pose{rotationAbout(Vec3::UnitZ(), 0.4), scale * Vec3(1, 2, 0.2 - 1e-3)};
        const Manifold m = collide(box, pose, HalfSpace{Vec3::UnitZ(), 0});
        REQUIRE(m.pointCount == 4);
        for (int i = 0; i < 4; ++i) CHECK(m.points[i].depth / scale == Approx(1e-3).margin(1e-12));
    }
    CHECK(compared == 200);
}

TEST_CASE("far from the origin: manifolds at 1e4, 1e5, 1e6 m equal the one at the origin within 1e-9 of size",
          "[robustness][far]") {
    std::mt19937_64 random(1002);
    std::uniform_real_distribution<double> push(0.0, 0.03);
    for (int trial = 0; trial < 200; ++trial) {
        const Polytope a = randomHull(random), b = randomHull(random);
        Pose poseA, poseB;
        randomContactPose(random, a, b, push(random), poseA, poseB);
        REQUIRE_FALSE(collide(a, poseA, b, poseB, allContacts()).empty());
        const double size = a.radius() + b.radius();
        for (double distance : {1e4, 1e5, 1e6}) {
            // A generic direction; the shifted poses are what a far scene holds (rounded to doubles).
            const Vec3 shift = distance * Vec3(1.0, -0.7, 0.4).normalized();
            const Pose farA = translated(poseA, shift), farB = translated(poseB, shift);
            const Manifold m = collide(a, farA, b, farB, allContacts());
            // The reference is that same rounded scene moved back to the origin — exactly: each
            // coordinate and the shift are within a factor of two, so the subtraction is exact
            // (Sterbenz). Rounding the poses at 1e6 m moves B by ~1e-10 m relative to A, and the
            // contact region's boundary points (where a tilted face's depth crosses zero) move by
            // that over the tilt: the true answer for the rounded input, not a loss of precision.
            // What is checked is that the computation itself loses nothing to the distance.
            const Manifold reference =
                collide(a, translated(farA, -shift), b, translated(farB, -shift), allContacts());
            INFO("trial " << trial << ", distance " << distance);
            CHECK((m.normal - reference.normal).norm() < 1e-9);
            CHECK(sameContacts(m, reference, 1e-9 * size, shift));
        }
    }
    // A box on a plane 1e6 m out along the plane: the same corners and depth as at the origin.
    const Polytope box = Polytope::box(Vec3(0.5, 0.5, 0.5));
    const Manifold near = collide(box, Pose{Mat3::Identity(), Vec3(0, 0, 0.499)}, HalfSpace{});
    const Manifold far = collide(box, Pose{Mat3::Identity(), Vec3(1e6, -1e6, 0.499)}, HalfSpace{});
    CHECK(sameContacts(far, near, 1e-9, Vec3(1e6, -1e6, 0)));
}

TEST_CASE("thin plates (100:1:100) stacked and needles (1:1:100) on a plate: vertical normals, full support",
          "[robustness][thin]") {
    const Vec3 plateHalf(0.5, 0.5, 0.005), needleHalf(0.5, 0.005, 0.005);  // lying flat, long along x
    std::mt19937_64 random(1003);
    std::uniform_real_distribution<double> yaw(-M_PI, M_PI), offset(-0.2, 0.2), sink(1e-6, 2e-3);
    for (bool generalPath : {false, true}) {
        const Polytope plate = generalPath ? Polytope::fromPoints(boxCorners(plateHalf)) : Polytope::box(plateHalf);
        const Polytope needle = generalPath ? Polytope::fromPoints(boxCorners(needleHalf)) : Polytope::box(needleHalf);
        for (int trial = 0; trial < 200; ++trial) {
            const double depth = sink(random);
            INFO((generalPath ? "hulls" : "boxes") << ", trial " << trial << ", depth " << depth);
            // Plate on plate: turned and shifted, sunk by `depth`.
            const Pose upperPlate{rotationAbout(Vec3::UnitZ(), yaw(random)),
                                  Vec3(offset(random), offset(random), 0.01 - depth)};
            const Manifold plates = collide(plate, Pose{}, plate, upperPlate, allContacts());
            REQUIRE(plates.pointCount >= 3);
            CHECK(Vec3::UnitZ().cross(plates.normal).norm() <= 1e-12);  // no sideways normal
            CHECK(plates.featureA.type == FeatureType::Face);
            CHECK(plates.featureB.type == FeatureType::Face);
            for (int i = 0; i < plates.pointCount; ++i) CHECK(plates.points[i].depth == Approx(depth).margin(1e-12));
            requireOnSurfaces(plates, plate, Pose{}, plate, upperPlate, 1e-12);
            // Needle on plate, across it or along it: two points spanning the needle's bottom face
            // clipped to the plate (a face–face contact of a 1 cm wide face).
            const Pose lying{rotationAbout(Vec3::UnitZ(), yaw(random)), Vec3(offset(random), offset(random), 0.01 - depth)};
            const Manifold needleOnPlate = collide(plate, Pose{}, needle, lying, allContacts());
            REQUIRE(needleOnPlate.pointCount >= 2);
            CHECK(Vec3::UnitZ().cross(needleOnPlate.normal).norm() <= 1e-12);
            for (int i = 0; i < needleOnPlate.pointCount; ++i)
                CHECK(needleOnPlate.points[i].depth == Approx(depth).margin(1e-12));
            requireOnSurfaces(needleOnPlate, plate, Pose{}, needle, lying, 1e-12);
        }
    }
}

TEST_CASE("near-parallel faces: tilts from 1e-12 to 1e-3 rad give face contact, continuous in the tilt",
          "[robustness][parallel]") {
    const double sink = 2e-3;  // deeper than any tilt lifts a corner, so every corner stays in contact
    for (bool generalPath : {false, true}) {
        const Polytope cube = generalPath ? Polytope::fromPoints(boxCorners(Vec3::Constant(0.5)))
                                          : Polytope::box(Vec3::Constant(0.5));
        for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(1, 2, 0), Vec3(-3, 1, 0.5)}) {
            for (double sign : {1.0, -1.0}) {
                Manifold previous;
                double previousTilt = 0;
                for (int step = 0; step <= 90; ++step) {
                    const double tilt = sign * std::pow(10.0, -12.0 + step / 10.0);  // 1e-12 … 1e-3
                    const Pose top{rotationAbout(axis, tilt), Vec3(0.1, -0.05, 1.0 - sink)};
                    const Manifold m = collide(cube, Pose{}, cube, top, allContacts());
                    INFO((generalPath ? "hulls" : "boxes") << ", axis " << axis.transpose() << ", tilt " << tilt);
                    REQUIRE(m.pointCount == 4);  // the overlap of two squares offset along x and y
                    CHECK(m.featureA.type == FeatureType::Face);
                    CHECK(m.featureB.type == FeatureType::Face);
                    // The normal is one of the two faces' normals: within the tilt of vertical.
                    CHECK(m.normal.z() > 0);
                    CHECK(Vec3::UnitZ().cross(m.normal).norm() <= std::abs(tilt) * (1 + 1e-9) + 1e-15);
                    requireOnSurfaces(m, cube, Pose{}, cube, top, 1e-12);
                    for (int i = 0; i < 4; ++i) CHECK(std::abs(m.points[i].depth - sink) <= 1.5 * std::abs(tilt) + 1e-12);
                    if (step > 0) {
                        // Continuity: from one tilt to the next, every contact moves by at most
                        // the change in tilt times the body's size (no jump between features).
                        const double change = std::abs(tilt - previousTilt);
                        CHECK(sameContacts(m, previous, 2.0 * change + 1e-12));
                        CHECK((m.normal - previous.normal).norm() <= 2.0 * change + 1e-15);
                    }
                    previous = m;
                    previousTilt = tilt;
                }
            }
        }
    }
}

TEST_CASE("exactly touching and separated by 1e-15: a unit normal and depth zero", "[robustness][touching]") {
    const Polytope cube = Polytope::box(Vec3::Constant(0.5));
    const Polytope hull = Polytope::fromPoints(boxCorners(Vec3::Constant(0.5)));
    const double edgeLift = std::sqrt(0.5);
    // Face on face, edge on face, edge across edge, vertex on face — all exactly touching.
    const Mat3 corner = Eigen::Quaterniond::FromTwoVectors(Vec3(-1, -1, -1).normalized(), -Vec3::UnitZ()).toRotationMatrix();
    const std::vector<std::pair<Pose, Pose>> touching = {
        {Pose{}, Pose{rotationAbout(Vec3::UnitZ(), 0.3), Vec3(0.2, 0.1, 1.0)}},
        {Pose{}, Pose{rotationAbout(Vec3::UnitX(), M_PI / 4), Vec3(0.1, 0, 0.5 + edgeLift)}},
        {Pose{rotationAbout(Vec3::UnitY(), M_PI / 4), Vec3::Zero()},
         Pose{rotationAbout(Vec3::UnitX(), M_PI / 4), Vec3(0, 0, 2 * edgeLift)}},
        {Pose{}, Pose{corner, Vec3(0.1, 0.2, 0.5 + std::sqrt(0.75))}},
    };
    for (const Polytope* shape : {&cube, &hull}) {
        for (std::size_t k = 0; k < touching.size(); ++k) {
            for (double gap : {0.0, 1e-15}) {
                const Pose poseB = translated(touching[k].second, gap * Vec3::UnitZ());
                const Manifold m = collide(*shape, touching[k].first, *shape, poseB, allContacts());
                INFO("configuration " << k << ", gap " << gap << (shape == &cube ? ", boxes" : ", hulls"));
                REQUIRE_FALSE(m.empty());
                CHECK(m.normal.allFinite());
                CHECK(std::abs(m.normal.norm() - 1) < 1e-15);
                CHECK(m.normal.z() > 1 - 1e-9);
                for (int i = 0; i < m.pointCount; ++i) CHECK(std::abs(m.points[i].depth) <= 1e-12);
            }
        }
    }
    // On a half-space, exactly touching and 1e-15 above it.
    for (double gap : {0.0, 1e-15}) {
        const Manifold m = collide(cube, Pose{Mat3::Identity(), Vec3(0, 0, 0.5 + gap)}, HalfSpace{});
        REQUIRE(m.pointCount == 4);
        CHECK((m.normal + Vec3::UnitZ()).norm() < 1e-15);
    }
}

TEST_CASE("deep overlap: crossed centres, coincident centres, one inside the other give a separating normal",
          "[robustness][deep]") {
    const Polytope cube = Polytope::box(Vec3::Constant(0.5));
    const Polytope slab = Polytope::box(Vec3(2, 1.5, 0.25));
    const Polytope small = Polytope::fromPoints(boxCorners(Vec3(0.2, 0.15, 0.1)));
    const Polytope big = Polytope::fromPoints(boxCorners(Vec3(2, 2, 2)));
    const Polytope rounded = Polytope::fromPoints(fibonacciSphere(60));
    struct Case {
        const char* name;
        const Polytope* a;
        Pose poseA;
        const Polytope* b;
        Pose poseB;
    };
    const Mat3 turn = rotationAbout(Vec3(1, 2, 3), 0.7);
    const std::vector<Case> cases = {
        {"centres crossed (B came from above, now below A's centre)", &cube, Pose{}, &cube,
         Pose{turn, Vec3(0.1, 0.05, -0.3)}},
        {"centres crossed, slab and rounded hull", &slab, Pose{}, &rounded, Pose{turn, Vec3(0.3, -0.2, -0.1)}},
        {"coincident centres, cube and slab", &slab, Pose{}, &cube, Pose{}},
        {"coincident centres, turned", &cube, Pose{turn, Vec3(1, 1, 1)}, &rounded, Pose{Mat3::Identity(), Vec3(1, 1, 1)}},
        {"one inside the other, off centre", &big, Pose{}, &small, Pose{turn, Vec3(0.7, -0.4, 0.2)}},
        {"one inside the other, centred", &small, Pose{turn, Vec3::Zero()}, &big, Pose{}},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        const Manifold m = collide(*c.a, c.poseA, *c.b, c.poseB, allContacts());
        REQUIRE_FALSE(m.empty());
        CHECK(m.normal.allFinite());
        CHECK(std::abs(m.normal.norm() - 1) < 1e-12);
        const double size = c.a->radius() + c.b->radius();
        for (int i = 0; i < m.pointCount; ++i) {
            CHECK(std::isfinite(m.points[i].depth));
            CHECK(m.points[i].depth >= 0);
            CHECK(m.points[i].depth <= size);
        }
        // The normal separates them: moving B by the depth along it clears A (and not much less does).
        requireSeparatingDepth(m, *c.a, c.poseA, *c.b, c.poseB, 1e-9 * size);
        // Swapped, the same (mirrored) answer; with coincident centres of symmetric shapes n and
        // −n are exact ties, so there it is only required to separate them as well.
        const Manifold swapped = collide(*c.b, c.poseB, *c.a, c.poseA, allContacts());
        if ((c.poseA.apply(c.a->centroid()) - c.poseB.apply(c.b->centroid())).norm() > 1e-9)
            CHECK((swapped.normal + m.normal).norm() < 1e-9);
        requireSeparatingDepth(swapped, *c.b, c.poseB, *c.a, c.poseA, 1e-9 * size);
    }
    // Coincident centres: the smallest overlap is the exact answer (the slab's thickness direction).
    const Manifold coincident = collide(slab, Pose{}, cube, Pose{}, allContacts());
    CHECK(std::abs(coincident.normal.z()) == Approx(1).margin(1e-12));
    CHECK(coincident.maxDepth() == Approx(0.75).margin(1e-12));
}

TEST_CASE("large hulls: a 4096-vertex near-sphere gives the analytic contact", "[robustness][large]") {
    std::mt19937_64 random(1004);
    std::uniform_real_distribution<double> jitter(-1e-4, 1e-4);
    std::vector<Vec3> points;
    for (const Vec3& p : fibonacciSphere(4096)) points.push_back((1 + jitter(random)) * p);
    const Polytope sphere = Polytope::fromPoints(points);
    REQUIRE(sphere.vertices().size() == 4096);
    const Polytope box = Polytope::box(Vec3(2, 2, 0.5));
    std::uniform_real_distribution<double> sink(1e-3, 5e-2);
    for (int trial = 0; trial < 20; ++trial) {
        const double depth = sink(random);
        const Pose poseS{randomRotation(random), Vec3(0.3, -0.2, 1.5 - depth)};
        // On a box and on a plane: the normal is vertical and the deepest point's depth is the
        // lowest vertex's (brute force over all 4096).
        double lowest = INFINITY;
        for (const Vec3& v : sphere.vertices()) lowest = std::min(lowest, poseS.apply(v).z());
        const Manifold onBox = collide(box, Pose{}, sphere, poseS, allContacts());
        INFO("trial " << trial);
        REQUIRE_FALSE(onBox.empty());
        CHECK((onBox.normal - Vec3::UnitZ()).norm() < 1e-12);
        CHECK(onBox.maxDepth() == Approx(0.5 - lowest).margin(1e-12));
        const Manifold onPlane = collide(sphere, translated(poseS, Vec3(0, 0, -0.5)), HalfSpace{});
        REQUIRE_FALSE(onPlane.empty());
        CHECK(onPlane.maxDepth() == Approx(0.5 - lowest).margin(1e-12));
        // Sphere on sphere: the normal along the centre line (within the facets' angular size),
        // the depth the spheres' overlap (within the facets' sagitta and the jitter).
        const Vec3 direction = randomDirection(random);
        const Pose other{randomRotation(random), poseS.position + (2 - depth) * direction};
        const Manifold spheres = collide(sphere, poseS, sphere, other, allContacts());
        REQUIRE_FALSE(spheres.empty());
        CHECK(std::acos(std::min(1.0, spheres.normal.dot(direction))) < 0.05);
        CHECK(spheres.maxDepth() == Approx(depth).margin(2e-3));
        for (int i = 0; i < spheres.pointCount; ++i) CHECK(spheres.points[i].depth >= -1e-9);
    }
}

TEST_CASE("hulls with near-coplanar faces: the whole flat side rests, not one sliver of it", "[robustness][large]") {
    // A cube's corners plus points scattered on its faces, each lifted off its face by up to
    // 1e-4 (noisy scan data): qhull splits every side into many faces a few 1e-4 rad apart — too
    // far apart to be merged at construction, well within the Gauss-map tolerance.
    std::mt19937_64 random(1005);
    std::uniform_real_distribution<double> unit(-0.5, 0.5), lift(0.0, 1e-4);
    std::vector<Vec3> points = boxCorners(Vec3::Constant(0.5));
    for (int i = 0; i < 600; ++i) {
        Vec3 p(unit(random), unit(random), unit(random));
        const int axis = i % 3;
        p[axis] = (i % 2 ? 0.5 : -0.5) + (i % 2 ? lift(random) : -lift(random));
        points.push_back(p);
    }
    const Polytope noisy = Polytope::fromPoints(points);
    REQUIRE(noisy.faces().size() > 100);
    const Polytope plate = Polytope::box(Vec3(2, 2, 0.1));
    for (double yaw : {0.0, 0.4, 1.3}) {
        const Pose pose{rotationAbout(Vec3::UnitZ(), yaw), Vec3(0.1, 0.2, 0.6 - 3e-3)};
        INFO("yaw " << yaw);
        for (int onPlane = 0; onPlane < 2; ++onPlane) {
            const Manifold m = onPlane ? collide(noisy, translated(pose, Vec3(0, 0, -0.1)), HalfSpace{Vec3::UnitZ(), 0.0}, allContacts())
                                       : collide(plate, Pose{}, noisy, pose, allContacts());
            REQUIRE(m.pointCount >= 4);
            CHECK(std::abs(m.normal.z()) > std::cos(1e-3));
            // The contacts span the bottom side: the four corners (bottom corners of the cube are
            // exact, unlifted points) are among them, with the sink as depth.
            int corners = 0;
            for (const Vec3& c : boxCorners(Vec3::Constant(0.5))) {
                if (c.z() > 0) continue;
                const Vec3 world = pose.apply(c) - (onPlane ? Vec3(0, 0, 0.1) : Vec3::Zero());
                for (int i = 0; i < m.pointCount; ++i)
                    if ((m.points[i].position.head<2>() - world.head<2>()).norm() < 1e-6 &&
                        std::abs(m.points[i].depth - 3e-3) < 1e-6)
                        ++corners;
            }
            CHECK(corners == 4);
        }
    }
}

TEST_CASE("overhang: a cube hanging off a long plank's edge keeps the resting normal", "[robustness][overhang]") {
    // The growth distance scales both bodies about their centroids; with the cube's centroid far
    // out along the plank the ray through the centroids leaves A − B through the plank's end
    // facet, so the paper's normal is horizontal although the cube rests on the plank's top.
    const Polytope plank = Polytope::box(Vec3(5, 0.5, 0.1));
    const Polytope plankHull = Polytope::fromPoints(boxCorners(Vec3(5, 0.5, 0.1)));
    const Polytope cube = Polytope::box(Vec3::Constant(0.5));
    const double sink = 0.03;  // an impact's depth: the paper's normal tilts below 0.45 m bearing
    int paperNormalsOff = 0, poses = 0;
    double worstPaperAngle = 0;
    for (const Polytope* base : {&plank, &plankHull}) {
        for (double yaw : {0.0, 0.2}) {
            for (int step = 0; step < 18; ++step) {
                const double bearing = 0.95 - 0.05 * step;  // length of cube over the plank: 0.95 … 0.10
                ++poses;
                const Pose top{rotationAbout(Vec3::UnitZ(), yaw), Vec3(5.5 - bearing, 0.1, 0.6 - sink)};
                INFO("bearing " << bearing << ", yaw " << yaw << (base == &plank ? ", boxes" : ", hulls"));
                const detail::GrowthDistance paper =
                    detail::growthDistance(*base, cube, Pose{}.relative(top), Settings{}, false);
                if (paper.valid && paper.normal.z() < 0.9) ++paperNormalsOff;
                if (paper.valid) worstPaperAngle = std::max(worstPaperAngle, std::acos(std::min(1.0, paper.normal.z())));
                const Manifold m = collide(*base, Pose{}, cube, top, allContacts());
                CHECK((m.normal - Vec3::UnitZ()).norm() < 1e-12);
                REQUIRE(m.pointCount >= 3);
                for (int i = 0; i < m.pointCount; ++i) CHECK(m.points[i].depth == Approx(sink).margin(1e-12));
                requireOnSurfaces(m, *base, Pose{}, cube, top, 1e-12);
                requireSeparatingDepth(m, *base, Pose{}, cube, top, 1e-9);
            }
        }
    }
    CHECK(paperNormalsOff > 0);  // the case is real: the paper's normal alone tilts for these
    report("overhang, collider level", std::to_string(paperNormalsOff) + " of " + std::to_string(poses) + " poses have the paper's normal > 25° off "
           "vertical (worst " + std::to_string(worstPaperAngle) + " rad); gdcontact's normal: vertical in all");
    // Where the cube barely overlaps the plank sideways the minimum translation really is
    // sideways, and the normal follows it: 1 mm of the cube over the plank's end, 10 mm sunk.
    const Manifold sideways = collide(plank, Pose{}, cube, Pose{Mat3::Identity(), Vec3(5.499, 0, 0.6 - 0.01)}, allContacts());
    CHECK((sideways.normal - Vec3::UnitX()).norm() < 1e-12);
}

// The speed/accuracy trade of gdcontact's Settings, against exact answers.
//
// For each setting (one at a time around the defaults) and for reference colliders of ODE and
// Bullet, on fixed deterministic test sets:
//   time      — mean ns per collide call over the cube pairs (and, separately, the hull pairs),
//               median of repetitions;
//   normal    — angle (degrees) between the returned normal and the exact minimum-translation
//               normal (SAT over all face normals and edge pairs) on shallow random contacts of
//               cubes and of 64-vertex hulls, where the growth-distance normal should agree;
//   polygon   — Hausdorff distance (mm) between the convex hull of the returned points and the
//               analytic contact region of a cube resting face-down on a cube (flat, and tilted by
//               0.2°–2°), and the ratio of their areas;
//   box drop  — alignment error (degrees) of a cube dropped tilted onto a slab, simulated with ODE's
//               exact dWorldStep, max over t ∈ [2 s, 3 s].
// A second table compares the stage-1 normal alone: growth distance, libccd MPR and GJK+EPA, SAT.
// Writes CSV (one row per configuration); scripts/bench turns it into docs/benchmarks.md.
#include "bullet_shapes.hpp"
#include "fixtures.hpp"
#include "ode_shapes.hpp"
#include "reference.hpp"

#include "geometry/growth_distance.hpp"  // stage 1 alone (internal header of the core, as its tests use it)

#include <gdcontact/collide.hpp>
#include <gdcontact/ode.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <unordered_map>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

namespace gdcbench {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegree = M_PI / 180.0;
constexpr double kSampleOverlap = 0.005;  // metres, 0.5 % of the cube's edge: shallow contact

struct Options {
    int samples = 100;          // per test set
    double minSeconds = 0.05;   // per timing repetition
    int repetitions = 5;
    std::string out;
};

// ---- test sets --------------------------------------------------------------------------------

struct PairSample {
    Pose a, b;
    Vec3 exactNormal;  // from A towards B
};

/// A cube A resting face-down on cube B; the exact region is in B's local xy (B's top face).
struct PolygonSample {
    Pose a, b;
    Polygon2 exact;
};

struct TestSets {
    std::vector<Vec3> cubePoints = boxVertices(Vec3::Constant(kCubeHalfExtent));
    std::vector<Vec3> hullPoints = fibonacciSphere(64, kSphereRadius);
    gdc::Polytope cube = gdc::Polytope::box(Vec3::Constant(kCubeHalfExtent));
    gdc::Polytope hull = gdc::Polytope::fromPoints(hullPoints);
    std::vector<PairSample> cubePairs, hullPairs;
    std::vector<PolygonSample> flat, tilted;
};

std::vector<PairSample> pairSamples(const gdc::Polytope& shape, const std::vector<Vec3>& points, int count,
                                    std::uint64_t seed) {
    std::vector<PairSample> samples;
    for (const auto& [a, b] : touchingPoses(points, points, count, kSampleOverlap, seed))
        samples.push_back({a, b, exactMinimumNormal(shape, a, shape, b).normal});
    return samples;
}

/// Clips a planar polygon (3-D) to the half-space z ≤ height.
std::vector<Vec3> clipBelow(const std::vector<Vec3>& polygon, double height) {
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec3& p = polygon[i];
        const Vec3& q = polygon[(i + 1) % polygon.size()];
        const double sp = height - p.z(), sq = height - q.z();
        if (sp >= 0) out.push_back(p);
        if ((sp >= 0) != (sq >= 0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    return out;
}

PolygonSample polygonSample(Random& random, double maxTiltDegrees) {
    const double h = kCubeHalfExtent;
    const Polygon2 topOfB{{-h, -h}, {h, -h}, {h, h}, {-h, h}};
    for (;;) {
        const Mat3 spin = rotation(Vec3::UnitZ(), random.uniform(0, M_PI / 2));
        const double azimuth = random.uniform(0, 2 * M_PI);
        const double tilt = maxTiltDegrees > 0 ? random.uniform(0.2, maxTiltDegrees) * kDegree : 0.0;
        const Mat3 turn = rotation({std::cos(azimuth), std::sin(azimuth), 0}, tilt) * spin;
        const Vec3 bottomCentre(random.uniform(-0.6, 0.6), random.uniform(-0.6, 0.6), h - kSampleOverlap);
        const Pose aLocal{turn, bottomCentre + turn * Vec3(0, 0, h)};
        // A's bottom face, counter-clockwise seen from above (+z).
        std::vector<Vec3> bottom;
        for (const Vec3& corner : {Vec3(-h, -h, -h), Vec3(h, -h, -h), Vec3(h, h, -h), Vec3(-h, h, -h)})
            bottom.push_back(aLocal.apply(corner));
        Polygon2 below;
        for (const Vec3& p : clipBelow(bottom, h)) below.emplace_back(p.x(), p.y());
        Polygon2 exact = intersectConvex(below, topOfB);
        if (exact.size() < 3 || area(exact) < 0.02) continue;  // too small a region to judge a polygon
        const Pose frame = commonFrame();
        return {compose(frame, aLocal), frame, std::move(exact)};
    }
}

TestSets makeTestSets(int samples) {
    TestSets sets;
    sets.cubePairs = pairSamples(sets.cube, sets.cubePoints, samples, 11);
    sets.hullPairs = pairSamples(sets.hull, sets.hullPoints, samples, 12);
    Random random(13);
    for (int i = 0; i < samples; ++i) sets.flat.push_back(polygonSample(random, 0.0));
    for (int i = 0; i < samples; ++i) sets.tilted.push_back(polygonSample(random, 2.0));
    return sets;
}

// ---- measures ---------------------------------------------------------------------------------

double angleDegrees(const Vec3& a, const Vec3& b) {
    return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) / kDegree;
}

struct Summary {
    double median = kNan, p95 = kNan, max = kNan, mean = kNan;
};

Summary summarize(std::vector<double> values) {
    Summary s;
    if (values.empty()) return s;
    std::sort(values.begin(), values.end());
    auto at = [&](double q) { return values[std::min(values.size() - 1, static_cast<std::size_t>(q * values.size()))]; };
    s.median = at(0.5);
    s.p95 = at(0.95);
    s.max = values.back();
    double sum = 0;
    for (double v : values) sum += v;
    s.mean = sum / values.size();
    return s;
}

struct PolygonError {
    double hausdorffMm;
    double areaRatio;
};

/// Returned positions (world) against the sample's exact region, in B's top plane.
PolygonError polygonError(const PolygonSample& sample, const std::vector<Vec3>& positions) {
    Polygon2 projected;
    for (const Vec3& p : positions) {
        const Vec3 local = sample.b.applyInverse(p);
        projected.emplace_back(local.x(), local.y());
    }
    if (projected.empty()) {
        // A missed contact: the whole region is missing, its diameter is the error.
        double diameter = 0;
        for (const auto& p : sample.exact)
            for (const auto& q : sample.exact) diameter = std::max(diameter, (p - q).norm());
        return {1000 * diameter, 0.0};
    }
    const Polygon2 hull = convexHull2(projected);
    return {1000 * hausdorff(hull, sample.exact), area(hull) / area(sample.exact)};
}

/// What one collider answers for a pair: the normal from A towards B and the positions.
struct Answer {
    bool touching = false;
    Vec3 normal = Vec3::UnitZ();
    std::vector<Vec3> positions;
};

/// A collider under test on a pair of cubes or of 64-vertex hulls: `answer` for the accuracy
/// measures, `count` (the bare call, returning the number of contacts) for the time.
struct Contender {
    std::string group, parameter, value;
    std::function<Answer(bool hulls, const Pose& a, const Pose& b)> answer;
    std::function<int(bool hulls, const Pose& a, const Pose& b)> count;
    bool handlesHulls = true;
    std::function<double()> boxDrop;  // alignment error (degrees), or empty
};

template <class F>
double nsPerCall(F&& runOnce, const Options& options) {
    std::vector<double> perCall;
    for (int r = 0; r < options.repetitions; ++r) {
        long long calls = 0;
        const double start = threadCpuSeconds();
        double elapsed = 0;
        do {
            calls += runOnce();
            elapsed = threadCpuSeconds() - start;
        } while (elapsed < options.minSeconds);
        perCall.push_back(1e9 * elapsed / calls);
    }
    return summarize(perCall).median;
}

struct Row {
    std::string group, parameter, value;
    double timeNs = kNan;      // cube sets
    double hullTimeNs = kNan;  // 64-vertex hull pairs
    Summary cubeNormal, hullNormal;
    Summary flatHausdorff, tiltedHausdorff;
    double flatArea = kNan, tiltedArea = kNan;
    double contacts = kNan;
    double boxDrop = kNan;
};

Row evaluate(const Contender& c, const TestSets& sets, const Options& options) {
    Row row;
    row.group = c.group, row.parameter = c.parameter, row.value = c.value;
    std::vector<double> cubeErrors, hullErrors, flatH, tiltedH, flatA, tiltedA;
    double contacts = 0;
    int calls = 0;
    for (const PairSample& s : sets.cubePairs) {
        const Answer a = c.answer(false, s.a, s.b);
        cubeErrors.push_back(a.touching ? angleDegrees(a.normal, s.exactNormal) : 180.0);
    }
    if (c.handlesHulls)
        for (const PairSample& s : sets.hullPairs) {
            const Answer a = c.answer(true, s.a, s.b);
            hullErrors.push_back(a.touching ? angleDegrees(a.normal, s.exactNormal) : 180.0);
        }
    for (const PolygonSample& s : sets.flat) {
        const Answer a = c.answer(false, s.a, s.b);
        const PolygonError e = polygonError(s, a.positions);
        flatH.push_back(e.hausdorffMm), flatA.push_back(e.areaRatio);
        contacts += a.positions.size(), ++calls;  // contacts per resting face–face pair
    }
    for (const PolygonSample& s : sets.tilted) {
        const PolygonError e = polygonError(s, c.answer(false, s.a, s.b).positions);
        tiltedH.push_back(e.hausdorffMm), tiltedA.push_back(e.areaRatio);
    }
    row.cubeNormal = summarize(cubeErrors);
    row.hullNormal = summarize(hullErrors);
    row.flatHausdorff = summarize(flatH);
    row.tiltedHausdorff = summarize(tiltedH);
    row.flatArea = summarize(flatA).mean;
    row.tiltedArea = summarize(tiltedA).mean;
    row.contacts = contacts / calls;
    // Time per call on the cube sets (every contender handles cubes) and, separately, on the hulls.
    auto timeOver = [&](bool hulls) {
        return nsPerCall(
            [&] {
                long long calls = 0;
                int contactsSeen = 0;
                if (hulls) {
                    for (const PairSample& s : sets.hullPairs) contactsSeen += c.count(true, s.a, s.b), ++calls;
                } else {
                    for (const PairSample& s : sets.cubePairs) contactsSeen += c.count(false, s.a, s.b), ++calls;
                    for (const PolygonSample& s : sets.flat) contactsSeen += c.count(false, s.a, s.b), ++calls;
                    for (const PolygonSample& s : sets.tilted) contactsSeen += c.count(false, s.a, s.b), ++calls;
                }
                volatile int keep = contactsSeen;  // the calls must not be optimised away
                (void)keep;
                return calls;
            },
            options);
    };
    row.timeNs = timeOver(false);
    if (c.handlesHulls) row.hullTimeNs = timeOver(true);
    if (c.boxDrop) row.boxDrop = c.boxDrop();
    return row;
}

// ---- box drop ---------------------------------------------------------------------------------

using GeomCollider = std::function<int(dGeomID, dGeomID, int, dContactGeom*, int)>;

/// A 1 m cube of 1 kg dropped from 1 m, tilted 15°, onto a static 4 × 4 × 1 m slab (box–box, so
/// every stage of the collider takes part); ODE's exact dWorldStep at 100 Hz for 3 s.
/// `asConvex` makes both geoms dConvex (for ODE's libccd collider) instead of dBox.
double boxDropAlignment(const GeomCollider& collide, bool asConvex) {
    dWorldID world = dWorldCreate();
    dWorldSetGravity(world, 0, 0, -9.81);
    dSpaceID space = dSimpleSpaceCreate(nullptr);
    dJointGroupID joints = dJointGroupCreate(0);
    const gdc::Polytope slabShape = gdc::Polytope::box({2.0, 2.0, 0.5});
    const gdc::Polytope cubeShape = gdc::Polytope::box(Vec3::Constant(0.5));
    std::unique_ptr<OdeConvex> slabConvex, cubeConvex;
    dGeomID slab, cube;
    if (asConvex) {
        slabConvex = std::make_unique<OdeConvex>(space, slabShape);
        cubeConvex = std::make_unique<OdeConvex>(space, cubeShape);
        slab = slabConvex->geom(), cube = cubeConvex->geom();
    } else {
        slab = createOdeBox(space, {2.0, 2.0, 0.5});
        cube = createOdeBox(space, Vec3::Constant(0.5));
    }
    setGeomPose(slab, {Mat3::Identity(), Vec3(0, 0, -0.5)});
    dBodyID body = dBodyCreate(world);
    dMass mass;
    dMassSetBoxTotal(&mass, 1.0, 1, 1, 1);
    dBodySetMass(body, &mass);
    dGeomSetBody(cube, body);
    setBodyPose(body, {rotation(Vec3::UnitZ(), 0.3) * rotation({1, 1, 0}, 15 * kDegree), Vec3(0, 0, 1.5)});

    const double dt = 0.01;
    double worst = 0;
    for (int step = 0; step < 300; ++step) {
        std::array<dContactGeom, 8> geoms;
        const int n = collide(cube, slab, 8, geoms.data(), sizeof(dContactGeom));
        for (int i = 0; i < n; ++i) {
            dContact contact{};
            contact.surface.mode = dContactApprox1;
            contact.surface.mu = 0.6;
            contact.geom = geoms[i];
            dJointAttach(dJointCreateContact(world, joints, &contact), body, nullptr);
        }
        dWorldStep(world, dt);
        dJointGroupEmpty(joints);
        if ((step + 1) * dt >= 2.0) {
            const dReal* r = dBodyGetRotation(body);
            // The body axis closest to vertical is the resting face's normal.
            const double upright = std::max({std::abs(r[8]), std::abs(r[9]), std::abs(r[10])});
            worst = std::max(worst, std::acos(std::min(1.0, upright)) / kDegree);
        }
    }
    dJointGroupDestroy(joints);
    cubeConvex.reset();
    slabConvex.reset();
    dSpaceDestroy(space);
    dWorldDestroy(world);
    return worst;
}

// ---- contenders -------------------------------------------------------------------------------

Answer fromManifold(const gdc::Manifold& m) {
    Answer a;
    a.touching = !m.empty();
    a.normal = m.normal;
    for (int i = 0; i < m.pointCount; ++i) a.positions.push_back(m.points[i].position);
    return a;
}

Contender gdcontactWith(const TestSets& sets, const gdc::Settings& settings, std::string parameter,
                        std::string value) {
    Contender c;
    c.group = "settings";
    c.parameter = std::move(parameter);
    c.value = std::move(value);
    c.answer = [&sets, settings](bool hulls, const Pose& a, const Pose& b) {
        const gdc::Polytope& shape = hulls ? sets.hull : sets.cube;
        return fromManifold(gdc::collide(shape, a, shape, b, settings));
    };
    c.count = [&sets, settings](bool hulls, const Pose& a, const Pose& b) {
        const gdc::Polytope& shape = hulls ? sets.hull : sets.cube;
        return gdc::collide(shape, a, shape, b, settings).pointCount;
    };
    c.boxDrop = [settings] {
        return boxDropAlignment(
            [settings](dGeomID o1, dGeomID o2, int flags, dContactGeom* contacts, int skip) {
                return gdc::ode::collide(o1, o2, flags, contacts, skip, settings);
            },
            false);
    };
    return c;
}

/// gdcontact answering from a pair cache filled one step earlier, when the pair stood `distance`/2
/// away (B shifted in a random direction): what Settings::manifoldReuseDistance = `distance` gives
/// a pair that moved that much since its last query — the carried contacts (their error against
/// the exact answer at the pose asked about) and the time of a carried answer.
Contender gdcontactCarried(const TestSets& sets, double distance, std::string value) {
    gdc::Settings settings;
    settings.manifoldReuseDistance = distance;
    auto earlier = [distance](const Pose& b) {
        // A direction fixed by the pose (so every run moves each sample alike), length distance/2.
        const Vec3 seed(std::sin(1e3 * b.position.x()), std::sin(1e3 * b.position.y() + 1), std::cos(1e3 * b.position.z()));
        Pose moved = b;
        moved.position -= 0.5 * distance * seed.normalized();
        return moved;
    };
    // Caches filled at the earlier poses, one per sample, keyed by the sample's address; timing then
    // measures carried answers only (a carried answer leaves its cache as it was), plus the lookup.
    auto caches = std::make_shared<std::unordered_map<const Pose*, gdc::PairCache>>();
    auto cacheFor = [&sets, settings, earlier, caches](bool hulls, const Pose& a, const Pose& b) -> gdc::PairCache& {
        auto [entry, isNew] = caches->try_emplace(&b);
        if (isNew) {
            const gdc::Polytope& shape = hulls ? sets.hull : sets.cube;
            gdc::collide(shape, a, shape, earlier(b), settings, entry->second);
        }
        return entry->second;
    };
    Contender c;
    c.group = "settings";
    c.parameter = "manifoldReuseDistance";
    c.value = std::move(value);
    c.answer = [&sets, settings, cacheFor](bool hulls, const Pose& a, const Pose& b) {
        const gdc::Polytope& shape = hulls ? sets.hull : sets.cube;
        return fromManifold(gdc::collide(shape, a, shape, b, settings, cacheFor(hulls, a, b)));
    };
    c.count = [&sets, settings, cacheFor](bool hulls, const Pose& a, const Pose& b) {
        const gdc::Polytope& shape = hulls ? sets.hull : sets.cube;
        return gdc::collide(shape, a, shape, b, settings, cacheFor(hulls, a, b)).pointCount;
    };
    return c;
}

/// ODE's own colliders on geoms posed for each call (ODE has no pose argument).
struct OdePair {
    dGeomID a, b;
};

Answer odeAnswer(OdePair pair, const Pose& a, const Pose& b) {
    setGeomPose(pair.a, a);
    setGeomPose(pair.b, b);
    std::array<dContactGeom, 8> contacts;
    const int n = dCollide(pair.a, pair.b, 8, contacts.data(), sizeof(dContactGeom));
    Answer answer;
    answer.touching = n > 0;
    // ODE's normal points from o2 into o1: from B into A.
    if (n > 0) answer.normal = -Vec3(contacts[0].normal[0], contacts[0].normal[1], contacts[0].normal[2]);
    for (int i = 0; i < n; ++i) answer.positions.emplace_back(contacts[i].pos[0], contacts[i].pos[1], contacts[i].pos[2]);
    return answer;
}

Answer bulletAnswer(const BulletContacts& out) {
    Answer answer;
    answer.touching = out.count > 0;
    answer.normal = out.normal;
    for (int i = 0; i < std::min(out.count, BulletContacts::kKeptPositions); ++i) answer.positions.push_back(out.positions[i]);
    return answer;
}

struct References {
    OdePair boxes, cubeHulls, sphereHulls;
    std::vector<std::unique_ptr<OdeConvex>> convexes;
    std::shared_ptr<btBoxShape> bulletBox;
    std::shared_ptr<btConvexHullShape> bulletCube, bulletHull;

    explicit References(const TestSets& sets) {
        boxes = {createOdeBox(nullptr, Vec3::Constant(kCubeHalfExtent)), createOdeBox(nullptr, Vec3::Constant(kCubeHalfExtent))};
        for (int i = 0; i < 2; ++i) convexes.push_back(std::make_unique<OdeConvex>(nullptr, sets.cube));
        for (int i = 0; i < 2; ++i) convexes.push_back(std::make_unique<OdeConvex>(nullptr, sets.hull));
        cubeHulls = {convexes[0]->geom(), convexes[1]->geom()};
        sphereHulls = {convexes[2]->geom(), convexes[3]->geom()};
        bulletBox = makeBulletBox(Vec3::Constant(kCubeHalfExtent));
        bulletCube = makeBulletHull(sets.cubePoints);
        bulletHull = makeBulletHull(sets.hullPoints);
    }
    ~References() {
        dGeomDestroy(boxes.a);
        dGeomDestroy(boxes.b);
    }
};

int odeCount(OdePair pair, const Pose& a, const Pose& b) {
    setGeomPose(pair.a, a);
    setGeomPose(pair.b, b);
    std::array<dContactGeom, 8> contacts;
    return dCollide(pair.a, pair.b, 8, contacts.data(), sizeof(dContactGeom));
}

std::vector<Contender> referenceContenders(References& refs) {
    std::vector<Contender> out;
    GeomCollider native = [](dGeomID o1, dGeomID o2, int flags, dContactGeom* contacts, int skip) {
        return dCollide(o1, o2, flags, contacts, skip);
    };
    Contender boxBox{"reference", "ODE", "dBoxBox",
                     [&refs](bool, const Pose& a, const Pose& b) { return odeAnswer(refs.boxes, a, b); },
                     [&refs](bool, const Pose& a, const Pose& b) { return odeCount(refs.boxes, a, b); }, false,
                     [native] { return boxDropAlignment(native, false); }};
    out.push_back(boxBox);
    Contender ccd{"reference", "ODE", "libccd convex",
                  [&refs](bool hulls, const Pose& a, const Pose& b) {
                      return odeAnswer(hulls ? refs.sphereHulls : refs.cubeHulls, a, b);
                  },
                  [&refs](bool hulls, const Pose& a, const Pose& b) {
                      return odeCount(hulls ? refs.sphereHulls : refs.cubeHulls, a, b);
                  },
                  true, [native] { return boxDropAlignment(native, true); }};
    out.push_back(ccd);
    auto bullet = [](auto detect) {
        return std::make_pair(
            [detect](bool hulls, const Pose& a, const Pose& b) {
                BulletContacts contacts;
                detect(hulls, toBullet(a), toBullet(b), contacts);
                return bulletAnswer(contacts);
            },
            [detect](bool hulls, const Pose& a, const Pose& b) {
                BulletContacts contacts;
                return detect(hulls, toBullet(a), toBullet(b), contacts);
            });
    };
    auto boxDetector = bullet([&refs](bool, const btTransform& a, const btTransform& b, BulletContacts& c) {
        return bulletBoxBox(*refs.bulletBox, a, *refs.bulletBox, b, c);
    });
    out.push_back({"reference", "Bullet", "btBoxBoxDetector", boxDetector.first, boxDetector.second, false, {}});
    auto gjkClip = bullet([&refs](bool hulls, const btTransform& a, const btTransform& b, BulletContacts& c) {
        const auto& shape = hulls ? *refs.bulletHull : *refs.bulletCube;
        return bulletGjkClip(shape, a, shape, b, c);
    });
    out.push_back({"reference", "Bullet", "GJK+EPA + clipping", gjkClip.first, gjkClip.second, true, {}});
    auto satClip = bullet([&refs](bool hulls, const btTransform& a, const btTransform& b, BulletContacts& c) {
        const auto& shape = hulls ? *refs.bulletHull : *refs.bulletCube;
        return bulletSatClip(shape, a, shape, b, c);
    });
    out.push_back({"reference", "Bullet", "SAT + clipping", satClip.first, satClip.second, true, {}});
    return out;
}

std::vector<Contender> settingsSweep(const TestSets& sets) {
    std::vector<Contender> out;
    auto text = [](double v) {
        std::ostringstream s;
        s << v;
        return s.str();
    };
    out.push_back(gdcontactWith(sets, {}, "defaults", "-"));
    for (double v : {1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-12}) {
        gdc::Settings s;
        s.rayCastTolerance = v;
        out.push_back(gdcontactWith(sets, s, "rayCastTolerance", text(v)));
    }
    for (int v : {1, 2, 3, 4, 6, 8, 16}) {
        gdc::Settings s;
        s.maxRayCastIterations = v;
        out.push_back(gdcontactWith(sets, s, "maxRayCastIterations", text(v)));
    }
    for (double v : {0.0, 0.001, 0.005, 0.01, 0.02, 0.1, 0.2}) {
        gdc::Settings s;
        s.angularTolerance = v;
        out.push_back(gdcontactWith(sets, s, "angularTolerance", text(v)));
    }
    for (int v : {1, 2, 3, 4, 6, 16}) {
        gdc::Settings s;
        s.maxContacts = v;
        out.push_back(gdcontactWith(sets, s, "maxContacts", text(v)));
    }
    gdc::Settings spanning;  // contacts where the region's edges cross the contact depth, too
    spanning.spanContactRegion = true;
    out.push_back(gdcontactWith(sets, spanning, "spanContactRegion", "true"));
    gdc::Settings separatingAxis;  // the whole pipeline with the SAT's exact normal in stage 1
    separatingAxis.normalMethod = gdc::NormalMethod::SeparatingAxis;
    out.push_back(gdcontactWith(sets, separatingAxis, "normalMethod", "SeparatingAxis"));
    // The pair cache's opt-in reuse: the pair moved half the distance since the query that filled it.
    for (double v : {1e-4, 1e-3, 1e-2}) out.push_back(gdcontactCarried(sets, v, text(v) + " (moved " + text(v / 2) + ")"));
    return out;
}

// ---- stage 1 alone: normal methods -------------------------------------------------------------

struct NormalMethod {
    std::string name;
    std::function<Vec3(const gdc::Polytope&, const std::vector<Vec3>&, const Pose&, const Pose&)> normal;
};

std::vector<NormalMethod> normalMethods() {
    std::vector<NormalMethod> out;
    out.push_back({"growth distance (paper, default settings)",
                   [](const gdc::Polytope& shape, const std::vector<Vec3>&, const Pose& a, const Pose& b) {
                       const gdc::detail::GrowthDistance g =
                           gdc::detail::growthDistance(shape, shape, a.relative(b), gdc::Settings{});
                       return Vec3(a.rotation * g.normal);
                   }});
    for (double tolerance : {1e-4, 1e-8}) {
        std::ostringstream name;
        name << "libccd MPR, tolerance " << tolerance;
        out.push_back({name.str(), [tolerance](const gdc::Polytope&, const std::vector<Vec3>& points, const Pose& a,
                                               const Pose& b) {
                           return mprNormal({&points, a}, {&points, b}, tolerance).normal;
                       }});
        std::ostringstream epaName;
        epaName << "libccd GJK+EPA, tolerance " << tolerance;
        out.push_back({epaName.str(), [tolerance](const gdc::Polytope&, const std::vector<Vec3>& points, const Pose& a,
                                                  const Pose& b) {
                           return epaNormal({&points, a}, {&points, b}, tolerance).normal;
                       }});
    }
    out.push_back({"SAT, all face normals and edge pairs (exact)",
                   [](const gdc::Polytope& shape, const std::vector<Vec3>&, const Pose& a, const Pose& b) {
                       return exactMinimumNormal(shape, a, shape, b).normal;
                   }});
    return out;
}

struct NormalRow {
    std::string method;
    double cubeNs, hullNs;
    Summary cube, hull;
};

NormalRow evaluateNormal(const NormalMethod& m, const TestSets& sets, const Options& options) {
    NormalRow row{m.name, kNan, kNan, {}, {}};
    std::vector<double> cubeErrors, hullErrors;
    for (const PairSample& s : sets.cubePairs)
        cubeErrors.push_back(angleDegrees(m.normal(sets.cube, sets.cubePoints, s.a, s.b), s.exactNormal));
    for (const PairSample& s : sets.hullPairs)
        hullErrors.push_back(angleDegrees(m.normal(sets.hull, sets.hullPoints, s.a, s.b), s.exactNormal));
    row.cube = summarize(cubeErrors);
    row.hull = summarize(hullErrors);
    auto timeSet = [&](const gdc::Polytope& shape, const std::vector<Vec3>& points, const std::vector<PairSample>& set) {
        return nsPerCall(
            [&] {
                double sink = 0;
                for (const PairSample& s : set) sink += m.normal(shape, points, s.a, s.b).x();
                volatile double keep = sink;
                (void)keep;
                return static_cast<long long>(set.size());
            },
            options);
    };
    row.cubeNs = timeSet(sets.cube, sets.cubePoints, sets.cubePairs);
    row.hullNs = timeSet(sets.hull, sets.hullPoints, sets.hullPairs);
    return row;
}

// ---- output -----------------------------------------------------------------------------------

std::string number(double v) {
    if (std::isnan(v)) return "";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return buffer;
}

/// A CSV field, quoted when it holds a comma or a quote.
std::string field(const std::string& text) {
    if (text.find_first_of(",\"") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return quoted + "\"";
}

void writeCsv(std::ostream& out, const std::vector<Row>& rows, const std::vector<NormalRow>& normals) {
    out << "table,group,parameter,value,time_ns,cube_normal_median_deg,cube_normal_p95_deg,cube_normal_max_deg,"
           "hull_normal_median_deg,hull_normal_p95_deg,hull_normal_max_deg,flat_hausdorff_mean_mm,"
           "flat_hausdorff_max_mm,flat_area_ratio,tilted_hausdorff_mean_mm,tilted_hausdorff_max_mm,"
           "tilted_area_ratio,contacts_mean,box_drop_alignment_deg,hull_time_ns\n";
    for (const Row& r : rows)
        out << "manifold," << field(r.group) << ',' << field(r.parameter) << ',' << field(r.value) << ',' << number(r.timeNs) << ','
            << number(r.cubeNormal.median) << ',' << number(r.cubeNormal.p95) << ',' << number(r.cubeNormal.max) << ','
            << number(r.hullNormal.median) << ',' << number(r.hullNormal.p95) << ',' << number(r.hullNormal.max) << ','
            << number(r.flatHausdorff.mean) << ',' << number(r.flatHausdorff.max) << ',' << number(r.flatArea) << ','
            << number(r.tiltedHausdorff.mean) << ',' << number(r.tiltedHausdorff.max) << ','
            << number(r.tiltedArea) << ',' << number(r.contacts) << ',' << number(r.boxDrop) << ','
            << number(r.hullTimeNs) << '\n';
    for (const NormalRow& r : normals)
        out << "normal,stage 1,method," << field(r.method) << ',' << number(r.cubeNs) << ',' << number(r.cube.median) << ','
            << number(r.cube.p95) << ',' << number(r.cube.max) << ',' << number(r.hull.median) << ','
            << number(r.hull.p95) << ',' << number(r.hull.max) << ",,,,,,,,," << number(r.hullNs) << '\n';
}

}  // namespace
}  // namespace gdcbench

int main(int argc, char** argv) {
    using namespace gdcbench;
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--quick") {
            options.samples = 20;
            options.minSeconds = 0.01;
            options.repetitions = 3;
        } else if (arg == "--out" && i + 1 < argc) {
            options.out = argv[++i];
        } else {
            std::cerr << "usage: bench_tradeoff [--quick] [--out FILE.csv]\n";
            return 2;
        }
    }
    OdeSession ode;
    const TestSets sets = makeTestSets(options.samples);
    std::vector<Row> rows;
    for (const Contender& c : settingsSweep(sets)) {
        rows.push_back(evaluate(c, sets, options));
        std::cerr << "settings " << c.parameter << " = " << c.value << ": " << rows.back().timeNs << " ns\n";
    }
    {
        References refs(sets);
        for (const Contender& c : referenceContenders(refs)) {
            rows.push_back(evaluate(c, sets, options));
            std::cerr << "reference " << c.parameter << " " << c.value << ": " << rows.back().timeNs << " ns\n";
        }
    }
    std::vector<NormalRow> normals;
    for (const NormalMethod& m : normalMethods()) {
        normals.push_back(evaluateNormal(m, sets, options));
        std::cerr << "normal " << m.name << ": " << normals.back().cubeNs << " ns\n";
    }
    if (options.out.empty()) {
        writeCsv(std::cout, rows, normals);
    } else {
        std::ofstream file(options.out);
        writeCsv(file, rows, normals);
    }
    return 0;
}

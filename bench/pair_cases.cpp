#include "pair_cases.hpp"

#include "bullet_shapes.hpp"
#include "ode_shapes.hpp"
#include "reference.hpp"

#include <gdcontact/collide.hpp>
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
#include <gdcontact/ode.hpp>
#endif

#include <array>
#include <map>
#include <memory>

namespace gdcbench {
namespace {

constexpr std::uint64_t kSeed = 20100701;
constexpr int kContactCapacity = 16;

/// A seed per case name (FNV-1a: the same on every standard library, unlike std::hash).
std::uint64_t seedOf(const std::string& name) {
    std::uint64_t h = 14695981039346656037ull;
    for (unsigned char ch : name) h = (h ^ ch) * 1099511628211ull;
    return kSeed ^ h;
}

gdc::Settings withMaxContacts(int maxContacts) {
    gdc::Settings settings;
    settings.maxContacts = maxContacts;
    return settings;
}

std::vector<dReal> flatten(const std::vector<Vec3>& points) {
    std::vector<dReal> flat;
    for (const Vec3& p : points) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
    return flat;
}

/// dCollide with ODE's native colliders, or with the gdcontact ODE adapter called directly
/// (without install(), so both can run in one program).
using OdeCollider = int (*)(dGeomID, dGeomID, int, dContactGeom*);
int nativeCollide(dGeomID a, dGeomID b, int maxContacts, dContactGeom* contacts) {
    return dCollide(a, b, maxContacts, contacts, sizeof(dContactGeom));
}
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
int adapterCollide(dGeomID a, dGeomID b, int maxContacts, dContactGeom* contacts) {
    return gdc::ode::collide(a, b, maxContacts, contacts, sizeof(dContactGeom));
}
#endif

/// The geoms of one ODE contender: one per pose, posed once outside the timed loop; except for
/// hulls above kReposeAbove vertices, where creating a dConvex per pose costs seconds of set-up
/// (ODE's dxConvex::FillEdges) and one geom is re-posed per call instead, and its AABB brought up
/// to date as ODE's space would before any collider runs (a loop over the hull's vertices, charged
/// to every ODE contender alike: gdcontact's adapter reads the AABB to notice dGeomSetConvex, and
/// without the update it paid ODE's recomputation alone). A single geom (a plane) serves every
/// pose. Destroyed with this object (by the OdeConvex that owns it, or here).
constexpr int kReposeAbove = 256;

struct PosedGeoms {
    std::vector<dGeomID> geoms;
    std::vector<Pose> poses;  // only when re-posed per call
    std::vector<std::unique_ptr<OdeConvex>> convexStorage;
    dGeomID at(int poseIndex) const {
        if (poses.empty()) return geoms[poseIndex % geoms.size()];
        setGeomPose(geoms[0], poses[poseIndex % poses.size()]);
        dReal aabb[6];
        dGeomGetAABB(geoms[0], aabb);
        return geoms[0];
    }
    ~PosedGeoms() {
        if (convexStorage.empty())
            for (dGeomID g : geoms) dGeomDestroy(g);
    }
};
using Geoms = std::shared_ptr<PosedGeoms>;

/// Poses `make()` geoms: one per pose, or one re-posed per call for big hulls.
template <class Make>
Geoms posed(const std::vector<Pose>& poses, int vertexCount, Geoms out, Make make) {
    if (vertexCount > kReposeAbove) {
        make();
        out->poses = poses;
        return out;
    }
    for (const Pose& pose : poses) setGeomPose(make(), pose);
    return out;
}

Geoms odeBoxes(const std::vector<Pose>& poses) {
    auto out = std::make_shared<PosedGeoms>();
    return posed(poses, 8, out, [&] {
        out->geoms.push_back(createOdeBox(nullptr, Vec3::Constant(kCubeHalfExtent)));
        return out->geoms.back();
    });
}

Geoms odeConvexes(const gdc::Polytope& hull, const std::vector<Pose>& poses) {
    auto out = std::make_shared<PosedGeoms>();
    return posed(poses, static_cast<int>(hull.vertices().size()), out, [&] {
        out->convexStorage.push_back(std::make_unique<OdeConvex>(nullptr, hull));
        out->geoms.push_back(out->convexStorage.back()->geom());
        return out->geoms.back();
    });
}

Geoms odePlane() {
    auto out = std::make_shared<PosedGeoms>();
    out->geoms.push_back(createOdePlane(nullptr, groundPlane()));
    return out;
}

#ifdef GDCONTACT_BENCH_ODE_ADAPTER
Geoms adapterConvexes(const std::vector<Vec3>& points, const std::vector<Pose>& poses) {
    auto out = std::make_shared<PosedGeoms>();
    const std::vector<dReal> flat = flatten(points);
    return posed(poses, static_cast<int>(points.size()), out, [&] {
        out->geoms.push_back(gdc::ode::createConvex(nullptr, flat.data(), static_cast<unsigned>(points.size())));
        return out->geoms.back();
    });
}
#endif

std::function<int(int)> odePair(Geoms a, Geoms b, OdeCollider collider, int maxContacts) {
    return [a, b, collider, maxContacts](int i) {
        std::array<dContactGeom, kContactCapacity> contacts;
        return collider(a->at(i), b->at(i), maxContacts, contacts.data());
    };
}

/// The contenders of a case, each built only if the filter wants it (so that a driver measuring
/// one contender does not pay for the others' set-up).
struct Contenders {
    const ContenderFilter& want;
    std::vector<PairContender> list;
    template <class Make>
    void add(std::string name, Make make) {
        if (!want || want(name)) list.push_back({std::move(name), make()});
    }
};

using BulletPoses = std::vector<std::pair<btTransform, btTransform>>;
BulletPoses bulletPoses(const std::vector<Pose>& a, const std::vector<Pose>& b) {
    BulletPoses out;
    for (std::size_t i = 0; i < a.size(); ++i) out.emplace_back(toBullet(a[i]), toBullet(b[i]));
    return out;
}

/// A Bullet detector on shared shapes, one pair of transforms per pose.
template <class Shape, class Detector>
std::function<int(int)> bulletPair(std::shared_ptr<Shape> shape, BulletPoses poses, Detector detector) {
    return [shape, poses = std::move(poses), detector](int i) {
        BulletContacts out;
        const auto& [a, b] = poses[i % poses.size()];
        return detector(*shape, a, *shape, b, out);
    };
}

/// The cycled poses of a cube pair case: A jittered about its canonical pose relative to B, then
/// both moved by one more small rigid jitter (so that B's world pose differs per pose as well,
/// while the relative tilt stays within kJitterRadians).
void cubePairPoses(const PairCase& c, int count, std::uint64_t seed, std::vector<Pose>& a, std::vector<Pose>& b) {
    const std::vector<Pose> relative = jitteredPoses(c.poseA, count, seed);
    const std::vector<Pose> common = jitteredPoses({Mat3::Identity(), Vec3::Zero()}, count, seed ^ 0x5bd1e995u);
    a.clear(), b.clear();
    for (int i = 0; i < count; ++i) {
        a.push_back(compose(common[i], relative[i]));
        b.push_back(compose(common[i], c.poseB));
    }
}

std::vector<PairContender> cubePairContenders(const PairCase& c, bool flat, const ContenderFilter& want) {
    std::vector<Pose> posesA{c.poseA}, posesB{c.poseB};
    if (!flat) cubePairPoses(c, kPosesPerCase, seedOf(c.name), posesA, posesB);
    auto cube = std::make_shared<gdc::Polytope>(gdc::Polytope::box(Vec3::Constant(kCubeHalfExtent)));
    const std::vector<Vec3> corners = boxVertices(Vec3::Constant(kCubeHalfExtent));
    auto cubeHull = std::make_shared<gdc::Polytope>(gdc::Polytope::fromPoints(corners));
    const gdc::Settings settings = withMaxContacts(c.maxContacts);
    const int m = c.maxContacts;

    // Interleaved: each ODE collider next to gdcontact's answer to it.
    Contenders out{want, {}};
    out.add("ode_dBoxBox", [&] { return odePair(odeBoxes(posesA), odeBoxes(posesB), nativeCollide, m); });
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
    out.add("gdcontact_ode_box", [&] { return odePair(odeBoxes(posesA), odeBoxes(posesB), adapterCollide, m); });
#endif
    if (!flat)
        out.add("gdcontact", [&] {
            return [cube, posesA, posesB, settings](int i) {
                return gdc::collide(*cube, posesA[i], *cube, posesB[i], settings).pointCount;
            };
        });
    out.add("ode_convex_ccd", [&] {
        return odePair(odeConvexes(*cubeHull, posesA), odeConvexes(*cubeHull, posesB), nativeCollide, m);
    });
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
    out.add("gdcontact_ode_hull8", [&] {
        return odePair(adapterConvexes(corners, posesA), adapterConvexes(corners, posesB), adapterCollide, m);
    });
#endif
    if (flat) return std::move(out.list);
    out.add("gdcontact_hull8", [&] {
        return [cubeHull, posesA, posesB, settings](int i) {
            return gdc::collide(*cubeHull, posesA[i], *cubeHull, posesB[i], settings).pointCount;
        };
    });
    // A box against the same cube as a hull: the general pipeline with one box and one hull.
    out.add("gdcontact_box_hull8", [&] {
        return [cube, cubeHull, posesA, posesB, settings](int i) {
            return gdc::collide(*cube, posesA[i], *cubeHull, posesB[i], settings).pointCount;
        };
    });
    const BulletPoses bullet = bulletPoses(posesA, posesB);
    std::shared_ptr<btBoxShape> bulletBox = makeBulletBox(Vec3::Constant(kCubeHalfExtent));
    std::shared_ptr<btConvexHullShape> bulletHull = makeBulletHull(corners);  // cheap at 8 vertices
    out.add("bullet_boxbox", [&] { return bulletPair(bulletBox, bullet, bulletBoxBox); });
    out.add("bullet_gjk_epa", [&] { return bulletPair(bulletHull, bullet, bulletGjkEpa); });
    out.add("bullet_gjk_clip", [&] { return bulletPair(bulletHull, bullet, bulletGjkClip); });
    out.add("bullet_sat_clip", [&] { return bulletPair(bulletHull, bullet, bulletSatClip); });
    return std::move(out.list);
}

/// A cube on the ground plane as a box (box_plane) or as an 8-vertex hull (convex_plane).
std::vector<PairContender> cubePlaneContenders(const PlaneCase& c, bool asHull, bool flat,
                                               const ContenderFilter& want) {
    const std::vector<Pose> poses =
        flat ? std::vector<Pose>{c.pose} : jitteredPoses(c.pose, kPosesPerCase, seedOf(c.name));
    const std::vector<Vec3> corners = boxVertices(Vec3::Constant(kCubeHalfExtent));
    auto shape = std::make_shared<gdc::Polytope>(asHull ? gdc::Polytope::fromPoints(corners)
                                                        : gdc::Polytope::box(Vec3::Constant(kCubeHalfExtent)));
    const gdc::Settings settings = withMaxContacts(c.maxContacts);
    const gdc::HalfSpace plane = c.plane;
    const int m = c.maxContacts;
    Geoms ground = odePlane();
    Contenders out{want, {}};
    out.add("ode", [&] {
        return odePair(asHull ? odeConvexes(*shape, poses) : odeBoxes(poses), ground, nativeCollide, m);
    });
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
    out.add("gdcontact_ode", [&] {
        return odePair(asHull ? adapterConvexes(corners, poses) : odeBoxes(poses), ground, adapterCollide, m);
    });
#endif
    if (!flat)
        out.add("gdcontact", [&] {
            return [shape, poses, plane, settings](int i) {
                return gdc::collide(*shape, poses[i], plane, settings).pointCount;
            };
        });
    return std::move(out.list);
}

/// The hull size sweep: 16 random touching relative poses of two equal near-spheres (and of the
/// hull on the plane), the same since issue 6 (seeded per size).
struct SweepPoses {
    std::vector<Vec3> points;
    std::vector<Pose> a, b, onPlane;
};

/// The poses of one size, computed once (the hull–hull and hull–plane cases share them; placing
/// the big hulls by bisection takes a while).
const SweepPoses& sweepPoses(int size) {
    static std::map<int, SweepPoses> cache;
    auto found = cache.find(size);
    if (found != cache.end()) return found->second;
    SweepPoses& s = cache[size];
    s.points = sweepHullPoints(size);
    for (const auto& [a, b] : touchingPoses(s.points, s.points, kPosesPerCase, kRestingOverlap, kSeed + size))
        s.a.push_back(a), s.b.push_back(b);
    const gdc::HalfSpace ground = groundPlane();
    Random random(kSeed ^ static_cast<std::uint64_t>(size));
    for (int i = 0; i < kPosesPerCase; ++i) {
        // Rest the hull on the plane with its lowest vertex kRestingOverlap below it.
        Pose pose{random.rotation(), Vec3::Zero()};
        double lowest = 1e300;
        for (const Vec3& v : s.points) lowest = std::min(lowest, ground.normal.dot(pose.rotation * v));
        pose.position = ground.normal * (ground.offset - lowest - kRestingOverlap);
        s.onPlane.push_back(pose);
    }
    return s;  // a reference into the cache: std::map never moves its elements
}

std::vector<PairContender> hullPairContenders(int size, const ContenderFilter& want) {
    const SweepPoses& s = sweepPoses(size);
    auto hull = std::make_shared<gdc::Polytope>(gdc::Polytope::fromPoints(s.points));
    const int m = gdc::Settings{}.maxContacts;
    Contenders out{want, {}};
    out.add("ode_convex_ccd",
            [&] { return odePair(odeConvexes(*hull, s.a), odeConvexes(*hull, s.b), nativeCollide, m); });
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
    out.add("gdcontact_ode", [&] {
        return odePair(adapterConvexes(s.points, s.a), adapterConvexes(s.points, s.b), adapterCollide, m);
    });
#endif
    out.add("gdcontact", [&] {
        return [hull, a = s.a, b = s.b](int i) { return gdc::collide(*hull, a[i], *hull, b[i]).pointCount; };
    });
    // Bullet's hull (its polyhedral features take a while for big hulls) only if a contender needs it.
    std::shared_ptr<btConvexHullShape> bulletHullStorage;
    auto bulletHull = [&] {
        if (!bulletHullStorage) bulletHullStorage = makeBulletHull(s.points);
        return bulletHullStorage;
    };
    const BulletPoses bullet = bulletPoses(s.a, s.b);
    out.add("bullet_gjk_epa", [&] { return bulletPair(bulletHull(), bullet, bulletGjkEpa); });
    out.add("bullet_gjk_clip", [&] { return bulletPair(bulletHull(), bullet, bulletGjkClip); });
    // Bullet's SAT tries every edge pair, each projected on every vertex: O(E²·V). Beyond 64
    // vertices a single call would take longer than the whole sweep may.
    if (size <= 64) out.add("bullet_sat_clip", [&] { return bulletPair(bulletHull(), bullet, bulletSatClip); });
    return std::move(out.list);
}

std::vector<PairContender> hullPlaneContenders(int size, const ContenderFilter& want) {
    const SweepPoses& s = sweepPoses(size);
    auto hull = std::make_shared<gdc::Polytope>(gdc::Polytope::fromPoints(s.points));
    const gdc::HalfSpace ground = groundPlane();
    const int m = gdc::Settings{}.maxContacts;
    Geoms plane = odePlane();
    Contenders out{want, {}};
    out.add("ode", [&] { return odePair(odeConvexes(*hull, s.onPlane), plane, nativeCollide, m); });
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
    out.add("gdcontact_ode", [&] { return odePair(adapterConvexes(s.points, s.onPlane), plane, adapterCollide, m); });
#endif
    out.add("gdcontact", [&] {
        return [hull, poses = s.onPlane, ground](int i) { return gdc::collide(*hull, poses[i], ground).pointCount; };
    });
    return std::move(out.list);
}

}  // namespace

std::vector<Pose> jitteredPoses(const Pose& canonical, int count, std::uint64_t seed) {
    Random random(seed);
    std::vector<Pose> poses;
    for (int i = 0; i < count; ++i) {
        const Vec3 axis = random.unitVector();
        const double angle = random.uniform(-kJitterRadians, kJitterRadians);
        Vec3 shift;
        for (int k = 0; k < 3; ++k) shift[k] = random.uniform(-kJitterMetres, kJitterMetres);
        poses.push_back({rotation(axis, angle) * canonical.rotation, canonical.position + shift});
    }
    return poses;
}

std::vector<PairCaseSet> pairCaseSets() {
    using Filter = const ContenderFilter&;
    std::vector<PairCaseSet> sets;
    for (const PairCase& c : cubePairCases())
        sets.push_back({"box_box", c.name, kPosesPerCase, [c](Filter f) { return cubePairContenders(c, false, f); }});
    for (const PlaneCase& c : cubePlaneCases()) {
        sets.push_back({"box_plane", c.name, kPosesPerCase,
                        [c](Filter f) { return cubePlaneContenders(c, false, false, f); }});
        sets.push_back({"convex_plane", c.name, kPosesPerCase,
                        [c](Filter f) { return cubePlaneContenders(c, true, false, f); }});
    }
    for (int size : hullSizes()) {
        const std::string n = std::to_string(size);
        sets.push_back({"hull_hull", n, kPosesPerCase, [size](Filter f) { return hullPairContenders(size, f); }});
        sets.push_back({"hull_plane", n, kPosesPerCase, [size](Filter f) { return hullPlaneContenders(size, f); }});
    }
    // The single exactly flat pose of the target cases (secondary: it flatters every collider).
    for (const PairCase& c : cubePairCases())
        if (c.name != "vertex_face" && c.name != "deep_overlap")
            sets.push_back({"box_box_flat", c.name, 1, [c](Filter f) { return cubePairContenders(c, true, f); }});
    for (const PlaneCase& c : cubePlaneCases())
        if (c.name == "face") {
            sets.push_back({"box_plane_flat", c.name, 1,
                            [c](Filter f) { return cubePlaneContenders(c, false, true, f); }});
            sets.push_back({"convex_plane_flat", c.name, 1,
                            [c](Filter f) { return cubePlaneContenders(c, true, true, f); }});
        }
    // The curved pairs (issue 33, curved_cases.cpp).
    for (PairCaseSet& set : curvedCaseSets()) sets.push_back(std::move(set));
    return sets;
}

}  // namespace gdcbench

// Per-pair collide time of gdcontact, ODE 0.16.2's native colliders and Bullet on the same shapes
// and poses (fixtures.hpp). Names are family/case/contender; the counter "contacts" is the number
// of contacts returned per call (averaged when a benchmark cycles over several poses).
// scripts/bench runs this with repetitions and reports medians and ratios to the ODE equivalent.
//
// Poses are set outside the timed loop: every contender is timed on the query alone (ODE gets one
// geom per pose, so that no dGeomSetRotation is timed; see PosedGeoms for the big hulls).
#include "bullet_shapes.hpp"
#include "fixtures.hpp"
#include "ode_shapes.hpp"
#include "reference.hpp"

#include <gdcontact/collide.hpp>
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
#include <gdcontact/ode.hpp>
#endif

#include <benchmark/benchmark.h>

#include <array>
#include <functional>
#include <memory>
#include <string>

namespace gdcbench {
namespace {

constexpr int kPosesPerSize = 16;  // random relative poses cycled through in the size sweep
constexpr std::uint64_t kSeed = 20100701;
constexpr int kContactCapacity = 16;

/// Registers a benchmark calling `collidePose(poseIndex)` with indices cycling through
/// 0 … poseCount−1; `collidePose` returns the number of contacts it produced.
void registerPair(const std::string& name, int poseCount, std::function<int(int)> collidePose) {
    benchmark::RegisterBenchmark(name.c_str(), [poseCount, collidePose](benchmark::State& state) {
        long long contacts = 0;
        int pose = 0;
        for (auto _ : state) {
            const int n = collidePose(pose);
            benchmark::DoNotOptimize(n);
            contacts += n;
            if (++pose == poseCount) pose = 0;
        }
        state.counters["contacts"] =
            benchmark::Counter(static_cast<double>(contacts), benchmark::Counter::kAvgIterations);
    });
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
/// (ODE's dxConvex::FillEdges) and one geom is re-posed per call instead, which costs under 0.1 %
/// of such a call. Destroyed with this object (by the OdeConvex that owns it, or here).
constexpr int kReposeAbove = 256;

struct PosedGeoms {
    std::vector<dGeomID> geoms;
    std::vector<Pose> poses;  // only when re-posed per call
    std::vector<std::unique_ptr<OdeConvex>> convexStorage;
    dGeomID at(int poseIndex) const {
        if (poses.empty()) return geoms[poseIndex % geoms.size()];
        setGeomPose(geoms[0], poses[poseIndex]);
        return geoms[0];
    }
    ~PosedGeoms() {
        if (convexStorage.empty())
            for (dGeomID g : geoms) dGeomDestroy(g);
    }
};

/// Poses `make()` geoms: one per pose, or one re-posed per call for big hulls.
template <class Make>
std::shared_ptr<PosedGeoms> posed(const std::vector<Pose>& poses, int vertexCount, std::shared_ptr<PosedGeoms> out,
                                  Make make) {
    if (vertexCount > kReposeAbove) {
        make();
        out->poses = poses;
        return out;
    }
    for (const Pose& pose : poses) setGeomPose(make(), pose);
    return out;
}

std::shared_ptr<PosedGeoms> odeBoxes(const std::vector<Pose>& poses) {
    auto out = std::make_shared<PosedGeoms>();
    return posed(poses, 8, out, [&] {
        out->geoms.push_back(createOdeBox(nullptr, Vec3::Constant(kCubeHalfExtent)));
        return out->geoms.back();
    });
}

std::shared_ptr<PosedGeoms> odeConvexes(const gdc::Polytope& hull, const std::vector<Pose>& poses) {
    auto out = std::make_shared<PosedGeoms>();
    return posed(poses, static_cast<int>(hull.vertices().size()), out, [&] {
        out->convexStorage.push_back(std::make_unique<OdeConvex>(nullptr, hull));
        out->geoms.push_back(out->convexStorage.back()->geom());
        return out->geoms.back();
    });
}

#ifdef GDCONTACT_BENCH_ODE_ADAPTER
std::shared_ptr<PosedGeoms> adapterConvexes(const std::vector<Vec3>& points, const std::vector<Pose>& poses) {
    auto out = std::make_shared<PosedGeoms>();
    const std::vector<dReal> flat = flatten(points);
    return posed(poses, static_cast<int>(points.size()), out, [&] {
        out->geoms.push_back(gdc::ode::createConvex(nullptr, flat.data(), static_cast<unsigned>(points.size())));
        return out->geoms.back();
    });
}
#endif

std::function<int(int)> odePair(std::shared_ptr<PosedGeoms> a, std::shared_ptr<PosedGeoms> b, OdeCollider collider,
                                int maxContacts) {
    return [a, b, collider, maxContacts](int i) {
        std::array<dContactGeom, kContactCapacity> contacts;
        return collider(a->at(i), b->at(i), maxContacts, contacts.data());
    };
}

void registerCubePairs() {
    auto cube = std::make_shared<gdc::Polytope>(gdc::Polytope::box(Vec3::Constant(kCubeHalfExtent)));
    const std::vector<Vec3> corners = boxVertices(Vec3::Constant(kCubeHalfExtent));
    auto cubeHull = std::make_shared<gdc::Polytope>(gdc::Polytope::fromPoints(corners));
    std::shared_ptr<btBoxShape> bulletBox = makeBulletBox(Vec3::Constant(kCubeHalfExtent));
    std::shared_ptr<btConvexHullShape> bulletHull = makeBulletHull(corners);

    for (const PairCase& c : cubePairCases()) {
        const std::string prefix = "box_box/" + c.name + "/";
        const gdc::Settings settings = withMaxContacts(c.maxContacts);
        registerPair(prefix + "gdcontact", 1, [cube, c, settings](int) {
            return gdc::collide(*cube, c.poseA, *cube, c.poseB, settings).pointCount;
        });
        registerPair(prefix + "gdcontact_hull8", 1, [cubeHull, c, settings](int) {
            return gdc::collide(*cubeHull, c.poseA, *cubeHull, c.poseB, settings).pointCount;
        });
        registerPair(prefix + "ode_dBoxBox", 1,
                     odePair(odeBoxes({c.poseA}), odeBoxes({c.poseB}), nativeCollide, c.maxContacts));
        registerPair(prefix + "ode_convex_ccd", 1,
                     odePair(odeConvexes(*cubeHull, {c.poseA}), odeConvexes(*cubeHull, {c.poseB}), nativeCollide,
                             c.maxContacts));
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
        registerPair(prefix + "gdcontact_ode_box", 1,
                     odePair(odeBoxes({c.poseA}), odeBoxes({c.poseB}), adapterCollide, c.maxContacts));
        registerPair(prefix + "gdcontact_ode_hull8", 1,
                     odePair(adapterConvexes(corners, {c.poseA}), adapterConvexes(corners, {c.poseB}),
                             adapterCollide, c.maxContacts));
#endif
        const btTransform a = toBullet(c.poseA), b = toBullet(c.poseB);
        registerPair(prefix + "bullet_boxbox", 1, [bulletBox, a, b](int) {
            BulletContacts out;
            return bulletBoxBox(*bulletBox, a, *bulletBox, b, out);
        });
        registerPair(prefix + "bullet_gjk_epa", 1, [bulletHull, a, b](int) {
            BulletContacts out;
            return bulletGjkEpa(*bulletHull, a, *bulletHull, b, out);
        });
        registerPair(prefix + "bullet_gjk_clip", 1, [bulletHull, a, b](int) {
            BulletContacts out;
            return bulletGjkClip(*bulletHull, a, *bulletHull, b, out);
        });
        registerPair(prefix + "bullet_sat_clip", 1, [bulletHull, a, b](int) {
            BulletContacts out;
            return bulletSatClip(*bulletHull, a, *bulletHull, b, out);
        });
    }
}

void registerCubePlanes() {
    auto cube = std::make_shared<gdc::Polytope>(gdc::Polytope::box(Vec3::Constant(kCubeHalfExtent)));
    const std::vector<Vec3> corners = boxVertices(Vec3::Constant(kCubeHalfExtent));
    auto cubeHull = std::make_shared<gdc::Polytope>(gdc::Polytope::fromPoints(corners));
    auto plane = std::make_shared<PosedGeoms>();
    plane->geoms.push_back(createOdePlane(nullptr, groundPlane()));

    for (const PlaneCase& c : cubePlaneCases()) {
        const gdc::Settings settings = withMaxContacts(c.maxContacts);
        registerPair("box_plane/" + c.name + "/gdcontact", 1, [cube, c, settings](int) {
            return gdc::collide(*cube, c.pose, c.plane, settings).pointCount;
        });
        registerPair("box_plane/" + c.name + "/ode", 1, odePair(odeBoxes({c.pose}), plane, nativeCollide, c.maxContacts));
        registerPair("convex_plane/" + c.name + "/gdcontact", 1, [cubeHull, c, settings](int) {
            return gdc::collide(*cubeHull, c.pose, c.plane, settings).pointCount;
        });
        registerPair("convex_plane/" + c.name + "/ode", 1,
                     odePair(odeConvexes(*cubeHull, {c.pose}), plane, nativeCollide, c.maxContacts));
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
        registerPair("box_plane/" + c.name + "/gdcontact_ode", 1,
                     odePair(odeBoxes({c.pose}), plane, adapterCollide, c.maxContacts));
        registerPair("convex_plane/" + c.name + "/gdcontact_ode", 1,
                     odePair(adapterConvexes(corners, {c.pose}), plane, adapterCollide, c.maxContacts));
#endif
    }
}

void registerSizeSweep() {
    auto plane = std::make_shared<PosedGeoms>();
    plane->geoms.push_back(createOdePlane(nullptr, groundPlane()));
    const gdc::HalfSpace ground = groundPlane();
    const int maxContacts = gdc::Settings{}.maxContacts;

    for (int size : hullSizes()) {
        const std::vector<Vec3> points = sweepHullPoints(size);
        auto hull = std::make_shared<gdc::Polytope>(gdc::Polytope::fromPoints(points));
        const auto pairPoses = touchingPoses(points, points, kPosesPerSize, kRestingOverlap, kSeed + size);
        std::vector<Pose> posesA, posesB, planePoses;
        for (const auto& [a, b] : pairPoses) posesA.push_back(a), posesB.push_back(b);
        Random random(kSeed ^ static_cast<std::uint64_t>(size));
        for (int i = 0; i < kPosesPerSize; ++i) {
            // Rest the hull on the plane with its lowest vertex kRestingOverlap below it.
            Pose pose{random.rotation(), Vec3::Zero()};
            double lowest = 1e300;
            for (const Vec3& v : points) lowest = std::min(lowest, ground.normal.dot(pose.rotation * v));
            pose.position = ground.normal * (ground.offset - lowest - kRestingOverlap);
            planePoses.push_back(pose);
        }

        const std::string pair = "hull_hull/" + std::to_string(size) + "/";
        const std::string onPlane = "hull_plane/" + std::to_string(size) + "/";
        registerPair(pair + "gdcontact", kPosesPerSize, [hull, pairPoses](int i) {
            return gdc::collide(*hull, pairPoses[i].first, *hull, pairPoses[i].second).pointCount;
        });
        registerPair(pair + "ode_convex_ccd", kPosesPerSize,
                     odePair(odeConvexes(*hull, posesA), odeConvexes(*hull, posesB), nativeCollide, maxContacts));
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
        registerPair(pair + "gdcontact_ode", kPosesPerSize,
                     odePair(adapterConvexes(points, posesA), adapterConvexes(points, posesB), adapterCollide,
                             maxContacts));
#endif
        std::shared_ptr<btConvexHullShape> bulletHull = makeBulletHull(points);
        std::vector<std::pair<btTransform, btTransform>> bulletPoses;
        for (const auto& [a, b] : pairPoses) bulletPoses.emplace_back(toBullet(a), toBullet(b));
        registerPair(pair + "bullet_gjk_epa", kPosesPerSize, [bulletHull, bulletPoses](int i) {
            BulletContacts out;
            return bulletGjkEpa(*bulletHull, bulletPoses[i].first, *bulletHull, bulletPoses[i].second, out);
        });
        registerPair(pair + "bullet_gjk_clip", kPosesPerSize, [bulletHull, bulletPoses](int i) {
            BulletContacts out;
            return bulletGjkClip(*bulletHull, bulletPoses[i].first, *bulletHull, bulletPoses[i].second, out);
        });
        // Bullet's SAT tries every edge pair, each projected on every vertex: O(E²·V). Beyond 64
        // vertices a single call would take longer than the whole sweep may.
        if (size <= 64)
            registerPair(pair + "bullet_sat_clip", kPosesPerSize, [bulletHull, bulletPoses](int i) {
                BulletContacts out;
                return bulletSatClip(*bulletHull, bulletPoses[i].first, *bulletHull, bulletPoses[i].second, out);
            });

        registerPair(onPlane + "gdcontact", kPosesPerSize, [hull, planePoses, ground](int i) {
            return gdc::collide(*hull, planePoses[i], ground).pointCount;
        });
        registerPair(onPlane + "ode", kPosesPerSize, odePair(odeConvexes(*hull, planePoses), plane, nativeCollide, maxContacts));
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
        registerPair(onPlane + "gdcontact_ode", kPosesPerSize,
                     odePair(adapterConvexes(points, planePoses), plane, adapterCollide, maxContacts));
#endif
    }
}

}  // namespace
}  // namespace gdcbench

int main(int argc, char** argv) {
    gdcbench::OdeSession ode;
    gdcbench::registerCubePairs();
    gdcbench::registerCubePlanes();
    gdcbench::registerSizeSweep();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    // Destroy the geoms the benchmarks hold while ODE is still initialised.
    benchmark::ClearRegisteredBenchmarks();
    return 0;
}

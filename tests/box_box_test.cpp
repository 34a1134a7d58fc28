// The box–box path (box_box.cpp) against the general pipeline (generalManifold): the
// same manifold — normal, points, depths, count, features — on random poses of every kind of box
// pair, and pinned cases where the two could part (a face exactly at the angular tolerance, a
// very thin box, exactly touching boxes, coincident centres).
#include "contact/box_box.hpp"
#include "general_pipeline.hpp"
#include "box_poses.hpp"
#include "contact_checks.hpp"
#include "geometry/growth_distance.hpp"
#include "geometry/minkowski.hpp"
#include "sanitizer_scale.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>

using namespace gdc;
using namespace gdc::testing;

namespace {

// The largest differences found, relative to the pair's size.
struct Differences {
    double normal = 0, position = 0, depth = 0;
    int poses = 0, mismatches = 0;
};

// Runs both paths; returns false (and prints the pose) when count or features differ, or a value
// differs by more than `relative` × size.
bool compare(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB, const Settings& settings,
             Differences& found, double relative = 1e-9) {
    const Manifold fast = collide(a, poseA, b, poseB, settings);
    const Manifold general = generalManifold(a, poseA, b, poseB, settings);
    ++found.poses;
    const double size = a.radius() + b.radius();
    bool same = fast.pointCount == general.pointCount && fast.featureA.type == general.featureA.type &&
                fast.featureA.index == general.featureA.index && fast.featureB.type == general.featureB.type &&
                fast.featureB.index == general.featureB.index;
    if (same && fast.pointCount > 0) {
        found.normal = std::max(found.normal, (fast.normal - general.normal).norm());
        same = (fast.normal - general.normal).norm() <= relative;
        for (int i = 0; i < fast.pointCount; ++i) {
            const double position = (fast.points[i].position - general.points[i].position).norm() / size;
            const double depth = std::abs(fast.points[i].depth - general.points[i].depth) / size;
            found.position = std::max(found.position, position);
            found.depth = std::max(found.depth, depth);
            same = same && position <= relative && depth <= relative;
        }
    }
    if (!same) {
        ++found.mismatches;
        if (found.mismatches <= 5) {
            std::printf("box-box mismatch: halfA %.17g %.17g %.17g halfB %.17g %.17g %.17g\n", a.boxHalfExtents().x(),
                        a.boxHalfExtents().y(), a.boxHalfExtents().z(), b.boxHalfExtents().x(), b.boxHalfExtents().y(),
                        b.boxHalfExtents().z());
            std::printf("  fast: %d points, features %d:%d %d:%d; general: %d points, features %d:%d %d:%d\n",
                        fast.pointCount, int(fast.featureA.type), fast.featureA.index, int(fast.featureB.type),
                        fast.featureB.index, general.pointCount, int(general.featureA.type), general.featureA.index,
                        int(general.featureB.type), general.featureB.index);
        }
    }
    return same;
}

}  // namespace

TEST_CASE("box numbering: the faces, normals and edges box_box.cpp assumes") {
    std::mt19937 random(11);
    for (int trial = 0; trial < 200; ++trial) {
        const Vec3 half = randomHalfExtents(random);
        const Polytope box = Polytope::box(half);
        REQUIRE(box.faces().size() == 6);
        for (int axis = 0; axis < 3; ++axis)
            for (int positive = 0; positive < 2; ++positive) {
                const Polytope::Face& face = box.faces()[2 * axis + positive];
                REQUIRE(face.normal == (positive ? 1.0 : -1.0) * Vec3::Unit(axis));  // exactly
                REQUIRE(face.offset == half[axis]);
            }
        const int expected[12][2] = {{0, 1}, {0, 2}, {0, 4}, {1, 3}, {1, 5}, {2, 3},
                                     {2, 6}, {3, 7}, {4, 5}, {4, 6}, {5, 7}, {6, 7}};
        REQUIRE(box.edges().size() == 12);
        for (int e = 0; e < 12; ++e) {
            REQUIRE(box.edges()[e].tail == expected[e][0]);
            REQUIRE(box.edges()[e].head == expected[e][1]);
        }
        for (int v = 0; v < 8; ++v)
            for (int axis = 0; axis < 3; ++axis)
                REQUIRE(box.vertices()[v][axis] == ((v >> axis) & 1 ? half[axis] : -half[axis]));
    }
}

TEST_CASE("selectBoxFeature picks selectFeature's feature, ties and exact tolerance boundaries included") {
    std::mt19937 random(12);
    std::uniform_real_distribution<double> symmetric(-1, 1), unit(0, 1);
    const Polytope box = Polytope::box(Vec3(0.3, 1.1, 0.02));
    int checked = 0;
    for (double radians : {0.0, 0.01, 0.05, 0.3, 0.7}) {
        const detail::AngularTolerance tolerance(radians);
        auto check = [&](Vec3 d) {
            const Feature general = detail::selectFeature(box, d, box.supportVertex(d), tolerance);
            const Feature fast = detail::selectBoxFeature(d, tolerance);
            INFO("direction " << d.transpose() << " tolerance " << radians);
            REQUIRE(fast.type == general.type);
            REQUIRE(fast.index == general.index);
            ++checked;
        };
        for (int trial = 0; trial < 20000; ++trial) {
            Vec3 d(symmetric(random), symmetric(random), symmetric(random));
            // Components exactly 0, and exactly at the tolerance's cosine and sine, in any sign.
            const double pick = unit(random);
            const int axis = static_cast<int>(unit(random) * 3) % 3, other = (axis + 1) % 3;
            if (pick < 0.2) d[axis] = unit(random) < 0.5 ? 0.0 : -0.0;
            if (pick < 0.1) d[other] = 0;
            d.normalize();
            if (pick > 0.7) {
                // Near a face or an edge's arc: one component at (or an ulp from) cos, one at sin.
                const double sign = unit(random) < 0.5 ? -1 : 1;
                const double c = pick > 0.85 ? tolerance.cosine : tolerance.sine;
                d = Vec3::Zero();
                d[axis] = sign * c;
                d[other] = unit(random) < 0.5 ? std::sqrt(std::max(0.0, 1 - c * c)) : 0.0;
                d[3 - axis - other] = unit(random) < 0.3 ? 0.0 : symmetric(random) * 1e-3;
                if (unit(random) < 0.3) d[axis] = std::nextafter(d[axis], unit(random) < 0.5 ? 2.0 : -2.0);
            }
            check(d);
        }
        for (int axis = 0; axis < 3; ++axis)
            for (double sign : {-1.0, 1.0}) check(sign * Vec3::Unit(axis));
    }
    INFO("directions checked: " << checked);
    CHECK(checked > 100000);
}

// boxGrowth against the growth distance's definition (design.md): with K = (A − c_A) − (B − c_B)
// and d = c_B − c_A, σ = max over K's facet normals m of (m·d) / h_K(m), and the normal is the
// maximiser. For two boxes K's facet normals are among the 15 separating axes — A's three face
// normals, B's three and the nine cross products — and h_K(m) = halfA·|m| + halfB·|Rᵀm|. The
// oracle evaluates all 15 directly; boxGrowth may skip, reorder and guard them as it likes. Where
// two axes tie within rounding at the maximum the normal may be either (or their sum), so only
// σ is compared there. The face-overlap bound must be a lower bound of the pair's overlap along
// every face normal of either box. Poses of every kind of box pair (box_poses.hpp) and exactly
// axis-aligned or single-axis turns (zero components: parallel edges, ties between facets).
TEST_CASE("boxGrowth is the growth distance over the 15 axes, its bound below every face overlap (10^5 poses per kind)") {
    const char* names[] = {"resting face", "face near the tolerance", "edge-edge", "vertex-face", "deep", "nearly touching",
                           "scattered", "axis-aligned or turned about one axis"};
    constexpr int kPoses = scaledForSanitizers(100000);
    for (int k = 0; k <= int(BoxPoseKind::Count); ++k) {
        std::mt19937 random(20261127 + 31 * k);
        std::uniform_real_distribution<double> unit(0, 1), symmetric(-1, 1);
        int valid = 0, untied = 0;
        double largestGrowth = 0, largestNormal = 0, largestBoundExcess = -INFINITY;
        for (int trial = 0; trial < kPoses; ++trial) {
            const Vec3 halfA = randomHalfExtents(random), halfB = randomHalfExtents(random);
            Pose bInA;
            if (k < int(BoxPoseKind::Count)) {
                bInA = boxPoseOfKind(BoxPoseKind(k), halfA, halfB, unit(random) * 0.7, k == 6 ? 1.5 : 0.8, random);
            } else {
                const Mat3 rotation = unit(random) < 0.3 ? Mat3::Identity()
                                                         : rotationAbout(Vec3::Unit(trial % 3),
                                                                         unit(random) < 0.5 ? M_PI / 2 * (trial % 4)
                                                                                            : symmetric(random) * M_PI);
                Vec3 offset = Vec3(symmetric(random), symmetric(random), symmetric(random)) * (halfA.norm() + halfB.norm());
                if (unit(random) < 0.3) offset[trial % 3] = 0;
                if (unit(random) < 0.1) offset[(trial + 1) % 3] = 0;
                bInA = Pose{rotation, offset};
            }
            const double size = halfA.norm() + halfB.norm();
            const Mat3& r = bInA.rotation;
            const Vec3& d = bInA.position;
            const double separation = d.norm();
            const detail::BoxGrowth fast = detail::boxGrowth(halfA, halfB, r, d, separation, size);
            // The oracle: σ and its maximiser over the 15 axes, and the runner-up for ties.
            auto support = [&](const Vec3& m) { return halfA.dot(m.cwiseAbs()) + halfB.dot((r.transpose() * m).cwiseAbs()); };
            double best = -INFINITY, second = -INFINITY;
            Vec3 bestAxis = Vec3::Zero();
            auto consider = [&](const Vec3& m) {
                if (!(m.norm() > 1e-9)) return;  // parallel edges: no facet
                const double sigma = std::abs(m.dot(d)) / support(m);  // m and −m: both facets
                const Vec3 unitAxis = (m.dot(d) < 0 ? -m : m).normalized();
                if (sigma > best) {
                    if (!(bestAxis - unitAxis).isZero(1e-9)) second = best;
                    best = sigma, bestAxis = unitAxis;
                } else if (sigma > second && !(bestAxis - unitAxis).isZero(1e-9)) {
                    second = sigma;
                }
            };
            for (int i = 0; i < 3; ++i) consider(Vec3::Unit(i)), consider(r.col(i));
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) consider(Vec3::Unit(i).cross(r.col(j)));
            INFO(names[k] << ", trial " << trial);
            if (!(separation > 0)) {
                REQUIRE_FALSE(fast.valid);  // coincident centres: no ray
                continue;
            }
            REQUIRE(fast.valid);
            ++valid;
            const double growth = separation / fast.exitDistance;
            largestGrowth = std::max(largestGrowth, std::abs(growth - best) / std::abs(best));
            REQUIRE(std::abs(growth - best) <= 1e-12 * std::abs(best));
            if (best - second > 1e-9 * std::abs(best)) {
                ++untied;
                const double normalError = (fast.normal.normalized() - bestAxis).norm();
                largestNormal = std::max(largestNormal, normalError);
                REQUIRE(normalError <= 1e-12);
            }
            // The bound: below the overlap along each of the twelve face normals.
            auto overlap = [&](const Vec3& m) { return support(m) - m.dot(d); };
            for (int i = 0; i < 3; ++i)
                for (double sign : {-1.0, 1.0})
                    for (const Vec3& m : {Vec3(sign * Vec3::Unit(i)), Vec3(sign * r.col(i))}) {
                        largestBoundExcess = std::max(largestBoundExcess, fast.faceOverlapLowerBound - overlap(m));
                        REQUIRE(fast.faceOverlapLowerBound <= overlap(m) + 1e-12 * size);
                    }
        }
        std::printf("boxGrowth vs the 15-axis oracle, %s: %d poses, %d valid, %d with one maximising axis; largest "
                    "relative growth error %.3g, normal error %.3g; bound above a face overlap by at most %.3g\n",
                    names[k], kPoses, valid, untied, largestGrowth, largestNormal, largestBoundExcess);
        CHECK(valid > kPoses / 2);
        CHECK(untied > valid / 2);
    }
}

TEST_CASE("box-box path equals the general pipeline on random poses of every kind of box pair") {
    std::mt19937 random(20261123);
    std::uniform_real_distribution<double> unit(0, 1);
    Differences found;
    int points = 0, kinds[int(BoxPoseKind::Count)] = {}, touching[int(BoxPoseKind::Count)] = {};
    constexpr int kPoses = 105000;
    for (int trial = 0; trial < kPoses; ++trial) {
        const Vec3 halfA = randomHalfExtents(random), halfB = randomHalfExtents(random);
        const Polytope a = Polytope::box(halfA), b = Polytope::box(halfB);
        const Settings settings = randomBoxPairSettings(random, halfA.norm() + halfB.norm());
        const BoxPoseKind kind = static_cast<BoxPoseKind>(trial % int(BoxPoseKind::Count));
        ++kinds[int(kind)];
        const Pose relative = boxPoseOfKind(kind, halfA, halfB, settings.angularTolerance, 0.8, random);
        // Both moved to a random place (A's frame is where the pipeline computes).
        const Pose world{randomRotation(random), Vec3(unit(random), unit(random), unit(random)) * 10};
        const Pose poseB{world.rotation * relative.rotation, world.apply(relative.position)};
        compare(a, world, b, poseB, settings, found);
        const int count = generalManifold(a, world, b, poseB, settings).pointCount;
        points += count;
        touching[int(kind)] += count > 0;
    }
    std::printf("poses in contact per kind (of %d each): resting face %d, face near the tolerance %d, edge-edge %d, "
                "vertex-face %d, deep %d, nearly touching %d, random %d\n",
                kinds[0], touching[0], touching[1], touching[2], touching[3], touching[4], touching[5], touching[6]);
    std::printf("box-box vs general over %d poses (%d points): largest difference, relative to the size: normal %.3g, "
                "position %.3g, depth %.3g; %d poses differ\n",
                found.poses, points, found.normal, found.position, found.depth, found.mismatches);
    WARN("box-box vs general over " << found.poses << " poses: largest normal difference " << found.normal
                                    << ", position " << found.position << ", depth " << found.depth
                                    << " (relative to size); " << found.mismatches << " poses differ");
    CHECK(found.mismatches == 0);
    CHECK(found.normal <= 1e-9);
    CHECK(found.position <= 1e-9);
    CHECK(found.depth <= 1e-9);
}

TEST_CASE("box-box pinned: a face tilted exactly at the angular tolerance") {
    const Polytope base = Polytope::box(Vec3(1.0, 0.8, 0.5)), top = Polytope::box(Vec3(0.4, 0.3, 0.2));
    Settings settings;
    Differences found;
    for (double scale : {1 - 1e-12, 1.0, 1 + 1e-12}) {
        const double angle = settings.angularTolerance * scale;
        const Mat3 rotation = rotationAbout(Vec3::UnitX(), angle);
        const double lowest = (rotation.transpose() * Vec3::UnitZ()).cwiseAbs().dot(Vec3(0.4, 0.3, 0.2));
        const Pose poseB{rotation, Vec3(0.1, 0.05, 0.5 + lowest - 1e-3)};
        REQUIRE(compare(base, Pose{}, top, poseB, settings, found));
        const Manifold m = collide(base, Pose{}, top, poseB, settings);
        REQUIRE(m.pointCount > 0);
        CHECK(m.featureA.type == FeatureType::Face);  // A's top face: the normal lies along it
        CHECK(m.featureA.index == 5);
    }
}

TEST_CASE("box-box pinned: a very thin box, exactly touching boxes, coincident centres") {
    Settings settings;
    Differences found;
    SECTION("a plate 2e-6 thick on a box and a box on the plate") {
        const Polytope plate = Polytope::box(Vec3(0.5, 0.5, 1e-6)), block = Polytope::box(Vec3(0.3, 0.2, 0.1));
        for (double sink : {0.0, 5e-7, 1e-4}) {
            const Pose onPlate{rotationAbout(Vec3(1, 2, 0).normalized(), 0.003), Vec3(0.05, -0.1, 1e-6 + 0.1 - sink)};
            REQUIRE(compare(plate, Pose{}, block, onPlate, settings, found));
            REQUIRE(compare(block, Pose{}, plate, Pose{Mat3::Identity(), Vec3(0.02, 0, 0.1 + 1e-6 - sink)}, settings,
                            found));
        }
    }
    SECTION("exactly touching: depth 0 at the four corners of the smaller face") {
        const Polytope cube = Polytope::box(Vec3(0.5, 0.5, 0.5)), small = Polytope::box(Vec3(0.25, 0.25, 0.25));
        const Pose touching{Mat3::Identity(), Vec3(0.1, 0.1, 0.75)};
        REQUIRE(compare(cube, Pose{}, small, touching, settings, found));
        const Manifold m = collide(cube, Pose{}, small, touching, settings);
        REQUIRE(m.pointCount == 4);
        for (int i = 0; i < 4; ++i) CHECK(m.points[i].depth == 0);
        CHECK(m.normal == Vec3::UnitZ());
    }
    SECTION("coincident centres: the general fallback normal, a full manifold") {
        const Polytope a = Polytope::box(Vec3(0.5, 0.4, 0.3)), b = Polytope::box(Vec3(0.2, 0.6, 0.1));
        for (const Mat3& rotation : {Mat3(Mat3::Identity()), rotationAbout(Vec3(1, 1, 0).normalized(), 0.4)}) {
            REQUIRE(compare(a, Pose{}, b, Pose{rotation, Vec3::Zero()}, settings, found));
            CHECK(collide(a, Pose{}, b, Pose{rotation, Vec3::Zero()}, settings).pointCount > 0);
        }
    }
    SECTION("collide() dispatches boxes to the box path, other settings to the general pipeline") {
        const Polytope a = Polytope::box(Vec3(0.5, 0.4, 0.3)), b = Polytope::box(Vec3(0.2, 0.6, 0.1));
        CHECK(detail::boxBoxApplies(a, b, settings));
        Settings wide = settings;
        wide.angularTolerance = 0.8;
        CHECK_FALSE(detail::boxBoxApplies(a, b, wide));
        Settings sat = settings;
        sat.normalMethod = NormalMethod::SeparatingAxis;
        CHECK_FALSE(detail::boxBoxApplies(a, b, sat));
    }
    CHECK(found.mismatches == 0);
}

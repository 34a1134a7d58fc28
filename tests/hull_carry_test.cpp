// What the hull enumeration finds on its way (hull_gauge.hpp's HullGaugeCarry: the overlaps along
// the faces it evaluated, its exit facet and that facet's features) is carried to the later stages
// of the general pipeline — refineNormal's overlaps, stage 1's overlap and support searches, the
// depth certificate — instead of searching again. Checked here by what the carry must keep: ODE's
// contact contract (touching_poses.hpp, requireContactContract) on 10^5 random poses of each pair
// type that reaches the enumeration and on exactly parallel faces, the early out's bound against
// the searches it spares, and stage 2's face proof against the search.
#include "general_pipeline.hpp"
#include "geometry/minkowski.hpp"
#include "geometry/hull_gauge.hpp"
#include "contact/gauss_map.hpp"
#include "sanitizer_scale.hpp"
#include "touching_poses.hpp"

#include <cstdio>

using namespace gdc;
using namespace gdc::testing;

namespace {

constexpr int kPoses = scaledForSanitizers(100000);

void checkOn(const char* name, const Polytope& a, const Polytope& b, std::uint32_t seed) {
    requireContactContract("hull enumeration carried", name, a, b, kPoses, seed, 0.03, /*deepEveryThird=*/true,
                           [](auto&&... args) { return generalManifold(args...); });
}

// Faces of A and B exactly parallel (B turned like A, or like A and then a quarter turn about A's z):
// a face of B then reaches along d exactly as far as the parallel face of A, which the enumeration's
// bookkeeping of which facet is the exit must not mistake for no change (the oracle found it: the
// carry kept A's face with B's vertex below it while the exit was B's face, a support far off: the
// deepest point then fell short of the penetration).
void checkAligned(const char* name, const Polytope& a, const Polytope& b, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    double largestShortfall = 0;
    int touching = 0;
    const double size = a.radius() + b.radius();
    for (int i = 0; i < kPoses; ++i) {
        const Mat3 turn = i % 2 ? Mat3(rotationAbout(Vec3::UnitZ(), M_PI / 2)) : Mat3(Mat3::Identity());
        const Pose poseA{randomRotation(random), Vec3(unit(random), unit(random), unit(random))};
        // B above A along one of A's axes (mostly z), shifted sideways, overlapping by up to 2 %.
        const Vec3 axis = i % 3 == 0 ? Vec3::UnitX() : Vec3::UnitZ();
        const Vec3 half = Vec3(a.vertices()[a.supportVertex(axis)].dot(axis), 0, 0);
        const double reach = half.x() + b.vertices()[b.supportVertex(-(turn.transpose() * axis))].dot(-(turn.transpose() * axis));
        const Vec3 side = Vec3(unit(random), unit(random), unit(random)) * (0.3 * a.radius());
        const Vec3 offset = (reach - (0.0125 + 0.0075 * unit(random)) * size) * axis + (side - side.dot(axis) * axis);
        const Pose poseB{poseA.rotation * turn, poseA.apply(offset)};
        Settings settings;
        settings.maxContacts = 1 + i % kMaxManifoldPoints;
        const Manifold x = generalManifold(a, poseA, b, poseB, settings);
        INFO(name << " pose " << i << " normal " << x.normal.transpose() << " features " << int(x.featureA.type) << ":"
                  << x.featureA.index << " " << int(x.featureB.type) << ":" << x.featureB.index);
        if (x.empty()) continue;
        ++touching;
        // The deepest point carries the penetration along n (the exit of the ray through A − B).
        const Vec3 normalInA = poseA.rotation.transpose() * x.normal;
        const detail::SeparationAlong exit = detail::separationAlong(a, b, poseA.relative(poseB), normalInA, settings);
        REQUIRE(exit.valid);
        const double shortfall = (exit.distance - x.maxDepth()) / size;
        largestShortfall = std::max(largestShortfall, shortfall);
        REQUIRE(x.maxDepth() >= 0.96 * exit.distance - 1e-9 * size);
        REQUIRE(x.maxDepth() <= 1.04 * exit.distance + 1e-9 * size);
    }
    std::printf("hull enumeration carried, %s: %d poses (%d touching), deepest depth short of the exit by at most "
                "%.3g x size\n",
                name, kPoses, touching, largestShortfall);
    CHECK(touching > kPoses * 3 / 4);
}

}  // namespace

TEST_CASE("hull carry: faces of A and B exactly parallel (10^5 poses per pair type)") {
    std::mt19937 random(23);
    const ProvingHulls hulls(random);
    checkAligned("8-vertex hull pair, aligned", hulls.cubeHull, hulls.cubeHull, 21);
    checkAligned("cube hull on plank hull, aligned", hulls.cubeHull, hulls.plankHull, 22);
    checkAligned("box and cube hull, aligned", hulls.box, hulls.cubeHull, 23);
}

// The early out's inradius bound (collide.cpp, separatedByEarlyOut) decides as the two support
// searches along the line of centres that it spares: on 10^5 poses per pair type, overlapping,
// touching and apart by up to 20 % of the size, with and without a margin.
int compareEarlyOut(const char* name, const Polytope& a, const Polytope& b, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int separated = 0, spared = 0;
    for (int i = 0; i < kPoses; ++i) {
        auto [poseA, poseB] = randomTouchingPoses(random, a, b, i % 2 == 0, 0.03);
        const double size = a.radius() + b.radius();
        const Vec3 apart = poseB.position - poseA.position;
        if (i % 3 == 0 && apart.norm() > 0) poseB.position += apart.normalized() * (0.2 * unit(random) * size);
        const double margin = i % 5 == 0 ? 0.01 * size : 0.0;
        const double tolerance = 1e-9 * size;
        const Pose bInA = poseA.relative(poseB);
        const detail::MinkowskiDifference pair(a, b, bInA, Settings{}.bruteForceSupportLimit);
        const Vec3 offset = pair.centreB - pair.centreA;
        const double distance = offset.norm();
        // The replaced test, written out.
        const bool searched =
            distance > size + margin || (distance > 0 && pair.overlapAlong(offset / distance) < -margin - tolerance);
        const bool bounded = detail::separatedByEarlyOut(pair, offset, distance, size, margin, tolerance);
        INFO(name << " pose " << i);
        REQUIRE(bounded == searched);
        separated += searched;
        spared += a.inradius() + b.inradius() - distance >= -margin;
    }
    std::printf("early out by the inradius bound, %s: %d poses, %d separated, the searches spared on %d\n", name,
                kPoses, separated, spared);
    CHECK(separated > kPoses / 100);  // the poses exercise both answers
    return spared;
}

TEST_CASE("hull carry: the early out's inradius bound decides as the centre line's searches (10^5 poses per pair type)") {
    std::mt19937 random(23);
    const ProvingHulls hulls(random);
    // A resting cube pair is what the bound is for (r_A + r_B − |d| is the penetration there).
    CHECK(compareEarlyOut("8-vertex hull pair", hulls.cubeHull, hulls.cubeHull, 31) > kPoses / 10);
    CHECK(compareEarlyOut("cube hull and plank hull", hulls.cubeHull, hulls.plankHull, 32) > kPoses / 10);
    compareEarlyOut("box and cube hull", hulls.box, hulls.cubeHull, 33);
    compareEarlyOut("box pair", hulls.box, hulls.box, 34);
    compareEarlyOut("random hulls (24 and 10 points)", hulls.rock, hulls.pebble, 35);
    compareEarlyOut("large hull (300 points) and box", hulls.boulder, hulls.box, 36);
}

TEST_CASE("hull carry: the proving pairs reach the enumeration") {
    std::mt19937 random(23);
    const ProvingHulls hulls(random);
    CHECK(detail::hullGaugeApplies(hulls.cubeHull, hulls.cubeHull));
    CHECK(detail::hullGaugeApplies(hulls.cubeHull, hulls.plankHull));
    CHECK(detail::hullGaugeApplies(hulls.box, hulls.cubeHull));
    CHECK(detail::hullGaugeApplies(hulls.cubeHull, hulls.box));
    CHECK(detail::hullGaugeApplies(hulls.pebble, hulls.cubeHull));
}

TEST_CASE("hull carry: the carried findings keep the contact contract (10^5 poses per pair type)") {
    std::mt19937 random(23);
    const ProvingHulls hulls(random);
    checkOn("8-vertex hull pair", hulls.cubeHull, hulls.cubeHull, 11);
    checkOn("cube hull on plank hull (overhangs)", hulls.cubeHull, hulls.plankHull, 12);
    checkOn("box and cube hull", hulls.box, hulls.cubeHull, 13);
    checkOn("cube hull and box", hulls.cubeHull, hulls.box, 14);
    checkOn("small random hull and cube hull", hulls.pebble, hulls.cubeHull, 15);
    checkOn("random hulls (24 and 10 points)", hulls.rock, hulls.pebble, 16);
}

// Stage 2's proof for the face the enumeration proposes (gauss_map.hpp, faceIsSelected) against the
// Gauss-map search it spares: on 10^5 directions per polytope near each face's normal (on it, within
// the angular tolerance, at about its edge, and beyond), with the support vertex the search would
// get, every face the proof accepts is the feature the search returns. The proof must also fire
// (it is what spares the search on resting pairs).
int compareFaceProof(const char* name, const Polytope& polytope, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const Settings settings;
    const detail::AngularTolerance tolerance(settings.angularTolerance);
    const int faceCount = static_cast<int>(polytope.faces().size());
    int proved = 0;
    for (int i = 0; i < kPoses; ++i) {
        const int face = i % faceCount;
        const Vec3& n = polytope.faces()[face].normal;
        const double scales[] = {0.0, 1e-12, 0.3 * settings.angularTolerance, settings.angularTolerance,
                                 3 * settings.angularTolerance, 0.5};
        const double tilt = scales[(i / faceCount) % 6];
        const Vec3 direction = (n + tilt * Vec3(unit(random), unit(random), unit(random))).normalized();
        const int support = polytope.supportVertex(direction, Settings{}.bruteForceSupportLimit);
        // A support vertex of another face now and then: the proof must then not accept.
        const int anySupport = i % 7 == 0 ? static_cast<int>(random() % polytope.vertices().size()) : support;
        if (!detail::faceIsSelected(polytope, face, direction, anySupport, tolerance)) continue;
        ++proved;
        const Feature searched = detail::selectFeature(polytope, direction, anySupport, tolerance);
        INFO(name << " direction " << i << " face " << face);
        REQUIRE(searched.type == FeatureType::Face);
        REQUIRE(searched.index == face);
    }
    std::printf("stage 2's face proof, %s: %d directions, the search spared (and agreeing) on %d\n", name, kPoses,
                proved);
    return proved;
}

TEST_CASE("hull carry: stage 2's face proof returns the Gauss-map search's feature (10^5 directions per polytope)") {
    std::mt19937 random(23);
    const ProvingHulls hulls(random);
    CHECK(compareFaceProof("cube hull", hulls.cubeHull, 41) > kPoses / 4);
    CHECK(compareFaceProof("plank hull", hulls.plankHull, 42) > kPoses / 4);
    CHECK(compareFaceProof("box", hulls.box, 43) > kPoses / 4);
    compareFaceProof("small random hull (10 points)", hulls.pebble, 44);
    compareFaceProof("random hull (24 points)", hulls.rock, 45);
    // Beyond kOtherFaceCosineMaxFaces faces there is no bound (largestOtherCosine = 2): no proof.
    const int proved = compareFaceProof("large hull (300 points)", hulls.boulder, 46);
    if (hulls.boulder.faces().size() > Polytope::kOtherFaceCosineMaxFaces) CHECK(proved == 0);
}

// The enumeration's bound of every face's overlap (HullGaugeCarry::faceOverlapBound, which spares
// the overhang check) against the overlaps the check would search, along every face normal of A
// and of −B: never above any, on 10^5 poses per pair type (overlapping, touching, deep every third).
// The pipeline comparisons above show the manifolds it gives are the former path's.
int compareOverlapBound(const char* name, const Polytope& a, const Polytope& b, std::uint32_t seed) {
    std::mt19937 random(seed);
    int bounded = 0, clears = 0;
    double tightest = INFINITY;  // least (searched overlap − bound) / size
    for (int i = 0; i < kPoses; ++i) {
        auto [poseA, poseB] = randomTouchingPoses(random, a, b, i % 3 == 0, 0.03);
        const detail::MinkowskiDifference pair(a, b, poseA.relative(poseB), Settings{}.bruteForceSupportLimit);
        detail::HullGaugeCarry carry;
        const detail::GrowthDistance growth = detail::hullGrowth(pair, &carry);
        if (!growth.valid) continue;
        ++bounded;
        const double size = a.radius() + b.radius();
        double least = INFINITY;
        for (const Polytope::Face& face : a.faces()) least = std::min(least, pair.overlapAlong(face.normal));
        for (const Polytope::Face& face : b.faces())
            least = std::min(least, pair.overlapAlong(-(pair.bInA.rotation * face.normal)));
        INFO(name << " pose " << i << " bound " << carry.faceOverlapBound << " least face overlap " << least);
        REQUIRE(carry.faceOverlapBound <= least);
        tightest = std::min(tightest, (least - carry.faceOverlapBound) / size);
        clears += carry.faceOverlapBound >= 0.5 * pair.overlapAlong(growth.normal) + 1e-9 * size;
    }
    std::printf("the enumeration's face-overlap bound, %s: %d poses, never above a face's overlap (closest %.3g x size), "
                "clears the overhang check on %d\n",
                name, bounded, tightest, clears);
    return clears;
}

TEST_CASE("hull carry: the enumeration's bound of the face overlaps holds (10^5 poses per pair type)") {
    std::mt19937 random(23);
    const ProvingHulls hulls(random);
    CHECK(compareOverlapBound("8-vertex hull pair", hulls.cubeHull, hulls.cubeHull, 51) > kPoses / 10);
    compareOverlapBound("cube hull on plank hull", hulls.cubeHull, hulls.plankHull, 52);
    compareOverlapBound("box and cube hull", hulls.box, hulls.cubeHull, 53);
    compareOverlapBound("cube hull and box", hulls.cubeHull, hulls.box, 54);
    compareOverlapBound("small random hull and cube hull", hulls.pebble, hulls.cubeHull, 55);
    compareOverlapBound("random hulls (24 and 10 points)", hulls.rock, hulls.pebble, 56);
}

TEST_CASE("hull carry: Face::largestOtherCosine is the largest cosine to any other face, or 2 beyond the limit") {
    std::mt19937 random(23);
    const ProvingHulls hulls(random);
    // A box's faces are perpendicular or opposite: exactly 0.
    for (const Polytope::Face& face : hulls.cubeHull.faces()) CHECK(face.largestOtherCosine == 0);
    // A random hull: the brute-force maximum over every other face (not only its neighbours).
    for (const Polytope* polytope : {&hulls.rock, &hulls.pebble, &hulls.boulder}) {
        const auto& faces = polytope->faces();
        for (std::size_t f = 0; f < faces.size(); ++f) {
            if (faces.size() > static_cast<std::size_t>(Polytope::kOtherFaceCosineMaxFaces)) {
                CHECK(faces[f].largestOtherCosine == 2);
                continue;
            }
            double largest = -1;
            for (std::size_t g = 0; g < faces.size(); ++g)
                if (g != f) largest = std::max(largest, faces[f].normal.dot(faces[g].normal));
            CHECK(faces[f].largestOtherCosine == largest);
            CHECK(faces[f].largestOtherCosine >= faces[f].nearestNeighbourCosine);
        }
    }
    // Beyond the limit: a 2000-point cloud's hull has more faces than kOtherFaceCosineMaxFaces.
    const Polytope fine = Polytope::fromPoints(randomCloud(random, 2000, Vec3(0.6, 0.6, 0.6)));
    REQUIRE(fine.faces().size() > static_cast<std::size_t>(Polytope::kOtherFaceCosineMaxFaces));
    for (const Polytope::Face& face : fine.faces()) CHECK(face.largestOtherCosine == 2);
}

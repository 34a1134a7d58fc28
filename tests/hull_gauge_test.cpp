// The hull's stage-1 hook (hull_gauge.cpp): the growth distance of two small polytopes by
// enumerating the facet normals of K = (A − c_A) − (B − c_B), against
// - a brute-force gauge: the maximum of (m·d)/h_K(m) over every face normal of A and B and the cross
//   product of every edge pair, both signs, with supports by a loop over all vertices — a superset of
//   K's facet normals, no Gauss-map test, so the enumeration's σ must equal it (to rounding) and its
//   normal must attain it;
// - the GJK ray cast it replaces (growthDistance): σ within the cast's tolerance, and the cast's
//   normal a facet normal of K whose ratio is within that tolerance of σ (where they differ, the
//   exit lies within the tolerance of an edge of K: a tie);
// Pair types: 8- and 16-vertex random hulls, a box against a hull, thin and needle hulls, a cube hull
// pair (exactly parallel faces and edges). The largest differences are printed.
#include "geometry/growth_distance.hpp"
#include "geometry/hull_gauge.hpp"
#include "geometry/minkowski.hpp"
#include "geometry_oracles.hpp"
#include "sanitizer_scale.hpp"
#include "touching_poses.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <iterator>

using namespace gdc;
using namespace gdc::testing;

namespace {

constexpr int kPoses = scaledForSanitizers(20000);  // per pair type; six types: 1.2·10^5 poses

// (m·d)/h_K(m) by brute-force supports (B in A's frame).
double gaugeRatio(const detail::MinkowskiDifference& pair, const Vec3& m) {
    double highestA = -INFINITY, lowestB = INFINITY;
    for (const Vec3& v : pair.a.vertices()) highestA = std::max(highestA, m.dot(v));
    for (const Vec3& v : pair.b.vertices()) lowestB = std::min(lowestB, m.dot(pair.bInA.apply(v)));
    const double support = highestA - m.dot(pair.centreA) + m.dot(pair.centreB) - lowestB;
    return m.dot(pair.centreB - pair.centreA) / support;
}

// The brute-force gauge: every face normal, every edge pair's cross product, both signs.
double bruteForceGauge(const detail::MinkowskiDifference& pair) {
    double best = -INFINITY;
    auto consider = [&](const Vec3& m) {
        if (m.squaredNorm() > 0) best = std::max({best, gaugeRatio(pair, m), gaugeRatio(pair, -m)});
    };
    for (const auto& face : pair.a.faces()) consider(face.normal);
    for (const auto& face : pair.b.faces()) consider(pair.bInA.rotation * face.normal);
    for (const auto& ea : pair.a.edges()) {
        const Vec3 da = pair.a.vertices()[ea.head] - pair.a.vertices()[ea.tail];
        for (const auto& eb : pair.b.edges()) {
            const Vec3 db = pair.bInA.rotation * (pair.b.vertices()[eb.head] - pair.b.vertices()[eb.tail]);
            const Vec3 m = da.cross(db);
            if (m.squaredNorm() > 1e-18 * da.squaredNorm() * db.squaredNorm()) consider(m);
        }
    }
    return best;
}

struct Largest {
    double normalAngle = 0, growth = 0, castRatioShortfall = 0, bruteForce = 0;
    int poses = 0, normalsApart = 0;
};

double angleBetween(const Vec3& x, const Vec3& y) { return std::atan2(x.cross(y).norm(), x.dot(y)); }


void compareOn(const char* name, const Polytope& a, const Polytope& b, std::uint32_t seed) {
    REQUIRE(detail::hullGaugeApplies(a, b));
    std::mt19937 random(seed);
    Largest largest;
    const Settings settings;
    // The cast stops within rayCastTolerance·size of K's surface: its σ and its normal's ratio are
    // that close, relative to the exit distance (at least the inradius of K, ~size/10 here; thin
    // hulls less): a bound with ample room.
    const double castTolerance = 1e3 * settings.rayCastTolerance;
    for (int i = 0; i < kPoses; ++i) {
        const auto [poseA, poseB] = randomTouchingPoses(random, a, b, i % 2 == 0, 0.05);
        const detail::MinkowskiDifference pair(a, b, poseA.relative(poseB), settings.bruteForceSupportLimit);
        const detail::GrowthDistance enumerated = detail::hullGrowth(pair);
        const detail::GrowthDistance cast = detail::growthDistance(pair, settings, /*needWitnesses=*/false);
        INFO(name << " pose " << i);
        REQUIRE(enumerated.valid);
        REQUIRE(cast.valid);
        ++largest.poses;
        const double sigma = enumerated.growth;
        // Exact: the enumeration's σ is the gauge, and its normal attains it.
        if (i % 10 == 0) {
            const double brute = bruteForceGauge(pair);
            const double difference = std::abs(brute - sigma) / sigma;
            largest.bruteForce = std::max(largest.bruteForce, difference);
            REQUIRE(difference <= 1e-12);
        }
        REQUIRE(std::abs(gaugeRatio(pair, enumerated.normal) - sigma) <= 1e-9 * sigma);
        // Against the ray cast.
        const double growthDifference = std::abs(cast.growth - sigma) / sigma;
        largest.growth = std::max(largest.growth, growthDifference);
        REQUIRE(growthDifference <= castTolerance);
        const double shortfall = (sigma - gaugeRatio(pair, cast.normal)) / sigma;
        largest.castRatioShortfall = std::max(largest.castRatioShortfall, shortfall);
        REQUIRE(shortfall <= castTolerance);  // the cast's normal is (within its tolerance) an exit facet
        const double angle = angleBetween(enumerated.normal, cast.normal);
        largest.normalAngle = std::max(largest.normalAngle, angle);
        if (angle > 1e-6) ++largest.normalsApart;
    }
    std::printf(
        "hull gauge vs ray cast, %s: %d poses. growth normal: largest angle %.3g rad (%d poses > 1e-6), "
        "sigma rel. difference %.3g, cast normal's ratio short of sigma by %.3g, brute force %.3g\n",
        name, largest.poses, largest.normalAngle, largest.normalsApart, largest.growth, largest.castRatioShortfall,
        largest.bruteForce);
    // Normals apart only at ties of K's facets within the cast's tolerance: rare.
    CHECK(largest.normalsApart <= kPoses / 100);
}

}  // namespace

TEST_CASE("hull gauge: the enumeration is the gauge, and agrees with the ray cast (1.2*10^5 poses)") {
    std::mt19937 random(23);
    const Polytope hull8 = Polytope::fromPoints(randomCloud(random, 8, Vec3(0.5, 0.4, 0.3)));
    const Polytope other8 = Polytope::fromPoints(randomCloud(random, 8, Vec3(0.3, 0.3, 0.3)));
    const Polytope hull16 = Polytope::fromPoints(randomCloud(random, 16, Vec3(0.5, 0.5, 0.4)));
    const Polytope other16 = Polytope::fromPoints(randomCloud(random, 16, Vec3(0.4, 0.3, 0.3)));
    const Polytope box = Polytope::box(Vec3(0.4, 0.25, 0.6));
    const Polytope cubeHull = Polytope::fromPoints(boxCorners(Vec3(0.5, 0.5, 0.5)));
    const Polytope thin = Polytope::fromPoints(randomCloud(random, 12, Vec3(0.6, 0.5, 0.02)));
    const Polytope needle = Polytope::fromPoints(randomCloud(random, 10, Vec3(0.8, 0.03, 0.03)));
    compareOn("8-vertex hulls", hull8, other8, 1);
    compareOn("16-vertex hulls", hull16, other16, 2);
    compareOn("box and 8-vertex hull", box, hull8, 3);
    compareOn("cube hulls", cubeHull, cubeHull, 4);
    compareOn("thin and 16-vertex hull", thin, hull16, 5);
    compareOn("needle and thin hull", needle, thin, 6);
}

TEST_CASE("hull gauge: applies to small pairs, not to two boxes or large hulls") {
    std::mt19937 random(5);
    const Polytope small = Polytope::fromPoints(randomCloud(random, 8, Vec3::Ones()));
    const Polytope large = Polytope::fromPoints(randomCloud(random, 200, Vec3::Ones()));
    const Polytope box = Polytope::box(Vec3::Ones());
    CHECK(detail::hullGaugeApplies(small, small));
    CHECK(detail::hullGaugeApplies(box, small));
    CHECK_FALSE(detail::hullGaugeApplies(box, box));
    CHECK_FALSE(detail::hullGaugeApplies(large, small));
}

TEST_CASE("hull gauge: exact ties of K's facets (a ray through an edge or corner of K)") {
    // Two axis-aligned cube hulls, B's centre on a diagonal of A's: the ray leaves K = a cube of
    // half-size 1 through its edge (x, z) or its corner (x, y, z), where two or three facets tie. The
    // enumeration answers the middle of the tied normals (boxGrowth's rule); the cast any normal of
    // the cone it converges into. Both are exit normals (their ratio is σ).
    const Polytope cube = Polytope::fromPoints(boxCorners(Vec3(0.5, 0.5, 0.5)));
    const Settings settings;
    // Exact ties, and near ones: the z facet ahead by 1e-11 to 1e-7 (relative), inside and outside
    // the enumeration's 1e-12 tie band and the cast's 1e-9 tolerance.
    const Vec3 offsets[] = {Vec3(0.99, 0, 0.99), Vec3(0.99, 0.99, 0.99), Vec3(0.995, 0.3, 0.995),
                            Vec3(0.99, 0, 0.99 + 1e-11), Vec3(0.99, 0, 0.99 + 1e-9), Vec3(0.99, 0, 0.99 + 1e-7),
                            Vec3(0.99, 0.99 + 1e-9, 0.99 + 2e-9)};
    for (int i = 0; i < int(std::size(offsets)); ++i) {
        const Vec3& offset = offsets[i];
        const bool exactTie = i < 3;
        const Pose poseA{Mat3::Identity(), Vec3::Zero()}, poseB{Mat3::Identity(), offset};
        const detail::MinkowskiDifference pair(cube, cube, poseA.relative(poseB), settings.bruteForceSupportLimit);
        const detail::GrowthDistance enumerated = detail::hullGrowth(pair);
        const detail::GrowthDistance cast = detail::growthDistance(pair, settings, false);
        REQUIRE(enumerated.valid);
        REQUIRE(cast.valid);
        // The middle of the tied face normals.
        Vec3 expected = Vec3::Zero();
        for (int k = 0; k < 3; ++k)
            if (offset[k] == offset.maxCoeff() || (offset[k] == 0.99 || offset[k] == 0.995)) expected[k] = 1;
        // Exact ties: the middle; near ones: the facet ahead, +z, however little (the exact answer).
        CHECK((enumerated.normal - (exactTie ? expected.normalized() : Vec3(Vec3::UnitZ()))).norm() < 1e-12);
        CHECK(std::abs(gaugeRatio(pair, cast.normal) - enumerated.growth) <= 1e-7 * enumerated.growth);
        std::printf("hull gauge tie at offset (%.12g, %.12g, %.12g): growth normal (%.6f, %.6f, %.6f) vs cast (%.6f, %.6f, %.6f)\n",
                    offset.x(), offset.y(), offset.z(), enumerated.normal.x(), enumerated.normal.y(), enumerated.normal.z(),
                    cast.normal.x(), cast.normal.y(), cast.normal.z());
    }
}

// Per-pair state for a scene: order-insensitive keys, normalised A/B order, and forgetting pairs
// that were not seen in a step.
#include <gdcontact/tracking.hpp>

#include <catch2/catch.hpp>

using gdc::Manifold;
using gdc::Polytope;
using gdc::Pose;
using gdc::Vec3;
using gdc::tracking::PairCache;
using gdc::tracking::PersistentManifold;
using gdc::tracking::TrackingSettings;

namespace {

// Stand-ins for three geoms: only their addresses matter to the cache.
struct Body {
    Polytope shape;
    Pose pose;
};

Pose at(const Vec3& position) {
    return {gdc::Mat3::Identity(), position};
}

}  // namespace

TEST_CASE("the pair key is order-insensitive and the A/B order follows the caller", "[tracking]") {
    const Body floor{Polytope::box({2.0, 2.0, 0.5}), at(Vec3::Zero())};
    const Body cube{Polytope::box({0.5, 0.5, 0.5}), at(Vec3(0.0, 0.0, 0.99))};
    PairCache cache;

    cache.beginStep();
    PersistentManifold& first = cache.manifoldFor(&floor, &cube);
    Manifold result = first.update(floor.shape, floor.pose, cube.shape, cube.pose);
    cache.endStep();
    REQUIRE(result.pointCount == 1);
    CHECK(result.normal.isApprox(Vec3::UnitZ(), 1e-9));
    CHECK(cache.size() == 1);

    // Next step the broad phase hands the pair over the other way round: same state, mirrored,
    // so the caller passes (cube, floor) and gets the normal from the cube towards the floor.
    cache.beginStep();
    PersistentManifold& second = cache.manifoldFor(&cube, &floor);
    CHECK(&second == &first);
    CHECK(second.pointCount() == 1);
    result = second.update(cube.shape, cube.pose, floor.shape, floor.pose);
    cache.endStep();
    CHECK(result.normal.isApprox(-Vec3::UnitZ(), 1e-9));
    CHECK(second.lastUpdate().dropped == 0);
    // MPR's point of this step lands on the stored one (same geometry), which it refreshes.
    CHECK(second.lastUpdate().mergedInto == 0);
    REQUIRE(result.pointCount == 1);
    CHECK(result.points[0].depth == Approx(0.01).margin(1e-9));
    CHECK(cache.size() == 1);
}

TEST_CASE("pairs not seen in a step are forgotten", "[tracking]") {
    int a = 0, b = 0, c = 0;  // only addresses are used
    PairCache cache;
    cache.beginStep();
    cache.manifoldFor(&a, &b);
    cache.manifoldFor(&b, &c);
    cache.manifoldFor(&c, &b);  // the same pair again
    cache.endStep();
    CHECK(cache.size() == 2);
    CHECK(cache.contains(&b, &a));
    CHECK(cache.contains(&c, &b));
    CHECK_FALSE(cache.contains(&a, &c));

    cache.beginStep();
    cache.manifoldFor(&c, &b);
    cache.endStep();
    CHECK(cache.size() == 1);
    CHECK_FALSE(cache.contains(&a, &b));
    CHECK(cache.contains(&b, &c));

    cache.beginStep();
    cache.endStep();
    CHECK(cache.size() == 0);
}

TEST_CASE("a forgotten pair starts again from an empty manifold", "[tracking]") {
    const Body floor{Polytope::box({2.0, 2.0, 0.5}), at(Vec3::Zero())};
    const Body cube{Polytope::box({0.5, 0.5, 0.5}), at(Vec3(0.0, 0.0, 0.99))};
    PairCache cache;
    cache.beginStep();
    cache.manifoldFor(&floor, &cube).update(floor.shape, floor.pose, cube.shape, cube.pose);
    cache.endStep();
    cache.beginStep();  // the pair's bounding boxes stopped overlapping: not asked for
    cache.endStep();
    cache.beginStep();
    PersistentManifold& again = cache.manifoldFor(&floor, &cube);
    CHECK(again.pointCount() == 0);
    CHECK_FALSE(again.hasNormal());
    cache.endStep();
}

TEST_CASE("the cache hands its settings to every pair and rejects bad keys", "[tracking]") {
    TrackingSettings settings;
    settings.maxPoints = 2;
    settings.breakingThreshold = 0.05;
    PairCache cache(settings);
    int a = 0, b = 0;
    CHECK(cache.manifoldFor(&a, &b).settings().maxPoints == 2);
    CHECK(cache.manifoldFor(&a, &b).settings().breakingThreshold == 0.05);
    CHECK_THROWS_AS(cache.manifoldFor(&a, &a), gdc::InvalidInput);
    CHECK_THROWS_AS(cache.manifoldFor(nullptr, &a), gdc::InvalidInput);
    settings.maxPoints = 0;
    CHECK_THROWS_AS(PairCache(settings), gdc::InvalidInput);
}

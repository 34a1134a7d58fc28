// The pair table (src/contact/pair_table.hpp): every cell, in both orders a caller may ask for,
// against exact answers — ODE's contact contract for polytope pairs, the plane itself for
// half-spaces — and its mirrored cells against the cells they mirror.
#include "contact/pair_table.hpp"
#include "touching_poses.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace gdc;
using namespace gdc::testing;

namespace {

// collidePair as a (a, poseA, b, poseB, settings) → Manifold function, in `order`.
auto tableQuery(detail::ImportanceOrder order) {
    return [order](const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB, const Settings& settings) {
        Manifold manifold;
        detail::collidePair(detail::Shape::of(a), poseA, detail::Shape::of(b), poseB,
                            detail::PairQuery{settings, order}, manifold);
        return manifold;
    };
}

}  // namespace

TEST_CASE("pair table: every polytope cell meets ODE's contact contract, in both orders of points") {
    std::mt19937 random(31);
    const ProvingHulls hulls(random);
    const Polytope box = Polytope::box(Vec3(0.5, 0.3, 0.2));
    struct Pair {
        const char* name;
        const Polytope& a;
        const Polytope& b;
    } pairs[] = {{"box-box", box, hulls.box}, {"box-hull", box, hulls.rock},
                 {"hull-box", hulls.rock, box}, {"hull-hull", hulls.pebble, hulls.cubeHull}};
    REQUIRE(detail::Shape::of(box).kind == detail::ShapeKind::Box);
    REQUIRE(detail::Shape::of(hulls.rock).kind == detail::ShapeKind::Hull);
    std::uint32_t seed = 1;
    for (const Pair& pair : pairs)
        for (detail::ImportanceOrder order : {detail::ImportanceOrder::Full, detail::ImportanceOrder::AmongEqualDepths})
            requireContactContract("pair table", pair.name, pair.a, pair.b, 3000, seed++, 0.02, true, tableQuery(order));
}

TEST_CASE("pair table: a polytope on a half-space touches the plane, and the half-space as A mirrors it") {
    std::mt19937 random(32);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const ProvingHulls hulls(random);
    int touching = 0;
    for (const Polytope* shape : {&hulls.box, &hulls.rock, &hulls.boulder}) {
        const detail::Shape a = detail::Shape::of(*shape);
        for (int i = 0; i < 2000; ++i) {
            const detail::UnitHalfSpace plane =
                detail::normaliseHalfSpace(HalfSpace{Vec3(unit(random), unit(random), unit(random) + 2.0), unit(random)});
            const Pose pose{randomRotation(random), Vec3(unit(random), unit(random), unit(random))};
            const Pose unused{randomRotation(random), Vec3(unit(random), unit(random), unit(random))};
            Settings settings;
            settings.maxContacts = 1 + i % kMaxManifoldPoints;
            const auto order = i % 2 ? detail::ImportanceOrder::Full : detail::ImportanceOrder::AmongEqualDepths;
            Manifold onPlane, mirrored;
            detail::collidePair(a, pose, detail::Shape::of(plane), unused, {settings, order}, onPlane);
            detail::collidePair(detail::Shape::of(plane), unused, a, pose, {settings, order}, mirrored);
            INFO("pose " << i);
            REQUIRE(mirrored.pointCount == onPlane.pointCount);
            if (onPlane.empty()) continue;
            ++touching;
            // The plane's own normal, from A into its solid; each contact's point on A inside A and
            // as deep below the plane as the depth says, its point on B on the plane.
            REQUIRE((onPlane.normal + plane.normal).norm() <= 1e-12);
            const double size = shape->radius() + std::abs(plane.offset) + pose.position.norm();
            for (int k = 0; k < onPlane.pointCount; ++k) {
                const ContactPoint& p = onPlane.points[k];
                const Vec3 onA = p.position + 0.5 * p.depth * onPlane.normal;
                const Vec3 onB = p.position - 0.5 * p.depth * onPlane.normal;
                REQUIRE(signedDistance(*shape, pose, onA) <= 1e-9 * size);
                REQUIRE(std::abs(plane.normal.dot(onB) - plane.offset) <= 1e-9 * size);
                REQUIRE(std::abs(plane.offset - plane.normal.dot(onA) - p.depth) <= 1e-9 * size);
            }
            // The mirror: the normal reversed, the same points and depths, the features swapped.
            REQUIRE(mirrored.normal == -onPlane.normal);
            for (int k = 0; k < onPlane.pointCount; ++k) {
                REQUIRE(mirrored.points[k].position == onPlane.points[k].position);
                REQUIRE(mirrored.points[k].depth == onPlane.points[k].depth);
            }
            REQUIRE(mirrored.featureA.type == onPlane.featureB.type);
            REQUIRE(mirrored.featureA.index == onPlane.featureB.index);
            REQUIRE(mirrored.featureB.type == onPlane.featureA.type);
            REQUIRE(mirrored.featureB.index == onPlane.featureA.index);
        }
    }
    CHECK(touching > 1000);
}

TEST_CASE("pair table: two half-spaces and non-finite poses are refused with a clear error") {
    const detail::UnitHalfSpace ground{Vec3::UnitZ(), 0.0};
    const Polytope box = Polytope::box(Vec3(0.5, 0.5, 0.5));
    Manifold out;
    const Settings settings;
    CHECK_THROWS_WITH(detail::collidePair(detail::Shape::of(ground), Pose{}, detail::Shape::of(ground), Pose{},
                                          {settings}, out),
                      Catch::Contains("two half-spaces"));
    const Pose bad{Mat3::Identity(), Vec3(NAN, 0, 0)};
    CHECK_THROWS_WITH(detail::collidePair(detail::Shape::of(box), Pose{}, detail::Shape::of(box), bad, {settings}, out),
                      Catch::Contains("pose of B is not finite"));
    // A half-space has no pose: whatever the caller passes for it is not read.
    CHECK_NOTHROW(detail::collidePair(detail::Shape::of(box), Pose{}, detail::Shape::of(ground), bad, {settings}, out));
    CHECK(out.pointCount == 4);
}

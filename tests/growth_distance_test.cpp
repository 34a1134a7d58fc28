// Stage 1: the growth distance and its normal against analytic answers, and its pitfalls:
// coincident contraction points, grazing rays, deep overlap with the centres crossed.
#include "geometry_oracles.hpp"
#include "geometry/growth_distance.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace gdc;
using namespace gdc::testing;
using gdc::detail::growthDistance;

TEST_CASE("growth factor of two axis-aligned unit cubes is their centre distance over 1") {
    // A − B of two unit cubes is a cube of half-size 1, so the ray along x exits at h = 1 and
    // α = |p_A − p_B| / 1: below 1 overlapping, above 1 separated.
    const Polytope cube = Polytope::box(Vec3(0.5, 0.5, 0.5));
    for (double distance : {0.3, 0.9, 1.0, 1.4, 3.0}) {
        auto gd = growthDistance(cube, cube, makePose(Vec3(distance, 0, 0)), {});
        REQUIRE(gd.valid);
        CHECK(gd.growth == Approx(distance).epsilon(1e-12));
        CHECK((gd.normal - Vec3::UnitX()).norm() < 1e-12);
    }
}

TEST_CASE("growth normal of a cube resting on a slab is the slab's face normal") {
    const Polytope slab = Polytope::box(Vec3(2, 2, 0.25)), cube = Polytope::box(Vec3(0.5, 0.5, 0.5));
    std::mt19937 random(11);
    std::uniform_real_distribution<double> offset(-1.2, 1.2), yaw(-M_PI, M_PI);
    for (int i = 0; i < 200; ++i) {
        Pose pose = makePose(Vec3(offset(random), offset(random), 0.749), rotationAbout(Vec3::UnitZ(), yaw(random)));
        auto gd = growthDistance(slab, cube, pose, {});
        REQUIRE(gd.valid);
        CHECK(gd.normal.dot(Vec3::UnitZ()) > 1 - 1e-12);
        CHECK(gd.growth < 1);
    }
}

TEST_CASE("coincident contraction points give no growth direction (the caller falls back)") {
    const Polytope cube = Polytope::box(Vec3(0.5, 0.5, 0.5));
    auto gd = growthDistance(cube, cube, makePose(Vec3::Zero(), rotationAbout(Vec3(1, 2, 3), 0.4)), {});
    CHECK_FALSE(gd.valid);
}

TEST_CASE("grazing ray through an edge and a vertex of A − B still gives a unit normal in the normal cone") {
    const Polytope cube = Polytope::box(Vec3(0.5, 0.5, 0.5));
    // Centre offsets along a diagonal make the ray pass exactly through an edge (then a vertex) of
    // the cube A − B; any normal of the cone there is a valid answer, none may be zero or NaN.
    for (const Vec3& direction : {Vec3(1, 1, 0), Vec3(1, 1, 1), Vec3(1, 1, 1e-9)}) {
        for (double scale : {0.5, 1.0, 2.0, 4.0}) {
            auto gd = growthDistance(cube, cube, makePose(scale * direction.normalized() * std::sqrt(2.0)), {});
            REQUIRE(gd.valid);
            CHECK(gd.normal.allFinite());
            CHECK(gd.normal.norm() == Approx(1).margin(1e-12));
            // The exit point is the corner region: the normal has non-negative components.
            CHECK(gd.normal.minCoeff() > -1e-9);
            CHECK(gd.normal.dot(direction.normalized()) > 0.5);
        }
    }
}

TEST_CASE("deep overlap with the centres crossed still yields a finite growth and unit normal") {
    const Polytope plank = Polytope::box(Vec3(2, 0.2, 0.2)), cube = Polytope::box(Vec3(0.3, 0.3, 0.3));
    std::mt19937 random(5);
    for (int i = 0; i < 200; ++i) {
        Pose pose = makePose(Vec3(std::uniform_real_distribution<double>(-1.5, 1.5)(random), 0.01, -0.02),
                             randomRotation(random));
        auto gd = growthDistance(plank, cube, pose, {});
        REQUIRE(gd.valid);
        CHECK(gd.normal.norm() == Approx(1).margin(1e-12));
        CHECK(gd.growth > 0);
        CHECK(gd.growth < 1);
    }
}

TEST_CASE("witness points lie on the surfaces of A and B") {
    const Polytope ico = Polytope::fromPoints({Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0),
                                               Vec3(0, 0, 1), Vec3(0, 0, -1)});
    std::mt19937 random(9);
    std::uniform_real_distribution<double> coordinate(-1.8, 1.8);
    for (int i = 0; i < 300; ++i) {
        Pose bInA = makePose(Vec3(coordinate(random), coordinate(random), coordinate(random)), randomRotation(random));
        auto gd = growthDistance(ico, ico, bInA, {});
        if (!gd.valid) continue;
        CHECK(std::abs(signedDistance(ico, Pose{}, gd.witnessA)) < 1e-9);
        CHECK(std::abs(signedDistance(ico, bInA, gd.witnessB)) < 1e-9);
        // The scaled shapes touch where the witnesses lie on the line through the centres.
        Vec3 along = gd.witnessA - gd.witnessB;
        Vec3 centres = bInA.position;
        CHECK(along.cross(centres).norm() <= 1e-9 * (1 + along.norm() * centres.norm()));
    }
}

TEST_CASE("the closed-form growth distance of two boxes equals the GJK ray cast") {
    const Polytope boxA = Polytope::box(Vec3(0.5, 0.3, 0.8)), boxB = Polytope::box(Vec3(0.2, 0.6, 0.4));
    const std::vector<Vec3> corners = boxB.vertices();
    const Polytope hullB = Polytope::fromPoints(corners);  // the same box, not flagged as one
    REQUIRE_FALSE(hullB.isBox());
    std::mt19937 random(41);
    std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
    for (int i = 0; i < 500; ++i) {
        Pose bInA = makePose(Vec3(coordinate(random), coordinate(random), coordinate(random)), randomRotation(random));
        auto closedForm = growthDistance(boxA, boxB, bInA, {}, /*needWitnesses=*/false);
        auto cast = growthDistance(boxA, hullB, bInA, {});
        REQUIRE(closedForm.valid == cast.valid);
        CHECK(closedForm.growth == Approx(cast.growth).epsilon(1e-9));
        CHECK(closedForm.normal.dot(cast.normal) > 1 - 1e-9);
    }
}

// Issue 21: a parallelogram facet of A − B (two parallel edges, as needles have) makes a flat
// tetrahedron in the ray cast. Its flatness was judged by volume against a face normal squared —
// a length cubed against a length to the fourth — so at size 1e-3 no tetrahedron was flat, and the
// barycentric weights of a rounding-sized volume came out ±1600: the cast's witness points, and
// the contact placed between them, lay far outside both bodies. Every weight must stay convex.
TEST_CASE("closest point of a flat tetrahedron has convex weights at every scale") {
    std::mt19937_64 random(2101);
    std::uniform_real_distribution<double> unit(-1, 1), tiny(-1e-15, 1e-15);
    for (double scale : {1e-3, 1e-1, 1.0, 1e3})
        for (int trial = 0; trial < 2000; ++trial) {
            // A parallelogram through (near) the origin, its fourth corner lifted by rounding.
            const Vec3 corner(unit(random), unit(random), unit(random)), u(unit(random), unit(random), unit(random)),
                v(unit(random), unit(random), unit(random));
            const double s = 0.3 * (unit(random) + 1.5), t = 0.3 * (unit(random) + 1.5);
            const Vec3 origin = corner + s * u + t * v;  // inside the parallelogram
            std::array<Vec3, 4> points = {scale * (corner - origin), scale * (corner + u - origin),
                                          scale * (corner + u + v - origin), scale * (corner + v - origin)};
            points[2] += scale * Vec3(tiny(random), tiny(random), tiny(random));
            const auto closest = gdc::detail::closestPointToOrigin(points, 4);
            CAPTURE(scale, trial);
            double sum = 0;
            Vec3 combination = Vec3::Zero();
            for (int i = 0; i < closest.count; ++i) {
                CHECK(closest.weights[i] >= -1e-9);
                CHECK(closest.weights[i] <= 1 + 1e-9);
                sum += closest.weights[i];
                combination += closest.weights[i] * points[closest.used[i]];
            }
            CHECK(sum == Approx(1).margin(1e-9));
            CHECK(combination.norm() <= 1e-9 * scale);
        }
}

namespace {

// The origin's projection on the plane of a triangle, in long double (the reference for the
// closest point when the projection falls inside).
Eigen::Matrix<long double, 3, 1> planeProjection(const std::array<Vec3, 4>& points) {
    using V = Eigen::Matrix<long double, 3, 1>;
    const V a = points[0].cast<long double>(), b = points[1].cast<long double>(), c = points[2].cast<long double>();
    const V normal = (b - a).cross(c - a);
    return normal * (normal.dot(a) / normal.squaredNorm());
}

// Whether v is the triangle's closest point to within what its coordinates allow: off the exact
// projection by at most 1e-11 of the triangle's extent from the origin (10^5 roundings of its
// coordinates), and with no vertex behind it: v·p ≥ |v|² − 1e-11·|v|·extent. The ray cast needs
// the second: a vertex of its simplex found again as the support point along v then has
// v·(x − p) > 0 as long as |v| > 1e-11·extent — the extent is below twice the pair's size (the cast
// starts half a size beyond A − B), so far below the cast's tolerance (1e-10 of the size) — and
// is never mistaken for a stall. Measured over the slivers below: 3200 and 5500 roundings (in
// units of 1e-16·extent); the barycentric form 3·10^7 and 4·10^15 (a vertex 0.4·extent behind v).
bool closeToPlane(const Vec3& v, const std::array<Vec3, 4>& points) {
    const Vec3 exact = planeProjection(points).cast<double>();
    const double extent = std::max({points[0].norm(), points[1].norm(), points[2].norm()});
    if (!((v - exact).norm() <= 1e-11 * extent)) return false;
    for (int i = 0; i < 3; ++i)
        if (!(v.dot(points[i]) >= v.squaredNorm() - 1e-11 * v.norm() * extent)) return false;
    return true;
}

}  // namespace

// Issue 21, oracle seeds 30651115 and 30662339: on a long thin triangle (a chord of A − B that two
// needles make, 700 long, the origin 7e-4 from its plane) the barycentric closest point was 7e-5
// rad off perpendicular: a vertex of the simplex lay behind v (v·p < |v|²), the cast took its own
// support point for no progress, stalled 1.5e-6 of the size short of the exit and returned a normal
// 0.05 rad from the exit facet's — a face in collide(A, B), an edge in collide(B, A). These are the
// two stalled triangles as the cast held them (x − support point), then thin triangles of every
// length and distance: the closest point is the plane's (closeToPlane).
TEST_CASE("closest point of a long thin triangle is perpendicular to it") {
    const std::array<std::array<Vec3, 4>, 2> stalled = {{
        {Vec3(210.23685642785676, -277.64805272013859, -88.280689828449837),
         Vec3(-210.22614314080488, 277.67938084143816, 88.284335975366773),
         Vec3(-200.28909988081011, 263.92011329450054, 84.018612587334076), Vec3::Zero()},
        {Vec3(0.55990212832672848, -2.752655558241198, -3.7505577083207946),
         Vec3(-0.92211069029924086, 4.5352353387912485, 6.1770255185516332),
         Vec3(-0.19745726816347409, 0.9682182354755593, 1.3207004366583106), Vec3::Zero()},
    }};
    for (const auto& points : stalled) {
        const auto closest = gdc::detail::closestPointToOrigin(points, 3);
        REQUIRE(closest.count == 3);
        CHECK(closeToPlane(closest.closest, points));
    }
    std::mt19937_64 random(2102);
    std::uniform_real_distribution<double> unit(-1, 1), fraction(0.05, 0.95);
    auto logUniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, 0.5 * (unit(random) + 1)); };
    int checked = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        // A sliver: a long side from p to q, the third corner near it (width ≪ length), the origin
        // over an interior point at a height ≪ length.
        const double length = logUniform(1e-3, 1e3), width = length * logUniform(1e-4, 1e-1), height = length * logUniform(1e-9, 1e-3);
        const Vec3 along = Vec3(unit(random), unit(random), unit(random)).normalized();
        const Vec3 side = along.cross(Vec3(unit(random), unit(random), unit(random))).normalized();
        const Vec3 up = along.cross(side);
        const Vec3 p = -fraction(random) * length * along, q = p + length * along;
        const Vec3 r = p + fraction(random) * length * along + width * side;
        // The origin over an interior point of the triangle (convex weights, none near zero).
        const double weightQ = fraction(random) * 0.5, weightR = fraction(random) * 0.5;
        const Vec3 foot = (1 - weightQ - weightR) * p + weightQ * q + weightR * r;
        const Vec3 shift = foot + height * up;  // the origin's place: every point is taken relative to it
        std::array<Vec3, 4> points = {p - shift, q - shift, r - shift, Vec3::Zero()};
        const auto closest = gdc::detail::closestPointToOrigin(points, 3);
        if (closest.count != 3) continue;  // the origin's foot fell outside (a corner of the sliver)
        ++checked;
        CAPTURE(trial, length, width, height);
        CHECK(closeToPlane(closest.closest, points));
    }
    CHECK(checked > 10000);
}

// The penetration oracle and mass properties that the scenes' quality measures rest on, against
// analytic answers.
#include "geometry.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace gdc;
using namespace gdc::scenes;

namespace {

Pose at(const Vec3& position, const Mat3& rotation = Mat3::Identity()) { return Pose{rotation, position}; }

}  // namespace

TEST_CASE("penetration depth of overlapping axis-aligned boxes is the smallest overlap") {
    const Polytope cube = Polytope::box(Vec3::Constant(0.5));
    // Stacked with 0.1 overlap vertically, shifted 0.3 sideways: overlaps 0.7 (x), 1 (y), 0.1 (z).
    CHECK(penetrationDepth(cube, at({0, 0, 0}), cube, at({0.3, 0, 0.9})) == Approx(0.1).epsilon(1e-12));
    CHECK(penetrationDepth(cube, at({0.3, 0, 0.9}), cube, at({0, 0, 0})) == Approx(0.1).epsilon(1e-12));
    // Side by side with 0.02 overlap along y.
    CHECK(penetrationDepth(cube, at({0, 0, 0}), cube, at({0.1, 0.98, 0.05})) == Approx(0.02).epsilon(1e-12));
}

TEST_CASE("penetration depth is zero for separated and exactly touching boxes") {
    const Polytope cube = Polytope::box(Vec3::Constant(0.5));
    CHECK(penetrationDepth(cube, at({0, 0, 0}), cube, at({0, 0, 1.1})) == 0.0);
    CHECK(penetrationDepth(cube, at({0, 0, 0}), cube, at({0.2, 0.1, 1.0})) == 0.0);
}

TEST_CASE("penetration depth of an edge pressed into a face is how far the edge is below the face") {
    const Polytope cube = Polytope::box(Vec3::Constant(0.5));
    const Mat3 edgeDown = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()).toRotationMatrix();
    const double lowestEdge = 0.5 * std::sqrt(2.0);
    for (double depth : {1e-6, 1e-3, 0.05}) {
        const Pose upper = at({0.1, 0.05, 0.5 + lowestEdge - depth}, edgeDown);
        CHECK(penetrationDepth(cube, at({0, 0, 0}), cube, upper) == Approx(depth).epsilon(1e-9));
    }
}

TEST_CASE("penetration depth of crossed ridges is found on the edge-edge axis") {
    // Two edge-up/edge-down cubes whose ridges cross at right angles. No face of either cube is
    // horizontal; only the cross product of the two ridges (vertical) separates them, so the
    // answer comes from the edge-edge axes alone.
    const Polytope cube = Polytope::box(Vec3::Constant(0.5));
    const double halfDiagonal = 0.5 * std::sqrt(2.0);
    const Mat3 ridgeAlongX = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()).toRotationMatrix();
    const Mat3 ridgeAlongY = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitY()).toRotationMatrix();
    for (double depth : {1e-6, 0.01, 0.1}) {
        const double got = penetrationDepth(cube, at({0, 0, 0}, ridgeAlongX), cube,
                                            at({0, 0, 2 * halfDiagonal - depth}, ridgeAlongY));
        CHECK(got == Approx(depth).epsilon(1e-9));
    }
    // Lifted 1 mm apart: every face axis still overlaps, the edge-edge axis shows the gap.
    CHECK(penetrationDepth(cube, at({0, 0, 0}, ridgeAlongX), cube, at({0, 0, 2 * halfDiagonal + 1e-3}, ridgeAlongY)) == 0.0);
}

TEST_CASE("penetration depth never exceeds the overlap along any direction") {
    Random random(7);
    const Polytope a = *makeIrregularSlab(random, 0.3, 0.1);
    const Polytope b = Polytope::box(Vec3(0.2, 0.1, 0.15));
    for (int trial = 0; trial < 50; ++trial) {
        const Mat3 rotation = Eigen::AngleAxisd(random.uniform(0, M_PI),
                                                Vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)).normalized())
                                  .toRotationMatrix();
        const Pose poseB = at({random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3)}, rotation);
        const double depth = penetrationDepth(a, Pose{}, b, poseB);
        REQUIRE(depth >= 0.0);
        for (int k = 0; k < 200; ++k) {
            const Vec3 axis = Vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)).normalized();
            double minA = 1e300, maxA = -1e300, minB = 1e300, maxB = -1e300;
            for (const Vec3& v : a.vertices()) {
                minA = std::min(minA, axis.dot(v));
                maxA = std::max(maxA, axis.dot(v));
            }
            for (const Vec3& v : b.vertices()) {
                minB = std::min(minB, axis.dot(poseB.apply(v)));
                maxB = std::max(maxB, axis.dot(poseB.apply(v)));
            }
            const double overlap = std::min(maxA - minB, maxB - minA);
            REQUIRE(depth <= std::max(overlap, 0.0) + 1e-12);
        }
    }
}

TEST_CASE("penetration into a half-space is the deepest vertex's distance below its boundary") {
    const Polytope cube = Polytope::box(Vec3::Constant(0.5));
    const HalfSpace ground{Vec3::UnitZ(), 0.0};
    CHECK(penetrationDepth(cube, at({0, 0, 0.5 - 1e-7}), ground) == Approx(1e-7).epsilon(1e-6));
    CHECK(penetrationDepth(cube, at({0, 0, 0.6}), ground) == 0.0);
    const Mat3 cornerDown = Eigen::AngleAxisd(0.3, Vec3(1, 2, 0).normalized()).toRotationMatrix();
    double lowest = 1e300;
    for (const Vec3& v : cube.vertices()) lowest = std::min(lowest, (cornerDown * v).z());
    CHECK(penetrationDepth(cube, at({3, -2, -lowest - 0.02}, cornerDown), ground) == Approx(0.02).epsilon(1e-9));
}

TEST_CASE("mass properties of a box match the closed form") {
    const Vec3 half(0.3, 0.2, 0.1);
    const MassProperties box = massProperties(Polytope::box(half));
    const double volume = 8 * half.prod();
    CHECK(box.volume == Approx(volume).epsilon(1e-12));
    CHECK(box.centroid.norm() == Approx(0.0).margin(1e-15));
    CHECK(box.inertiaAboutCentroid(0, 0) == Approx(volume * (half.y() * half.y() + half.z() * half.z()) / 3).epsilon(1e-12));
    CHECK(box.inertiaAboutCentroid(1, 1) == Approx(volume * (half.x() * half.x() + half.z() * half.z()) / 3).epsilon(1e-12));
    CHECK(box.inertiaAboutCentroid(2, 2) == Approx(volume * (half.x() * half.x() + half.y() * half.y()) / 3).epsilon(1e-12));
    CHECK(std::abs(box.inertiaAboutCentroid(0, 1)) < 1e-15);
}

TEST_CASE("mass properties of the corner tetrahedron match the closed form") {
    const Polytope tetra = Polytope::fromPoints({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
    const MassProperties p = massProperties(tetra);
    CHECK(p.volume == Approx(1.0 / 6).epsilon(1e-12));
    CHECK((p.centroid - Vec3::Constant(0.25)).norm() < 1e-14);
    // About the centroid: ∫x² dV = 1/160 and ∫xy dV = −1/480, so I_xx = 2/160, I_xy = +1/480.
    for (int i = 0; i < 3; ++i) {
        CHECK(p.inertiaAboutCentroid(i, i) == Approx(1.0 / 80).epsilon(1e-12));
        for (int j = 0; j < 3; ++j)
            if (i != j) CHECK(p.inertiaAboutCentroid(i, j) == Approx(1.0 / 480).epsilon(1e-12));
    }
}

TEST_CASE("the scenes' random numbers are fixed by their seed and stay in range") {
    Random first(42), second(42), other(43);
    bool differs = false;
    for (int i = 0; i < 1000; ++i) {
        const double value = first.uniform(-2.0, 3.0);
        REQUIRE(value == second.uniform(-2.0, 3.0));
        REQUIRE(value >= -2.0);
        REQUIRE(value < 3.0);
        differs = differs || value != other.uniform(-2.0, 3.0);
    }
    CHECK(differs);
}

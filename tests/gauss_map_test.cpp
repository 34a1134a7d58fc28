// Stage 2: Gauss-map feature selection with its angular tolerance and face > edge > vertex precedence.
#include "contact/gauss_map.hpp"
#include "geometry_oracles.hpp"

#include <algorithm>
#include <vector>

#include <catch2/catch.hpp>

using namespace gdc;
using namespace gdc::testing;
using gdc::detail::selectFeature;

TEST_CASE("a direction within the angular tolerance of a face normal selects that face") {
    const Polytope cube = Polytope::box(Vec3(0.5, 1, 2));
    const double tolerance = 0.05;
    for (double tilt : {0.0, 1e-12, 1e-6, 0.01, 0.049}) {
        Vec3 direction = rotationAbout(Vec3(1, 1, 0), tilt) * Vec3::UnitZ();
        Feature f = selectFeature(cube, direction, cube.supportVertex(direction), detail::AngularTolerance(tolerance));
        REQUIRE(f.type == FeatureType::Face);
        CHECK(cube.faces()[f.index].normal.z() == Approx(1));
    }
}

TEST_CASE("a direction near an edge's arc but beyond the face tolerance selects the edge") {
    const Polytope cube = Polytope::box(Vec3(0.5, 0.5, 0.5));
    // Halfway between +z and +x, tipped slightly towards y: on the arc of the edge x = z = 0.5.
    Vec3 direction = rotationAbout(Vec3::UnitX(), 0.02) * Vec3(1, 0, 1).normalized();
    Feature f = selectFeature(cube, direction, cube.supportVertex(direction), detail::AngularTolerance(0.05));
    REQUIRE(f.type == FeatureType::Edge);
    const auto& edge = cube.edges()[f.index];
    Vec3 midpoint = 0.5 * (cube.vertices()[edge.tail] + cube.vertices()[edge.head]);
    CHECK((midpoint - Vec3(0.5, 0, 0.5)).norm() < 1e-12);
}

TEST_CASE("a direction into a corner's region selects that vertex") {
    const Polytope cube = Polytope::box(Vec3(0.5, 0.5, 0.5));
    Feature f = selectFeature(cube, Vec3(1, 1, 1).normalized(), cube.supportVertex(Vec3(1, 1, 1).normalized()), detail::AngularTolerance(0.05));
    REQUIRE(f.type == FeatureType::Vertex);
    CHECK((cube.vertices()[f.index] - Vec3(0.5, 0.5, 0.5)).norm() < 1e-12);
}

TEST_CASE("a face wins over its edges and vertices when the tolerance reaches it") {
    const Polytope cube = Polytope::box(Vec3(0.5, 0.5, 0.5));
    // 30° from +z towards the corner: beyond a 0.05 rad tolerance a vertex, within 0.6 rad the face.
    Vec3 direction = rotationAbout(Vec3(1, -1, 0), 0.52) * Vec3::UnitZ();
    CHECK(selectFeature(cube, direction, cube.supportVertex(direction), detail::AngularTolerance(0.05)).type != FeatureType::Face);
    Feature wide = selectFeature(cube, direction, cube.supportVertex(direction), detail::AngularTolerance(0.6));
    REQUIRE(wide.type == FeatureType::Face);
    CHECK(cube.faces()[wide.index].normal.z() == Approx(1));
}

namespace {

// A box 2 × 1.2 × 0.8 whose +x side is bent outwards along y = 0 by `angle` (two faces `angle`
// apart, as the oracle's "faces 1e-9..1e-4 rad apart" family makes them): its top and bottom edges
// on that side are each two nearly collinear edges meeting at the bend.
Polytope bentBox(double angle) {
    const Vec3 h(1, 0.6, 0.4);
    std::vector<Vec3> points;
    for (double x : {-h.x(), h.x()})
        for (double y : {-h.y(), h.y()})
            for (double z : {-h.z(), h.z()}) points.emplace_back(x, y, z);
    for (double z : {-h.z(), h.z()}) points.emplace_back(h.x() + angle * h.y(), 0, z);
    return Polytope::fromPoints(points);
}

// The edges of the bent side's top: both end at the bend vertex (x > 1, y = 0, z = 0.4).
std::vector<int> bentTopEdges(const Polytope& p) {
    std::vector<int> out;
    for (int e = 0; e < static_cast<int>(p.edges().size()); ++e) {
        const Vec3& tail = p.vertices()[p.edges()[e].tail];
        const Vec3& head = p.vertices()[p.edges()[e].head];
        auto isBend = [](const Vec3& v) { return v.x() > 1 && std::abs(v.y()) < 1e-12 && v.z() > 0; };
        if (isBend(tail) || isBend(head))
            if (std::abs(tail.z() - head.z()) < 1e-12) out.push_back(e);
    }
    return out;
}

}  // namespace

// Issue 21: rounding picked one of two nearly collinear edges in collide(A, B) and the other in
// collide(B, A) (oracle seeds 40023674 and 40092705): two different edge–edge normals, or one
// order missing the deepest point. The chain holds both, whichever was selected.
TEST_CASE("an edge's chain holds the nearly collinear edges continuing it, whichever was selected") {
    const detail::AngularTolerance tolerance(0.05);
    for (double angle : {2e-6, 1e-5, 1e-4, 0.02}) {
        const Polytope box = bentBox(angle);
        const std::vector<int> top = bentTopEdges(box);
        REQUIRE(top.size() == 2);
        // Between the top (+z) and the bent side (+x), tipped a little along y either way.
        for (double tip : {-0.01, 0.0, 0.01}) {
            const Vec3 direction = (rotationAbout(Vec3::UnitX(), tip) * Vec3(1, 0, 1)).normalized();
            const Feature selected = selectFeature(box, direction, box.supportVertex(direction), tolerance);
            REQUIRE(selected.type == FeatureType::Edge);
            CHECK((selected.index == top[0] || selected.index == top[1]));
            for (int edge : top) {
                detail::SmallVector<int, 8> chain;
                detail::edgeChain(box, edge, direction, tolerance, chain);
                REQUIRE(chain.size() == 2);
                CHECK(std::min(chain[0], chain[1]) == std::min(top[0], top[1]));
                CHECK(std::max(chain[0], chain[1]) == std::max(top[0], top[1]));
            }
        }
    }
}

TEST_CASE("an edge's chain stops at a corner and beyond the angular tolerance") {
    const detail::AngularTolerance tolerance(0.05);
    // A box's edges meet at right angles: every chain is the edge alone.
    const Polytope cube = Polytope::box(Vec3(0.5, 0.5, 0.5));
    for (int e = 0; e < static_cast<int>(cube.edges().size()); ++e) {
        const Polytope::Edge& edge = cube.edges()[e];
        const Vec3 direction = (cube.faces()[edge.leftFace].normal + cube.faces()[edge.rightFace].normal).normalized();
        detail::SmallVector<int, 8> chain;
        detail::edgeChain(cube, e, direction, tolerance, chain);
        REQUIRE(chain.size() == 1);
        CHECK(chain[0] == e);
    }
    // Bent by 0.1 rad, beyond the tolerance: the two edges stay apart.
    const Polytope box = bentBox(0.1);
    const std::vector<int> top = bentTopEdges(box);
    REQUIRE(top.size() == 2);
    const Vec3 direction = Vec3(1, 0, 1).normalized();
    detail::SmallVector<int, 8> chain;
    detail::edgeChain(box, top[0], direction, tolerance, chain);
    CHECK(chain.size() == 1);
}

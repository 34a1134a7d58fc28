// Stage 2: Gauss-map feature selection with its angular tolerance and face > edge > vertex precedence.
#include "gauss_map.hpp"
#include "geometry_oracles.hpp"

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

// Shapes from OBJ files (samples/scenes/obj_shape): against hulls, volumes and centres worked out
// by hand, and every kind of bad file refused with a message that says what is wrong.
#include "obj_shape.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

using namespace gdc;
using namespace gdc::scenes;

namespace {

// A cube of side 2 centred at (1, 2, 3), as six quads.
const char* const kCube = R"(# cube
o cube
v 0 1 2
v 2 1 2
v 2 3 2
v 0 3 2
v 0 1 4
v 2 1 4
v 2 3 4
v 0 3 4
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

// Two unit-corner tetrahedra (volume 1/6 each), one at the origin and one 3 m along x.
const char* const kTwoTetrahedra = R"(o first
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
o second
v 3 0 0
v 4 0 0
v 3 1 0
v 3 0 1
f 5 7 6
f 5 6 8
f 5 8 7
f 6 7 8
)";

/// Where each vertex of a part lies in the parts' common frame.
std::vector<Vec3> placedVertices(const PlacedPart& part) {
    std::vector<Vec3> points;
    for (const Vec3& v : part.shape->vertices()) points.push_back(part.offset.apply(v));
    return points;
}

/// The message of the ObjError that parsing `text` throws ("" when none is thrown).
std::string errorOf(const std::string& text, ObjLayout layout = ObjLayout::PartPerObject) {
    try {
        parseObjShape(text, layout, 1.0, "test.obj");
    } catch (const ObjError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("a cube OBJ gives the 8-vertex hull with the cube's volume and extent, centred on its centre") {
    for (ObjLayout layout : {ObjLayout::Hull, ObjLayout::PartPerObject}) {
        const ObjShape shape = parseObjShape(kCube, layout);
        REQUIRE(shape.parts.size() == 1);
        const PlacedPart& part = shape.parts[0];
        CHECK(part.shape->vertices().size() == 8);
        CHECK(part.shape->faces().size() == 6);  // qhull's triangles merged back into the quads
        CHECK(part.shape->volume() == Approx(8.0).epsilon(1e-12));
        CHECK(shape.volume == Approx(8.0).epsilon(1e-12));
        CHECK(shape.radius == Approx(std::sqrt(3.0)).epsilon(1e-12));
        // The frame's origin is the cube's centre: every corner at (±1, ±1, ±1).
        for (const Vec3& corner : placedVertices(part))
            CHECK((corner.cwiseAbs() - Vec3::Ones()).cwiseAbs().maxCoeff() < 1e-12);
        CHECK(shape.partNames[0] == (layout == ObjLayout::Hull ? "hull" : "object 'cube'"));
    }
}

TEST_CASE("the scale multiplies every coordinate: volume by its cube") {
    const ObjShape shape = parseObjShape(kCube, ObjLayout::Hull, 0.5);
    CHECK(shape.volume == Approx(1.0).epsilon(1e-12));
    CHECK(shape.radius == Approx(0.5 * std::sqrt(3.0)).epsilon(1e-12));
}

TEST_CASE("a two-object OBJ gives a two-part composite whose parts are the objects' hulls") {
    const ObjShape shape = parseObjShape(kTwoTetrahedra, ObjLayout::PartPerObject);
    REQUIRE(shape.parts.size() == 2);
    CHECK(shape.partNames == std::vector<std::string>{"object 'first'", "object 'second'"});
    // Equal volumes: the common centre is halfway between the two centroids, (0.25,0.25,0.25) and
    // (3.25,0.25,0.25), i.e. (1.75, 0.25, 0.25) in the file.
    const Vec3 centre(1.75, 0.25, 0.25);
    const std::vector<Vec3> expected[2] = {
        {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
        {Vec3(3, 0, 0), Vec3(4, 0, 0), Vec3(3, 1, 0), Vec3(3, 0, 1)}};
    for (int k = 0; k < 2; ++k) {
        INFO("part " << k);
        CHECK(shape.parts[k].shape->volume() == Approx(1.0 / 6.0).epsilon(1e-12));
        const std::vector<Vec3> placed = placedVertices(shape.parts[k]);
        REQUIRE(placed.size() == 4);
        for (const Vec3& corner : expected[k]) {
            const bool found = std::any_of(placed.begin(), placed.end(),
                                           [&](const Vec3& v) { return (v - (corner - centre)).norm() < 1e-12; });
            CHECK(found);
        }
    }
    // As one hull instead: all eight points, one part.
    const ObjShape hull = parseObjShape(kTwoTetrahedra, ObjLayout::Hull);
    REQUIRE(hull.parts.size() == 1);
    CHECK(hull.volume > 2.0 / 6.0);
}

TEST_CASE("the sample maul OBJ loads as its handle and head, of the volumes its comments give") {
    const std::string path = std::string(GDCONTACT_SOURCE_DIR) + "/samples/viewer/assets/maul.obj";
    const ObjShape shape = loadObjShape(path, ObjLayout::PartPerObject);
    REQUIRE(shape.parts.size() == 2);
    CHECK(shape.partNames == std::vector<std::string>{"object 'handle'", "object 'head'"});
    CHECK(shape.parts[0].shape->vertices().size() == 8);
    CHECK(shape.parts[0].shape->volume() == Approx(0.03 * 0.03 * 0.3).epsilon(1e-9));
    CHECK(shape.parts[1].shape->vertices().size() == 6);
    CHECK(shape.parts[1].shape->volume() == Approx(0.16 * 0.08 / 2 * 0.06).epsilon(1e-9));
    // Each part is made about its own centroid (ODE wants a dConvex's origin inside it) ...
    for (const PlacedPart& part : shape.parts) CHECK(part.shape->centroid().norm() < 1e-12);
    // ... and the origin of their frame is the common centre of mass: the volume-weighted part
    // centroids cancel.
    Vec3 moment = Vec3::Zero();
    for (const PlacedPart& part : shape.parts) moment += part.shape->volume() * part.offset.apply(part.shape->centroid());
    CHECK(moment.norm() < 1e-15);
}

TEST_CASE("bad OBJ files are refused with a message naming the file and the fault") {
    CHECK_THAT(errorOf(""), Catch::Contains("test.obj") && Catch::Contains("no vertices"));
    CHECK_THAT(errorOf("this is not an OBJ file\n"), Catch::Contains("no vertices"));
    CHECK_THAT(errorOf("v 1 2\nv 0 0 0\n"), Catch::Contains("line 1") && Catch::Contains("three finite numbers"));
    CHECK_THAT(errorOf("v 0 0 0\nv a b c\n"), Catch::Contains("line 2") && Catch::Contains("'v a b c'"));
    CHECK_THAT(errorOf("v nan 0 0\n", ObjLayout::Hull), Catch::Contains("three finite numbers"));
    CHECK_THAT(errorOf("v 1e999 0 0\n", ObjLayout::Hull), Catch::Contains("three finite numbers"));
    // A face that refers to vertices the file does not have.
    CHECK_THAT(errorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 9\n"), Catch::Contains("refers to vertex 9"));
    CHECK_THAT(errorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"), Catch::Contains("not a readable OBJ file"));
    // Vertices only: no objects to make parts of (as one hull it is fine, see below).
    CHECK_THAT(errorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"), Catch::Contains("no faces"));
    CHECK(parseObjShape("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n", ObjLayout::Hull).volume == Approx(1.0 / 6.0));
}

TEST_CASE("an object with no volume is refused, naming it") {
    // A flat square: four coplanar points have no 3-D hull.
    const std::string flat = "o floor\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    CHECK_THAT(errorOf(flat), Catch::Contains("object 'floor'") && Catch::Contains("cannot be a convex part") &&
                                  Catch::Contains("coplanar"));
    CHECK_THAT(errorOf(flat, ObjLayout::Hull), Catch::Contains("hull cannot be a convex part"));
    // A single triangle: too few points.
    CHECK_THAT(errorOf("o sliver\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
               Catch::Contains("object 'sliver'") && Catch::Contains("at least 4 points"));
    // A good object next to a flat one still fails, and says which.
    CHECK_THAT(errorOf(std::string(kCube) + flat), Catch::Contains("object 'floor'"));
}

TEST_CASE("a missing file is refused with the reason") {
    try {
        loadObjShape("no/such/file.obj", ObjLayout::Hull);
        FAIL("no error for a missing file");
    } catch (const ObjError& e) {
        CHECK_THAT(std::string(e.what()), Catch::Contains("no/such/file.obj") && Catch::Contains("cannot open"));
    }
}

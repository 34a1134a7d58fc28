// Dropping, throwing, inspecting and debug drawing (samples/viewer/interaction): the maths on its
// own, then as a person uses it in a real window (Xvfb + Mesa llvmpipe, started by the test), alone
// and side by side (both worlds get the added body; each view draws its own debug overlay).
#include "interaction.hpp"
#include "image.hpp"
#include "ode_precision.hpp"  // values read back through dReal
#include "ode_session.hpp"
#include "viewer.hpp"
#include "viewer_test_support.hpp"
#include "x_server.hpp"

#include <catch2/catch.hpp>
#include <ode/ode.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

using namespace gdc;
using namespace gdc::viewer;
using gdc::viewer::test::positionOf;
using gdc::viewer::test::testOptions;

namespace {

// A value read back from ODE (a body's position or velocity), of magnitude up to `scale`: within
// 1e-9 in a double-precision ODE, within 64 float ulps of `scale` where dReal is float.
double throughReal(double scale) {
    return gdc::ode::test::kOdeIsDouble ? 1e-9 : gdc::ode::test::realTolerance(1e-9) * scale;
}

using gdc::testing::OdeSession;

const std::string kMaul = std::string(GDCONTACT_SOURCE_DIR) + "/samples/viewer/assets/maul.obj";

Vec3 velocityOf(dBodyID body) {
    const dReal* v = dBodyGetLinearVel(body);
    return Vec3(v[0], v[1], v[2]);
}

const scenes::Body& bodyOf(Viewer& viewer, dBodyID id) {
    for (const auto& body : viewer.scene().bodies())
        if (body.body == id) return body;
    FAIL("no such body in the scene");
    throw;
}

/// A point on the ground z = 0, beside the scene's bodies (along the camera's right, so it is
/// in view), and the pixel that shows it.
Vec3 groundBeside(Viewer& viewer, double offset, Eigen::Vector2d& pixel) {
    const OrbitCamera& camera = viewer.camera();
    const Vec3 forward = camera.target() - camera.eye();
    const Vec3 right = forward.cross(Vec3::UnitZ()).normalized();
    Vec3 ground = camera.target() + offset * right;
    ground.z() = 0.0;
    pixel = camera.project(ground, viewer.windowWidth(), viewer.windowHeight());
    return ground;
}

/// Pixels of the bounding-box cyan (0.1, 0.95, 0.95) and nothing else in the frame.
long cyanPixels(const Image& image) {
    long count = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const std::uint8_t* p = image.pixel(x, y);
            count += p[0] < 60 && p[1] > 220 && p[2] > 220;
        }
    return count;
}

}  // namespace

// ---- the maths, without a window -------------------------------------------------------------

TEST_CASE("a flick's velocity is the cursor's motion over its last moments") {
    FlickTracker flick;
    CHECK_FALSE(flick.active());
    flick.window = 0.125;  // and times that binary fractions hold exactly
    flick.begin(0, 0, 0.0);
    CHECK(flick.velocity() == Eigen::Vector2d::Zero());  // one sample: no motion yet
    flick.move(10, 0, 0.125);
    CHECK(flick.velocity().x() == Approx(80.0));
    flick.move(30, -20, 0.25);
    flick.move(60, -40, 0.375);
    // Only the last 0.125 s counts: from the sample at 0.25 s, (60 − 30, −40 + 20) px over 0.125 s.
    CHECK(flick.velocity().x() == Approx(240.0));
    CHECK(flick.velocity().y() == Approx(-160.0));
    flick.end();
    CHECK_FALSE(flick.active());
}

TEST_CASE("a flick's speed is the cursor's speed carried to the target's distance") {
    OrbitCamera camera(Vec3::UnitZ());
    camera.frame(Vec3(-1, -1, 0), Vec3(1, 1, 1));
    const int width = 640, height = 480;
    // One metre across the view at the target's distance, as the camera projects it.
    const Vec3 forward = (camera.target() - camera.eye()).normalized();
    const Vec3 right = forward.cross(camera.up()).normalized();
    const double pixelsPerMetre = (camera.project(camera.target() + right, width, height) -
                                   camera.project(camera.target(), width, height)).norm();
    CHECK(flickSpeed(camera, height, Eigen::Vector2d(pixelsPerMetre, 0.0)) == Approx(1.0).epsilon(1e-9));
    CHECK(flickSpeed(camera, height, Eigen::Vector2d(0.0, -3.0 * pixelsPerMetre)) == Approx(3.0).epsilon(1e-9));
}

TEST_CASE("a throw starts on the cursor ray in front of the eye and moves along it") {
    const Ray ray{Vec3(1, 2, 3), Vec3(1, -2, -2).normalized()};
    const Launch launch = launchAlong(ray, 0.25, 12.0);
    CHECK((launch.position - ray.at(0.5)).norm() < 1e-12);
    CHECK((launch.velocity - 12.0 * ray.direction).norm() < 1e-12);
}

TEST_CASE("the shapes to add are centred on their centre of mass and as large as asked") {
    const SpawnShape box = makeSpawnBox(0.5);
    CHECK(box.radius == Approx(0.5).epsilon(1e-12));
    REQUIRE(box.parts.size() == 1);
    CHECK(box.parts[0].isBox);
    const SpawnShape rock = makeSpawnRock(0.5, 7);
    CHECK(rock.radius <= 0.5 * 2.0);  // points within 0.5 of the origin, recentred on the hull's centroid
    CHECK(rock.parts[0].shape->vertices().size() >= 4);
    // The same seed gives the same rock, another seed another one.
    CHECK(makeSpawnRock(0.5, 7).parts[0].shape->vertices() == rock.parts[0].shape->vertices());
    CHECK(makeSpawnRock(0.5, 8).parts[0].shape->vertices() != rock.parts[0].shape->vertices());
    const SpawnShape composite = makeSpawnComposite(0.5);
    CHECK(composite.parts.size() == 2);
    for (const SpawnShape* shape : {&box, &rock, &composite}) {
        INFO(shape->name);
        Vec3 moment = Vec3::Zero();
        for (const auto& part : shape->parts) moment += part.shape->volume() * part.offset.apply(part.shape->centroid());
        CHECK(moment.norm() < 1e-12);
    }
}

TEST_CASE("the contact under the cursor is the one drawn nearest it, within the given pixels") {
    OdeSession ode;
    auto scene = scenes::makeScene("box_drop");
    scene->runUntil(2.5);  // the box rests on the ground: its corners touch
    const auto& contacts = scene->lastContacts();
    REQUIRE(contacts.size() >= 3);
    OrbitCamera camera(Vec3::UnitZ());
    camera.frame(Vec3(-0.5, -0.5, 0.0), Vec3(0.5, 0.5, 0.5));
    const int width = 640, height = 480;
    for (const scenes::ContactSample& contact : contacts) {
        const Eigen::Vector2d pixel = camera.project(contact.position, width, height);
        const auto found = contactNearPixel(*scene, camera, pixel.x() + 2.0, pixel.y() - 1.0, width, height, 10.0);
        REQUIRE(found);
        // This contact or one drawn at least as near the cursor.
        const double foundDistance = (camera.project(found->position, width, height) - pixel - Eigen::Vector2d(2, -1)).norm();
        CHECK(foundDistance <= std::sqrt(5.0) + 1e-9);
    }
    // Far from every contact: none.
    CHECK_FALSE(contactNearPixel(*scene, camera, 1.0, 1.0, width, height, 10.0));
}

// ---- in a window ------------------------------------------------------------------------------

TEST_CASE("dropping a box at the cursor adds one body over the ground point under it") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    Viewer viewer(testOptions("box_drop"));
    viewer.simulate(0.1);
    const std::size_t count = viewer.scene().bodies().size();
    Eigen::Vector2d pixel;
    const Vec3 ground = groundBeside(viewer, 1.2, pixel);
    REQUIRE(pixel.x() > 0);
    REQUIRE(pixel.x() < viewer.windowWidth());

    viewer.interaction().kind = SpawnKind::Box;
    const dBodyID dropped = viewer.dropAt(pixel.x(), pixel.y());
    REQUIRE(dropped != nullptr);
    CHECK(viewer.scene().bodies().size() == count + 1);
    const scenes::Body& body = bodyOf(viewer, dropped);
    CHECK(body.removable);
    CHECK_FALSE(body.measured);
    // Over the point under the cursor (the ground there is clear), its bounding sphere 5 % of its
    // radius above the ground.
    const Vec3 at = positionOf(dropped);
    INFO("dropped at " << at.transpose() << ", ground point " << ground.transpose());
    CHECK((at.head<2>() - ground.head<2>()).norm() < 1e-6);
    CHECK(at.z() == Approx(1.05 * body.radius).epsilon(gdc::ode::test::realTolerance(1e-9)));  // read through dReal
    CHECK(velocityOf(dropped).norm() == 0.0);

    // It falls and comes to rest on the ground, by the scene's own contacts.
    viewer.simulate(1.5);
    const Vec3 rest = positionOf(dropped);
    CHECK(rest.z() < at.z());
    CHECK(rest.z() > 0.0);
    CHECK(velocityOf(dropped).norm() < 0.05);
}

TEST_CASE("dropping onto a body puts the new one above it, and on the sky adds nothing") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    Viewer viewer(testOptions("box_drop"));
    viewer.simulate(2.0);  // the box lies on the ground
    const dBodyID box = viewer.scene().bodies().front().body;
    const Eigen::Vector2d pixel = viewer.camera().project(positionOf(box), viewer.windowWidth(), viewer.windowHeight());
    double top = -1e9;  // the box's highest vertex
    for (const auto& part : viewer.scene().bodies().front().parts)
        for (const Vec3& v : part.shape->vertices()) top = std::max(top, scenes::worldHeight(part, v));
    const dBodyID dropped = viewer.dropAt(pixel.x(), pixel.y());
    REQUIRE(dropped != nullptr);
    CHECK(positionOf(dropped).z() - bodyOf(viewer, dropped).radius > top);

    // The top row looks along the horizon: ground far out of sight, where nothing is dropped.
    const std::size_t count = viewer.scene().bodies().size();
    CHECK(viewer.dropAt(0.5 * viewer.windowWidth(), 0.5) == nullptr);
    // Looking up, the top row shows the sky: nothing to drop onto.
    viewer.camera().orbit(0.0, -0.3);
    CHECK(viewer.dropAt(0.5 * viewer.windowWidth(), 0.5) == nullptr);
    CHECK(viewer.scene().bodies().size() == count);
}

TEST_CASE("a thrown body leaves the camera along the cursor ray at the throw speed") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    Viewer viewer(testOptions("brick_wall"));
    const double x = 0.6 * viewer.windowWidth(), y = 0.4 * viewer.windowHeight();
    const Ray ray = viewer.camera().rayThroughPixel(x, y, viewer.windowWidth(), viewer.windowHeight());
    for (SpawnKind kind : {SpawnKind::Box, SpawnKind::Rock, SpawnKind::Composite}) {
        SECTION(spawnKindName(kind)) {
            viewer.interaction().kind = kind;
            const std::size_t count = viewer.scene().bodies().size();
            const dBodyID thrown = viewer.throwAt(x, y, 9.0);
            REQUIRE(thrown != nullptr);
            CHECK(viewer.scene().bodies().size() == count + 1);
            const Vec3 start = positionOf(thrown);
            const double along = (start - ray.origin).norm();
            CHECK((start - ray.origin).cross(ray.direction).norm() < throughReal(1.0 + along));  // on the ray
            CHECK((start - ray.origin).dot(ray.direction) > 0.0);           // in front of the eye
            CHECK((velocityOf(thrown) - 9.0 * ray.direction).norm() < throughReal(9.0));
            // One step later gravity has bent it by g·dt at most.
            viewer.simulate(0.01);
            CHECK((velocityOf(thrown) - 9.0 * ray.direction).norm() < 9.81 * 0.01 + 1e-9);
        }
    }
}

TEST_CASE("bodies added to a scene collide by the scene's contact method") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    for (scenes::Method method : {scenes::Method::Gdcontact, scenes::Method::Tracking, scenes::Method::Ode}) {
        SECTION(scenes::methodName(method)) {
            ViewerOptions options = testOptions("box_drop");
            options.method = method;
            Viewer viewer(options);
            Eigen::Vector2d pixel;
            groundBeside(viewer, 1.2, pixel);
            viewer.interaction().kind = SpawnKind::Rock;
            const dBodyID rock = viewer.dropAt(pixel.x(), pixel.y());
            REQUIRE(rock != nullptr);
            viewer.simulate(2.0);
            const auto inspection = inspectBody(viewer.scene(), rock);
            REQUIRE(inspection);
            INFO("rock at " << inspection->position.transpose());
            CHECK(inspection->position.z() > 0.0);  // held up by the ground's contacts
            CHECK(inspection->linearVelocity.norm() < 0.05);
            CHECK_FALSE(inspection->contacts.empty());
        }
    }
}

TEST_CASE("the inspector shows the body under the cursor with its mass and its contacts") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    Viewer viewer(testOptions("box_drop"));
    Eigen::Vector2d pixel;
    groundBeside(viewer, 1.2, pixel);
    viewer.interaction().kind = SpawnKind::Box;
    viewer.interaction().density = 700.0;
    const dBodyID box = viewer.dropAt(pixel.x(), pixel.y());
    REQUIRE(box != nullptr);
    viewer.simulate(1.5);

    const Eigen::Vector2d centre = viewer.camera().project(positionOf(box), viewer.windowWidth(), viewer.windowHeight());
    const auto inspection = viewer.inspectAt(centre.x(), centre.y());
    REQUIRE(inspection);
    CHECK(inspection->body == box);
    // 700 kg/m³ times the box's volume, from its half extents.
    const Vec3 half = bodyOf(viewer, box).parts.front().shape->boxHalfExtents();
    CHECK(inspection->mass == Approx(700.0 * 8.0 * half.prod()).epsilon(1e-9));
    REQUIRE_FALSE(inspection->contacts.empty());
    for (const InspectedContact& contact : inspection->contacts) {
        CHECK(contact.depth >= 0.0);
        CHECK(contact.normal.norm() == Approx(1.0).epsilon(1e-9));
        CHECK(contact.normal.z() > 0.99);  // the ground pushes it up
        CHECK(contact.other == "static");
    }
    CHECK_FALSE(viewer.inspectAt(1.0, 1.0));  // the far ground: static geometry, no body
}

TEST_CASE("wireframe shows the ground through the bodies, bounds draws each part's box") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    ViewerOptions options = testOptions("brick_wall");
    options.contacts = false;  // coloured pixels are then the bodies' alone
    Viewer viewer(options);
    viewer.simulate(0.1);
    auto frame = [&] {
        viewer.draw();
        return viewer.capture();
    };
    const Image solid = frame();
    viewer.interaction().debug.wireframe = true;
    const Image wire = frame();
    viewer.interaction().debug.wireframe = false;
    viewer.interaction().debug.bounds = true;
    const Image boxes = frame();
    writePng(solid, std::string(GDCONTACT_VIEWER_TEST_OUTPUT) + "/debug_solid.png");
    writePng(wire, std::string(GDCONTACT_VIEWER_TEST_OUTPUT) + "/debug_wireframe.png");
    writePng(boxes, std::string(GDCONTACT_VIEWER_TEST_OUTPUT) + "/debug_bounds.png");
    const long solidColoured = statistics(solid).colouredPixels, wireColoured = statistics(wire).colouredPixels;
    INFO("coloured pixels: solid " << solidColoured << ", wireframe " << wireColoured);
    CHECK(wireColoured > 0);
    CHECK(wireColoured < solidColoured / 2);  // edges only: the faces' pixels show the ground now
    CHECK(cyanPixels(solid) == 0);
    CHECK(cyanPixels(boxes) > 100);
}

TEST_CASE("the viewer loads an OBJ file given on the command line, and refuses a bad one") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    const std::string viewer = std::string("\"") + GDCONTACT_VIEWER_EXECUTABLE + "\"";
    CHECK(std::system((viewer + " --scene box_drop --obj \"" + kMaul + "\" --frames 2 --size 320x200 --hidden > /dev/null").c_str()) == 0);

    const std::string bad = std::string(GDCONTACT_VIEWER_TEST_OUTPUT) + "/bad.obj";
    const std::string log = std::string(GDCONTACT_VIEWER_TEST_OUTPUT) + "/bad_obj.log";
    std::ofstream(bad) << "o broken\nv 0 0\nv 1 0 0\n";
    CHECK(std::system((viewer + " --obj \"" + bad + "\" --frames 1 --hidden > /dev/null 2> \"" + log + "\"").c_str()) != 0);
    std::stringstream message;
    message << std::ifstream(log).rdbuf();
    CHECK_THAT(message.str(), Catch::Contains("bad.obj: line 2") && Catch::Contains("three finite numbers"));
}

TEST_CASE("an OBJ composite dropped into a scene is one body of the file's parts") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    Viewer viewer(testOptions("composites"));
    REQUIRE(viewer.interaction().loadObj(kMaul, scenes::ObjLayout::PartPerObject, 2.0));
    CHECK(viewer.interaction().kind == SpawnKind::Obj);
    // A bad file later keeps the loaded shape and says why.
    CHECK_FALSE(viewer.interaction().loadObj("no/such.obj", scenes::ObjLayout::Hull, 1.0));
    CHECK_THAT(viewer.interaction().objStatus(), Catch::Contains("cannot open"));
    CHECK(viewer.interaction().kind == SpawnKind::Obj);

    Eigen::Vector2d pixel;
    groundBeside(viewer, 0.0, pixel);
    const dBodyID maul = viewer.dropAt(pixel.x(), pixel.y());
    REQUIRE(maul != nullptr);
    const scenes::Body& body = bodyOf(viewer, maul);
    CHECK(body.parts.size() == 2);
    // Scaled by 2: volumes × 8, mass at 1000 kg/m³.
    dMass mass;
    dBodyGetMass(maul, &mass);
    CHECK(mass.mass == Approx(1000.0 * 8.0 * (2.7e-4 + 3.84e-4)).epsilon(gdc::ode::test::realTolerance(1e-9)));
    viewer.simulate(0.5);
    viewer.draw();
    CHECK(statistics(viewer.capture()).colouredPixels > 0);
}

TEST_CASE("a cylinder stands and a capsule lies, each a real curved part reaching as far as asked") {
    const SpawnShape cylinder = makeSpawnCylinder(0.5);
    REQUIRE(cylinder.parts.size() == 1);
    const scenes::PlacedPart& can = cylinder.parts[0];
    CHECK(can.round == scenes::RoundKind::Cylinder);
    CHECK(can.roundRadius == Approx(0.3));
    CHECK(can.roundLength == Approx(0.8));
    CHECK(can.offset.position.norm() < 1e-12);
    CHECK((can.offset.rotation * Vec3::UnitZ() - Vec3::UnitZ()).norm() < 1e-12);  // standing
    CHECK(cylinder.radius == Approx(0.5).epsilon(1e-12));  // the rim, which the prism's vertices lie on

    const SpawnShape capsule = makeSpawnCapsule(0.5);
    REQUIRE(capsule.parts.size() == 1);
    const scenes::PlacedPart& pill = capsule.parts[0];
    CHECK(pill.round == scenes::RoundKind::Capsule);
    CHECK(pill.roundRadius == Approx(0.2));
    CHECK(pill.roundLength == Approx(0.6));
    CHECK(pill.offset.position.norm() < 1e-12);
    CHECK(std::abs((pill.offset.rotation * Vec3::UnitZ()).z()) < 1e-12);  // lying
    CHECK(capsule.radius == Approx(0.5).epsilon(1e-12));  // the poles
    // The exact mass properties, not the tessellation's: π r² h and π r² (L + 4r/3).
    CHECK(scenes::massProperties(can).volume ==
          Approx(scenes::kPi * 0.09 * 0.8).epsilon(gdc::ode::test::realTolerance(1e-12)));
    CHECK(scenes::massProperties(pill).volume ==
          Approx(scenes::kPi * 0.04 * (0.6 + 4.0 * 0.2 / 3.0)).epsilon(gdc::ode::test::realTolerance(1e-12)));
}

// ---- side by side -----------------------------------------------------------------------------

namespace {

/// The pixel (window coordinates) of view `view` that shows world point `p`.
Eigen::Vector2d pixelInView(Viewer& viewer, int view, const Vec3& p) {
    const Viewport port = viewer.viewport(view);
    return viewer.camera().project(p, port.width, port.height) + Eigen::Vector2d(port.x, port.y);
}

const scenes::Body* bodyNamed(Viewer& viewer, int view, const std::string& name) {
    for (const auto& body : viewer.scene(view).bodies())
        if (body.name == name) return &body;
    return nullptr;
}

/// Index of `body` in the bodies of world `view`, or -1.
long indexOf(Viewer& viewer, int view, dBodyID body) {
    const auto& bodies = viewer.scene(view).bodies();
    for (std::size_t i = 0; i < bodies.size(); ++i)
        if (bodies[i].body == body) return long(i);
    return -1;
}

Image crop(const Image& image, const Viewport& port) {
    Image out;
    out.width = port.width;
    out.height = port.height;
    for (int y = port.y; y < port.y + port.height; ++y)
        out.rgb.insert(out.rgb.end(), image.pixel(port.x, y), image.pixel(port.x, y) + 3 * std::size_t(port.width));
    return out;
}

}  // namespace

TEST_CASE("side by side: a dropped or thrown body goes into both worlds alike, and ctrl-click removes it from both") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    ViewerOptions options = testOptions("box_drop");
    options.width = 640;
    options.sideBySide = true;  // gdcontact left, ODE's native colliders right
    Viewer viewer(options);
    REQUIRE(viewer.viewCount() == 2);
    viewer.simulate(0.1);
    const std::size_t count = viewer.scene(0).bodies().size();
    REQUIRE(viewer.scene(1).bodies().size() == count);
    // A ground point beside the falling box, as each view shows it.
    const OrbitCamera& camera = viewer.camera();
    const Vec3 right = (camera.target() - camera.eye()).cross(Vec3::UnitZ()).normalized();
    Vec3 ground = camera.target() + 0.8 * right;
    ground.z() = 0.0;

    for (int view : {0, 1}) {
        SECTION(view == 0 ? "dropped in the left view" : "dropped in the right view") {
            viewer.interaction().kind = SpawnKind::Rock;  // each rock differs: both worlds must get this one
            const Eigen::Vector2d pixel = pixelInView(viewer, view, ground);
            const dBodyID dropped = viewer.dropAt(pixel.x(), pixel.y());
            REQUIRE(dropped != nullptr);
            REQUIRE(viewer.scene(0).bodies().size() == count + 1);
            REQUIRE(viewer.scene(1).bodies().size() == count + 1);
            // The body returned is the pointed-at view's; the other world's twin is at the same
            // index, with the same name (how the viewer pairs bodies), pose, velocity and shape.
            CHECK(indexOf(viewer, view, dropped) == long(count));
            const scenes::Body& a = viewer.scene(0).bodies().back();
            const scenes::Body& b = viewer.scene(1).bodies().back();
            CHECK(a.name == b.name);
            CHECK(a.removable);
            CHECK(b.removable);
            CHECK_FALSE(b.measured);
            CHECK((positionOf(a.body) - positionOf(b.body)).norm() == 0.0);
            CHECK((positionOf(a.body).head<2>() - ground.head<2>()).norm() < 1e-6);
            CHECK(velocityOf(b.body).norm() == 0.0);
            REQUIRE(a.parts.size() == b.parts.size());
            CHECK(a.parts.front().shape->vertices() == b.parts.front().shape->vertices());
            dMass massA, massB;
            dBodyGetMass(a.body, &massA);
            dBodyGetMass(b.body, &massB);
            CHECK(massA.mass == massB.mass);

            // Each world's contacts land it; it rests on the ground in both.
            viewer.simulate(1.5);
            for (dBodyID body : {a.body, b.body}) {
                CHECK(positionOf(body).z() > 0.0);
                CHECK(velocityOf(body).norm() < 0.05);
            }
            // A drag of it reaches its twin.
            const std::string name = a.name;
            const Eigen::Vector2d on = pixelInView(viewer, 1 - view, positionOf(viewer.scene(1 - view).bodies().back().body));
            REQUIRE(viewer.grab(on.x(), on.y()));
            CHECK(viewer.drag(0).body() == a.body);
            CHECK(viewer.drag(1).body() == b.body);
            viewer.release();
            // ctrl-click on it in either view removes it from both worlds, and nothing else.
            REQUIRE(viewer.removeAt(on.x(), on.y()));
            CHECK(viewer.scene(0).bodies().size() == count);
            CHECK(viewer.scene(1).bodies().size() == count);
            CHECK(bodyNamed(viewer, 0, name) == nullptr);
            CHECK(bodyNamed(viewer, 1, name) == nullptr);
        }
    }
    SECTION("thrown from the right view") {
        viewer.interaction().kind = SpawnKind::Composite;
        const Viewport port = viewer.viewport(1);
        const double x = port.x + 0.6 * port.width, y = port.y + 0.4 * port.height;
        const Ray ray = viewer.camera().rayThroughPixel(x - port.x, y - port.y, port.width, port.height);
        const dBodyID thrown = viewer.throwAt(x, y, 7.0);
        REQUIRE(thrown != nullptr);
        CHECK(indexOf(viewer, 1, thrown) == long(count));
        const scenes::Body& a = viewer.scene(0).bodies().back();
        const scenes::Body& b = viewer.scene(1).bodies().back();
        CHECK(a.name == b.name);
        CHECK(a.parts.size() == 2);
        CHECK((positionOf(a.body) - positionOf(b.body)).norm() == 0.0);
        CHECK((positionOf(b.body) - ray.origin).cross(ray.direction).norm() <
              throughReal(1.0 + (positionOf(b.body) - ray.origin).norm()));  // on the right view's ray
        CHECK((velocityOf(a.body) - 7.0 * ray.direction).norm() < throughReal(7.0));
        CHECK((velocityOf(b.body) - 7.0 * ray.direction).norm() < throughReal(7.0));
    }
    SECTION("reset and the side-by-side toggle rebuild both worlds without the added body") {
        const Eigen::Vector2d pixel = pixelInView(viewer, 0, ground);
        REQUIRE(viewer.dropAt(pixel.x(), pixel.y()) != nullptr);
        viewer.resetScene();
        CHECK(viewer.scene(0).bodies().size() == count);
        CHECK(viewer.scene(1).bodies().size() == count);
        REQUIRE(viewer.dropAt(pixel.x(), pixel.y()) != nullptr);
        viewer.setSideBySide(false);
        viewer.setSideBySide(true);
        CHECK(viewer.scene(0).bodies().size() == count);
        CHECK(viewer.scene(1).bodies().size() == count);
    }
    // The panel's column is no view: nothing is added from there.
    CHECK(viewer.dropAt(-1.0, 10.0) == nullptr);
}

TEST_CASE("side by side: wireframe and bounding boxes are drawn in each view, with that view's world") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    ViewerOptions options = testOptions("brick_wall");
    options.width = 640;
    options.sideBySide = true;
    options.contacts = false;  // coloured pixels are then the bodies' alone
    options.labels = false;
    Viewer viewer(options);
    REQUIRE(viewer.viewCount() == 2);
    viewer.simulate(0.1);
    // A box dropped beside the wall, into both worlds.
    const OrbitCamera& camera = viewer.camera();
    const Vec3 right = (camera.target() - camera.eye()).cross(Vec3::UnitZ()).normalized();
    Vec3 ground = camera.target() + 0.4 * right;
    ground.z() = 0.0;
    viewer.interaction().kind = SpawnKind::Box;
    const Eigen::Vector2d pixel = pixelInView(viewer, 0, ground);
    REQUIRE(viewer.dropAt(pixel.x(), pixel.y()) != nullptr);
    viewer.simulate(0.3);

    auto frame = [&] {
        viewer.draw();
        return viewer.capture();
    };
    const Image solid = frame();
    viewer.interaction().debug.wireframe = true;
    const Image wire = frame();
    viewer.interaction().debug.bounds = true;
    const Image both = frame();
    viewer.interaction().debug.wireframe = false;
    const Image boxes = frame();
    writePng(both, std::string(GDCONTACT_VIEWER_TEST_OUTPUT) + "/side_by_side_drop_wireframe.png");
    for (int view : {0, 1}) {
        const Viewport port = viewer.viewport(view);
        const long solidColoured = statistics(crop(solid, port)).colouredPixels;
        const long wireColoured = statistics(crop(wire, port)).colouredPixels;
        INFO("view " << view << ": coloured pixels solid " << solidColoured << ", wireframe " << wireColoured);
        CHECK(wireColoured > 0);                    // the edges are drawn in this view too
        CHECK(wireColoured < solidColoured / 2);    // and only the edges
        CHECK(cyanPixels(crop(solid, port)) == 0);
        CHECK(cyanPixels(crop(boxes, port)) > 100);  // each view has its bounding boxes
        CHECK(cyanPixels(crop(both, port)) > 100);
    }
    // Nothing of either view's overlay spills into the panel's column or the gap between views.
    const Viewport left = viewer.viewport(0), rightView = viewer.viewport(1);
    REQUIRE(rightView.x > left.x + left.width);
    CHECK(cyanPixels(crop(boxes, Viewport{left.x + left.width, 0, rightView.x - left.x - left.width, boxes.height})) == 0);
}

TEST_CASE("the help names one key for each action: t throws, x draws contacts through bodies") {
    // No window needed: --help prints and exits before any is made.
    const std::string command = std::string("\"") + GDCONTACT_VIEWER_EXECUTABLE + "\" --help";
    std::string text;
    if (FILE* pipe = popen(command.c_str(), "r")) {
        char buffer[512];
        while (std::fgets(buffer, sizeof buffer, pipe)) text += buffer;
        CHECK(pclose(pipe) == 0);
    }
    CHECK_THAT(text, Catch::Contains("t throw from the camera") && Catch::Contains("x contacts through") &&
                         Catch::Contains("d drop at the cursor") && Catch::Contains("v side by side"));
    CHECK_THAT(text, !Catch::Contains("t contacts through"));
}

namespace {

/// The lowest height of a dCylinder or dCapsule geom's exact surface (its axis is the geom's z).
double lowestPointOfRound(dGeomID geom) {
    const dReal* r = dGeomGetRotation(geom);
    const double axisZ = std::min(1.0, std::abs(double(r[10])));  // the z of the geom's z axis
    const double height = dGeomGetPosition(geom)[2];
    dReal radius, length;
    if (dGeomGetClass(geom) == dCylinderClass) {
        dGeomCylinderGetParams(geom, &radius, &length);
        return height - 0.5 * length * axisZ - radius * std::sqrt(1.0 - axisZ * axisZ);  // the rim's lowest point
    }
    dGeomCapsuleGetParams(geom, &radius, &length);
    return height - 0.5 * length * axisZ - radius;
}

}  // namespace

TEST_CASE("side by side: a cylinder and a capsule are ODE's own geoms in both worlds, drawn, and rest on the ground") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    const std::pair<SpawnKind, int> kinds[] = {{SpawnKind::Cylinder, dCylinderClass}, {SpawnKind::Capsule, dCapsuleClass}};
    for (const auto& [kind, geomClass] : kinds) {
        SECTION(spawnKindName(kind)) {
            ViewerOptions options = testOptions("box_drop");
            options.width = 640;
            options.sideBySide = true;  // gdcontact left, ODE's native colliders right
            Viewer viewer(options);
            viewer.simulate(0.1);
            const std::size_t count = viewer.scene(0).bodies().size();
            const OrbitCamera& camera = viewer.camera();
            const Vec3 right = (camera.target() - camera.eye()).cross(Vec3::UnitZ()).normalized();
            Vec3 ground = camera.target() + 0.8 * right;
            ground.z() = 0.0;
            viewer.interaction().kind = kind;
            const Eigen::Vector2d pixel = pixelInView(viewer, 0, ground);
            REQUIRE(viewer.dropAt(pixel.x(), pixel.y()) != nullptr);
            viewer.simulate(2.0);

            for (int view : {0, 1}) {
                INFO((view == 0 ? "gdcontact" : "ODE's colliders"));
                REQUIRE(viewer.scene(view).bodies().size() == count + 1);
                const scenes::Body& body = viewer.scene(view).bodies().back();
                REQUIRE(body.parts.size() == 1);
                const dGeomID geom = body.parts[0].geom;
                CHECK(dGeomGetClass(geom) == geomClass);  // the exact geom, not a hull
                // The density times the exact volume: π r² h, π r² (L + 4r/3).
                dReal radius, length;
                if (geomClass == dCylinderClass) dGeomCylinderGetParams(geom, &radius, &length);
                else dGeomCapsuleGetParams(geom, &radius, &length);
                const double ends = geomClass == dCylinderClass ? 0.0 : 4.0 * radius / 3.0;
                dMass mass;
                dBodyGetMass(body.body, &mass);
                CHECK(mass.mass == Approx(1000.0 * scenes::kPi * radius * radius * (length + ends)).epsilon(1e-6));
                // Drawn: the view's shapes have a mesh for it.
                bool drawn = false;
                for (const DrawShape& shape : viewer.shapes(view).shapes()) drawn |= shape.geom == geom && !shape.isPlane();
                CHECK(drawn);
                // At rest on the ground, not sunk into it: its exact lowest point within a
                // millimetre of z = 0 (what ERP leaves of a resting overlap is far less).
                const double lowest = lowestPointOfRound(geom);
                INFO("lowest point " << lowest << " m, speed " << velocityOf(body.body).norm() << " m/s");
                CHECK(lowest > -1e-3);
                CHECK(lowest < 1e-3);
                CHECK(velocityOf(body.body).norm() < 0.05);
                CHECK(viewer.scene(view).lastContacts().size() > 0);
            }
        }
    }
}

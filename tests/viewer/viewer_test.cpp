// The viewer as a person and as the docs use it, in a real window (Xvfb + Mesa llvmpipe, started
// by the test): every scene renders to a non-blank frame showing its bodies; dragging a body with
// the mouse moves it towards the cursor; ctrl-click removes a brick; the headless command writes
// a screenshot of each scene, and records every K-th frame as PNG.
#include "image.hpp"
#include "ode_session.hpp"
#include "viewer.hpp"
#include "x_server.hpp"

#include <catch2/catch.hpp>
#include <ode/ode.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace gdc;
using namespace gdc::viewer;

namespace {

using gdc::testing::OdeSession;

ViewerOptions testOptions(const std::string& scene) {
    ViewerOptions options;
    options.scene = scene;
    options.width = 480;
    options.height = 270;
    options.visible = false;
    options.panel = false;
    return options;
}

Vec3 positionOf(dBodyID body) {
    const dReal* p = dBodyGetPosition(body);
    return Vec3(p[0], p[1], p[2]);
}

// A frame shows something: not one flat colour, and a share of pixels in the bodies' colours.
void requireShowsBodies(const Image& image) {
    const ImageStatistics stats = statistics(image);
    INFO("luminance variance " << stats.luminanceVariance << ", coloured pixels " << stats.colouredPixels);
    CHECK(stats.luminanceVariance > 50.0);
    CHECK(stats.colouredPixels > long(image.width) * image.height / 200);
}

// The body that the cursor at its projected centre picks — one a person can click on.
const scenes::Body* clickableBody(Viewer& viewer, bool removable, Eigen::Vector2d& pixel) {
    std::vector<const scenes::Body*> candidates;
    for (const auto& body : viewer.scene().bodies())
        if (!removable || body.removable) candidates.push_back(&body);
    // Highest first: the top of a stack moves freely.
    std::sort(candidates.begin(), candidates.end(),
              [](auto* a, auto* b) { return positionOf(a->body).z() > positionOf(b->body).z(); });
    for (const auto* body : candidates) {
        pixel = viewer.camera().project(positionOf(body->body), viewer.windowWidth(), viewer.windowHeight());
        if (viewer.grab(pixel.x(), pixel.y())) {
            const bool itself = viewer.drag().body() == body->body;
            viewer.release();
            if (itself) return body;
        }
    }
    return nullptr;
}

}  // namespace

TEST_CASE("every scene renders a frame that shows its bodies") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    for (const std::string& name : scenes::sceneNames()) {
        SECTION(name) {
            Viewer viewer(testOptions(name));
            for (int frame = 0; frame < 10; ++frame) {
                viewer.simulate(1.0 / 60.0);
                viewer.draw();
                viewer.present();
            }
            viewer.draw();
            const Image image = viewer.capture();
            REQUIRE(image.width == 480);
            REQUIRE(image.height == 270);
            requireShowsBodies(image);
        }
    }
}

TEST_CASE("dragging a body with the mouse pulls it towards the cursor") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    Viewer viewer(testOptions("brick_wall"));
    viewer.simulate(0.5);  // let the wall settle on the ground

    Eigen::Vector2d pixel;
    const scenes::Body* brick = clickableBody(viewer, false, pixel);
    REQUIRE(brick != nullptr);
    const Vec3 before = positionOf(brick->body);

    // Press on the brick, move the cursor 60 pixels up (the view looks down on the wall, so this
    // is up and away), hold for a second of simulated time.
    REQUIRE(viewer.grab(pixel.x(), pixel.y()));
    REQUIRE(viewer.drag().body() == brick->body);
    const double grabToTarget = (viewer.drag().target() - viewer.drag().anchorWorld()).norm();
    CHECK(grabToTarget < 1e-9);  // the spring starts relaxed at the grabbed point
    viewer.dragTo(pixel.x(), pixel.y() - 60.0);
    const Vec3 target = viewer.drag().target();
    const double startGap = (target - viewer.drag().anchorWorld()).norm();
    REQUIRE(startGap > 0.05);
    viewer.simulate(1.0);
    const Vec3 after = positionOf(brick->body);
    const double endGap = (target - viewer.drag().anchorWorld()).norm();
    viewer.release();

    INFO("moved " << (after - before).transpose() << ", gap " << startGap << " → " << endGap);
    CHECK(after.z() > before.z() + 0.02);          // lifted off the wall
    CHECK(endGap < 0.25 * startGap);               // followed the cursor
    CHECK((after - before).dot(target - before) > 0.0);
    CHECK_FALSE(viewer.drag().active());
}

TEST_CASE("ctrl-click removes the brick under the cursor and nothing else") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    OdeSession ode;
    Viewer viewer(testOptions("brick_wall"));
    viewer.simulate(0.1);
    const std::size_t count = viewer.scene().bodies().size();
    Eigen::Vector2d pixel;
    const scenes::Body* brick = clickableBody(viewer, true, pixel);
    REQUIRE(brick != nullptr);
    const dBodyID removed = brick->body;
    REQUIRE(viewer.removeAt(pixel.x(), pixel.y()));
    CHECK(viewer.scene().bodies().size() == count - 1);
    for (const auto& body : viewer.scene().bodies()) CHECK(body.body != removed);
    // The simulation and the drawing carry on without it.
    viewer.simulate(0.1);
    viewer.draw();
    requireShowsBodies(viewer.capture());
    // Clicking the sky removes nothing.
    CHECK_FALSE(viewer.removeAt(1.0, 1.0));
    CHECK(viewer.scene().bodies().size() == count - 1);
}

TEST_CASE("the headless command writes a screenshot of each scene") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    for (const std::string& name : scenes::sceneNames()) {
        SECTION(name) {
            const std::string path = std::string(GDCONTACT_VIEWER_TEST_OUTPUT) + "/viewer_" + name + ".png";
            std::remove(path.c_str());
            const std::string command = std::string("\"") + GDCONTACT_VIEWER_EXECUTABLE + "\" --scene " + name +
                                        " --frames 12 --size 480x270 --hidden --screenshot \"" + path + "\" > /dev/null";
            INFO(command);
            REQUIRE(std::system(command.c_str()) == 0);
            const Image image = readPng(path);
            CHECK(image.width == 480);
            CHECK(image.height == 270);
            requireShowsBodies(image);
        }
    }
    // Bad input is refused with an error, not a crash.
    CHECK(std::system((std::string("\"") + GDCONTACT_VIEWER_EXECUTABLE + "\" --scene no_such_scene --frames 1 --hidden 2> /dev/null").c_str()) != 0);
}

TEST_CASE("the headless command records every K-th frame and the last as PNG") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    const std::string directory = std::string(GDCONTACT_VIEWER_TEST_OUTPUT) + "/viewer_recording";
    const std::string viewer = std::string("\"") + GDCONTACT_VIEWER_EXECUTABLE + "\"";
    std::system(("rm -rf \"" + directory + "\"").c_str());
    // 25 frames, every 10th: frames 0, 10, 20 and the last (24), as frame_0000.png ... frame_0003.png.
    const std::string command = viewer + " --scene box_drop --frames 25 --record-every 10 --record-dir \"" + directory +
                                "\" --size 480x270 --hidden --no-panel > /dev/null";
    INFO(command);
    REQUIRE(std::system(command.c_str()) == 0);
    std::vector<Image> frames;
    for (int i = 0; i < 4; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame_%04d.png", i);
        frames.push_back(readPng(directory + name));
        CHECK(frames.back().width == 480);
        CHECK(frames.back().height == 270);
        requireShowsBodies(frames.back());
    }
    CHECK_THROWS(readPng(directory + "/frame_0004.png"));
    // The box falls between the first and the last recorded frame: the pictures differ.
    CHECK(frames.front().rgb != frames.back().rgb);
    // Recording needs a folder and a frame count.
    CHECK(std::system((viewer + " --scene box_drop --frames 5 --record-every 2 --hidden 2> /dev/null").c_str()) != 0);
    CHECK(std::system((viewer + " --scene box_drop --record-every 2 --record-dir x --hidden 2> /dev/null").c_str()) != 0);
}

// The renderer in a real OpenGL context (Xvfb + Mesa llvmpipe, started by the test itself): what
// is drawn where the camera says it is.
#include "camera.hpp"
#include "image.hpp"
#include "renderer.hpp"
#include "scene_shapes.hpp"
#include "x_server.hpp"

#include <GLFW/glfw3.h>
#include <catch2/catch.hpp>
#include <ode/ode.h>

#include <algorithm>

using namespace gdc;
using namespace gdc::viewer;

namespace {

// A hidden window with an OpenGL 2.1 context, as the viewer makes.
class GlWindow {
public:
    GlWindow(int width, int height) {
        if (!glfwInit()) return;
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
        glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
        window_ = glfwCreateWindow(width, height, "render test", nullptr, nullptr);
        if (window_) glfwMakeContextCurrent(window_);
    }
    ~GlWindow() {
        if (window_) glfwDestroyWindow(window_);
        glfwTerminate();
    }
    explicit operator bool() const { return window_ != nullptr; }

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace

TEST_CASE("a box is drawn in its colour where the camera projects it, on a grey ground and sky") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    const int width = 320, height = 240;
    GlWindow window(width, height);
    REQUIRE(window);

    dInitODE2(0);
    dSpaceID space = dSimpleSpaceCreate(nullptr);
    dGeomID box = dCreateBox(space, 1, 1, 1);
    dGeomSetPosition(box, 0, 0, 0.5);
    dCreatePlane(space, 0, 0, 1, 0);
    SceneShapes shapes;
    shapes.update(space);

    OrbitCamera camera(Vec3::UnitZ());
    camera.frame(Vec3(-1, -1, 0), Vec3(1, 1, 1));
    FrameInput in;
    in.camera = &camera;
    in.width = width;
    in.height = height;
    in.shapes = &shapes.shapes();
    const Colour red{0.9f, 0.15f, 0.1f};
    for (const auto& shape : shapes.shapes()) in.colours.push_back(shape.isPlane() ? Colour{0.5f, 0.5f, 0.5f} : red);
    Renderer renderer;
    renderer.render(in);
    const Image image = readFramebuffer(width, height);
    REQUIRE(image.width == width);

    // The centre of the box's top face and of its box: red-dominated pixels (lit flat shading
    // scales all channels alike, so the hue survives).
    for (const Vec3& point : {Vec3(0, 0, 1.0), Vec3(0, 0, 0.5)}) {
        const Eigen::Vector2d p = camera.project(point, width, height);
        const std::uint8_t* pixel = image.pixel(int(p.x()), int(p.y()));
        INFO("pixel " << int(pixel[0]) << " " << int(pixel[1]) << " " << int(pixel[2]));
        CHECK(pixel[0] > 2 * pixel[1]);
        CHECK(pixel[0] > 2 * pixel[2]);
    }
    // Top-left corner: sky, a grey (channels spread far less than the 40 that counts as coloured).
    const std::uint8_t* sky = image.pixel(0, 0);
    CHECK(std::max({sky[0], sky[1], sky[2]}) - std::min({sky[0], sky[1], sky[2]}) < 20);
    // The ground between the camera and the box: grey too.
    Vec3 towardsEye = camera.eye() - camera.target();
    towardsEye.z() = 0.0;
    const Eigen::Vector2d ground = camera.project(1.6 * towardsEye.normalized(), width, height);
    REQUIRE(ground.y() < height);
    const std::uint8_t* g = image.pixel(int(ground.x()), int(ground.y()));
    CHECK(std::max({g[0], g[1], g[2]}) - std::min({g[0], g[1], g[2]}) < 20);
    // Only the box is coloured: a sizeable but bounded share of the image.
    const ImageStatistics stats = statistics(image);
    CHECK(stats.colouredPixels > width * height / 50);
    CHECK(stats.colouredPixels < width * height / 2);

    // PNG round trip keeps every byte.
    const std::string path = "render_test_box.png";
    writePng(image, path);
    const Image back = readPng(path);
    CHECK(back.width == width);
    CHECK(back.height == height);
    CHECK(back.rgb == image.rgb);

    dSpaceDestroy(space);
    dCloseODE();
}

namespace {

// A unit box standing on the ground at the origin, framed as the viewer frames a scene.
struct BoxOnGround {
    dSpaceID space = nullptr;
    SceneShapes shapes;
    OrbitCamera camera{Vec3::UnitZ()};
    BoxOnGround() {
        dInitODE2(0);
        space = dSimpleSpaceCreate(nullptr);
        dGeomID box = dCreateBox(space, 1, 1, 1);
        dGeomSetPosition(box, 0, 0, 0.5);
        dCreatePlane(space, 0, 0, 1, 0);
        shapes.update(space);
        camera.frame(Vec3(-1, -1, 0), Vec3(1, 1, 1));
    }
    ~BoxOnGround() {
        dSpaceDestroy(space);
        dCloseODE();
    }
    FrameInput input(int width, int height) const {
        FrameInput in;
        in.camera = &camera;
        in.width = width;
        in.height = height;
        in.shapes = &shapes.shapes();
        for (const auto& shape : shapes.shapes())
            in.colours.push_back(shape.isPlane() ? Colour{0.5f, 0.5f, 0.5f} : Colour{0.9f, 0.15f, 0.1f});
        return in;
    }
};

double luminance(const std::uint8_t* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

}  // namespace

TEST_CASE("a contact behind a body is hidden unless drawn through, one in front of it is always drawn") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    const int width = 320, height = 240;
    GlWindow window(width, height);
    REQUIRE(window);
    BoxOnGround scene;
    // On the line of sight through the box's centre: 1.2 m beyond it (hidden by the box) or
    // 1.2 m before it (between the eye and the box). A touching contact is drawn green.
    const Vec3 centre(0, 0, 0.5);
    const Vec3 sight = (scene.camera.target() - scene.camera.eye()).normalized();
    Renderer renderer;
    auto markerShows = [&](const Vec3& where, bool through) {
        FrameInput in = scene.input(width, height);
        in.contacts.push_back({where, Vec3::UnitZ(), 0.0});
        in.normalLength = 0.0;  // the point alone
        in.depthExaggeration = 0.0;
        in.contactsThrough = through;
        renderer.render(in);
        const Image image = readFramebuffer(width, height);
        const Eigen::Vector2d p = scene.camera.project(where, width, height);
        const std::uint8_t* pixel = image.pixel(int(p.x()), int(p.y()));
        INFO("pixel " << int(pixel[0]) << " " << int(pixel[1]) << " " << int(pixel[2]));
        const bool green = pixel[1] > 200 && pixel[0] < 60;
        const bool boxRed = pixel[0] > 2 * pixel[1] && pixel[0] > 2 * pixel[2];
        CHECK((green || boxRed));  // one or the other, nothing in between
        return green;
    };
    CHECK_FALSE(markerShows(centre + 1.2 * sight, false));
    CHECK(markerShows(centre + 1.2 * sight, true));
    CHECK(markerShows(centre - 1.2 * sight, false));
    CHECK(markerShows(centre - 1.2 * sight, true));
}

TEST_CASE("the box's visible faces get three different shades and its shadow darkens the ground") {
    const std::string problem = test::ensureXServer();
    if (!problem.empty()) return test::reportSkipped(problem);
    const int width = 320, height = 240;
    GlWindow window(width, height);
    REQUIRE(window);
    BoxOnGround scene;
    Renderer renderer;
    FrameInput in = scene.input(width, height);
    renderer.render(in);
    const Image lit = readFramebuffer(width, height);
    // The default view sees the top, the −y face and the +x face.
    std::vector<double> shades;
    for (const Vec3& faceCentre : {Vec3(0, 0, 1.0), Vec3(0, -0.5, 0.5), Vec3(0.5, 0, 0.5)}) {
        const Eigen::Vector2d p = scene.camera.project(faceCentre, width, height);
        shades.push_back(luminance(lit.pixel(int(p.x()), int(p.y()))));
    }
    INFO("top " << shades[0] << ", front " << shades[1] << ", side " << shades[2]);
    CHECK(std::abs(shades[0] - shades[1]) > 10.0);
    CHECK(std::abs(shades[1] - shades[2]) > 10.0);
    CHECK(std::abs(shades[0] - shades[2]) > 10.0);

    // Where the sun projects a point of the top face 0.1 m in from its −x edge onto the ground:
    // inside the box's shadow, and (the sun shines from the camera's right) beside the box in the
    // picture, not hidden behind it.
    const Vec3 sun = sunDirection();
    const Vec3 shadowed = Vec3(-0.4, 0, 1.0) - (1.0 / sun.z()) * sun;
    const Eigen::Vector2d p = scene.camera.project(shadowed, width, height);
    REQUIRE(p.x() >= 0);
    REQUIRE(p.x() < width);
    REQUIRE(p.y() >= 0);
    REQUIRE(p.y() < height);
    in.shadows = false;
    renderer.render(in);
    const Image unshadowed = readFramebuffer(width, height);
    const double withShadow = luminance(lit.pixel(int(p.x()), int(p.y())));
    const double without = luminance(unshadowed.pixel(int(p.x()), int(p.y())));
    INFO("ground luminance " << withShadow << " in the shadow, " << without << " without shadows");
    CHECK(withShadow < 0.8 * without);
    // The shadow is grey: the sky and the ground stay uncoloured.
    const std::uint8_t* g = lit.pixel(int(p.x()), int(p.y()));
    CHECK(std::max({g[0], g[1], g[2]}) - std::min({g[0], g[1], g[2]}) < 20);
}

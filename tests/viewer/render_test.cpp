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

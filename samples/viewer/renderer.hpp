// Draws a frame with OpenGL 2.1 fixed-function calls (what Mesa's llvmpipe offers under Xvfb as
// readily as a desktop driver): flat-shaded bodies with dark outlines, a checkered ground, contact
// points, normals and depths, and the drag spring. Reads the scene state; never changes it.
#pragma once

#include "camera.hpp"
#include "scene_shapes.hpp"

#include <array>
#include <optional>
#include <vector>

namespace gdc::viewer {

using Colour = std::array<float, 3>;

struct ContactMark {
    Vec3 position;
    Vec3 normal;   // unit
    double depth;  // ≥ 0 overlap (m)
};

struct FrameInput {
    const OrbitCamera* camera = nullptr;
    int width = 0, height = 0;  // framebuffer pixels
    const std::vector<DrawShape>* shapes = nullptr;
    std::vector<Colour> colours;        // one per shape
    std::vector<bool> highlighted;      // one per shape (may be empty)
    std::vector<ContactMark> contacts;  // drawn when non-empty
    double normalLength = 0.1;          // m: drawn length of a contact normal
    double depthForRed = 0.005;         // m: a contact this deep is drawn fully red
    double depthExaggeration = 10.0;    // the depth segment is drawn this many times longer
    double groundTile = 0.5;            // m: checker tile of a ground plane
    std::optional<std::pair<Vec3, Vec3>> spring;  // drag anchor → target
    bool outlines = true;
};

/// Draws frames into the current GL context's framebuffer (viewport = the whole framebuffer).
/// Holds the GL objects it made (the ground's checker texture); use it with one context only.
class Renderer {
public:
    Renderer() = default;
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;
    void render(const FrameInput& input);

private:
    void drawGround(const DrawShape& plane, const FrameInput& input);
    unsigned groundTexture_ = 0;
};

}  // namespace gdc::viewer

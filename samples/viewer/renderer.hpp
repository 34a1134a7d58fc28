// Draws a frame with OpenGL 2.1 fixed-function calls (what Mesa's llvmpipe offers under Xvfb as
// readily as a desktop driver): bodies lit per face by a sun fixed in the world plus a sky/ground
// hemisphere ambient (so a top, a side and an underside never share a shade), dark outlines, each
// body's shadow projected onto the ground, a checkered ground, contact points, normals and depths,
// and the drag spring. Reads the scene state; never changes it.
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
    int width = 0, height = 0;  // framebuffer pixels of the viewport drawn into
    int x = 0, y = 0;           // its lower-left corner in the framebuffer (OpenGL's convention)
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
    /// Contact marks drawn over the bodies in front of them (false: hidden where a body is nearer
    /// the eye, like everything else in the picture).
    bool contactsThrough = false;
    bool shadows = true;  // each body's shadow on the ground planes
};

/// Where the sun shines from (unit vector towards it, world frame, z up): fixed in the world so
/// shades and shadows stay put while the camera orbits.
Vec3 sunDirection();

/// Points OpenGL at the frame's viewport (clipped to it with the scissor test: side by side, the
/// other view stays) and loads its camera's projection and view matrices.
void useFrameCamera(const FrameInput& in);
/// Brightness factor of a face with world normal `normal` (z up): hemisphere ambient (sky above,
/// ground below) plus the sun's Lambert term. Between 0.25 (facing down) and 1.0 (facing the sun).
double faceBrightness(const Vec3& normal);

/// Draws frames into a rectangle (the viewport) of the current GL context's framebuffer.
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
    void drawShadows(const DrawShape& plane, const FrameInput& input);
    unsigned groundTexture_ = 0;
};

}  // namespace gdc::viewer

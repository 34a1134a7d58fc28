#include "renderer.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace gdc::viewer {
namespace {

// Background and ground are unsaturated greys so every saturated pixel in a frame is a body or
// an overlay (the headless test counts them).
constexpr float kSkyTop[3] = {0.50f, 0.52f, 0.55f};
constexpr float kSkyBottom[3] = {0.82f, 0.83f, 0.84f};
constexpr float kGroundLight[3] = {0.72f, 0.72f, 0.72f};
constexpr float kGroundDark[3] = {0.60f, 0.60f, 0.60f};

void vertex(const Vec3& v) { glVertex3d(v.x(), v.y(), v.z()); }

void drawBackground() {
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_LIGHTING);
    glBegin(GL_QUADS);
    glColor3fv(kSkyBottom);
    glVertex2d(-1, -1);
    glVertex2d(1, -1);
    glColor3fv(kSkyTop);
    glVertex2d(1, 1);
    glVertex2d(-1, 1);
    glEnd();
}

void drawMesh(const DrawShape& shape, const Colour& colour, bool highlighted, bool outlines) {
    const ConvexMesh& mesh = *shape.mesh;
    const Mat3& r = shape.pose.rotation;
    Colour c = colour;
    if (highlighted)
        for (float& channel : c) channel = 0.5f * channel + 0.5f;
    // Lit here, once per face, rather than by GL lighting: the faces are flat anyway, and a sun
    // fixed in the world keeps each face's shade (and the shadows) still while the camera orbits.
    glDisable(GL_LIGHTING);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);  // push faces back so the outlines on their edges win
    for (const auto& face : mesh.faces) {
        const float shade = float(faceBrightness(r * face.normal));
        glColor3f(shade * c[0], shade * c[1], shade * c[2]);
        glBegin(GL_POLYGON);
        for (int i : face.loop) vertex(shape.pose.apply(mesh.vertices[i]));
        glEnd();
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    if (!outlines) return;
    glDisable(GL_LIGHTING);
    glColor3f(0.25f * c[0], 0.25f * c[1], 0.25f * c[2]);
    glBegin(GL_LINES);
    for (const auto& [a, b] : mesh.edges) {
        vertex(shape.pose.apply(mesh.vertices[a]));
        vertex(shape.pose.apply(mesh.vertices[b]));
    }
    glEnd();
}

void drawContacts(const FrameInput& in) {
    // Depth-tested by default, so a contact behind a body does not seem to float in front of it;
    // "through" shows them all (contacts lie between bodies, so most are hidden by both).
    glDisable(GL_LIGHTING);
    if (in.contactsThrough) glDisable(GL_DEPTH_TEST);
    else glEnable(GL_DEPTH_TEST);
    glBegin(GL_LINES);
    for (const auto& c : in.contacts) {
        glColor3f(1.0f, 0.85f, 0.1f);  // normal: yellow
        vertex(c.position);
        vertex(c.position + in.normalLength * c.normal);
        glColor3f(1.0f, 0.1f, 0.6f);  // depth: magenta, centred on the point, exaggerated
        const Vec3 half = 0.5 * in.depthExaggeration * c.depth * c.normal;
        vertex(c.position - half);
        vertex(c.position + half);
    }
    glEnd();
    glPointSize(6.0f);
    glBegin(GL_POINTS);
    for (const auto& c : in.contacts) {
        const float red = float(std::clamp(c.depth / in.depthForRed, 0.0, 1.0));
        glColor3f(red, 1.0f - red, 0.1f);  // green (touching) → red (deep)
        vertex(c.position);
    }
    glEnd();
    glEnable(GL_DEPTH_TEST);
}

}  // namespace

void useFrameCamera(const FrameInput& in) {
    glViewport(in.x, in.y, in.width, in.height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(in.x, in.y, in.width, in.height);
    glMatrixMode(GL_PROJECTION);
    const Mat4 projection = in.camera->projection(double(in.width) / std::max(in.height, 1));
    glLoadMatrixd(projection.data());
    glMatrixMode(GL_MODELVIEW);
    const Mat4 view = in.camera->view();
    glLoadMatrixd(view.data());
}

Vec3 sunDirection() {
    // 50° up, from the default camera's right (it looks along +x+y·2.2 from the −y side): the
    // shadows fall to the left, beside the bodies, where the camera sees them, not behind them.
    return Vec3(0.976, -0.22, 1.2).normalized();
}

double faceBrightness(const Vec3& normal) {
    // Hemisphere ambient: 0.5 from the sky for a face looking up, 0.25 for one looking down (the
    // ground's bounce light), so a stacked body's underside and the top of the one below differ.
    const double up = std::clamp(normal.z(), -1.0, 1.0);
    const double ambient = 0.375 + 0.125 * up;
    return ambient + 0.5 * std::max(0.0, normal.dot(sunDirection()));
}

void Renderer::drawShadows(const DrawShape& plane, const FrameInput& in) {
    // Each body's faces projected along the sun's direction onto the plane: dark, translucent,
    // and counted in the stencil buffer so where two shadows overlap the ground darkens once.
    const Vec3 n = plane.planeNormal;
    const Vec3 sun = sunDirection();
    const double towardsSun = n.dot(sun);
    if (towardsSun < 0.05) return;  // sun at or below this plane's horizon: no shadow to cast on it
    auto project = [&](const Vec3& p) {
        const double height = std::max(0.0, n.dot(p) - plane.planeOffset);
        return Vec3(p - (height / towardsSun) * sun);
    };
    glDisable(GL_LIGHTING);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -1.0f);  // in front of the ground it lies on
    glEnable(GL_STENCIL_TEST);      // without a stencil buffer the test passes: overlaps darken twice
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    glColor4f(0.0f, 0.0f, 0.0f, 0.32f);
    for (const auto& shape : *in.shapes) {
        if (shape.isPlane()) continue;
        for (const auto& face : shape.mesh->faces) {
            glBegin(GL_POLYGON);
            for (int i : face.loop) vertex(project(shape.pose.apply(shape.mesh->vertices[i])));
            glEnd();
        }
    }
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
}

void Renderer::drawGround(const DrawShape& plane, const FrameInput& in) {
    // One large quad with a repeating 2×2 checker texture: a software rasteriser fills it far
    // faster than thousands of tile quads.
    if (groundTexture_ == 0) {
        std::uint8_t texels[2 * 2 * 3];
        for (int i = 0; i < 4; ++i)
            for (int c = 0; c < 3; ++c)
                texels[3 * i + c] = std::uint8_t(255.0f * ((i == 0 || i == 3) ? kGroundDark[c] : kGroundLight[c]));
        glGenTextures(1, &groundTexture_);
        glBindTexture(GL_TEXTURE_2D, groundTexture_);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, 2, 2, 0, GL_RGB, GL_UNSIGNED_BYTE, texels);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    }
    const Vec3 n = plane.planeNormal;
    const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 u = (helper - helper.dot(n) * n).normalized();
    const Vec3 v = n.cross(u);
    // Centred under the camera target (snapped to whole texture periods so the pattern does not
    // slide when the camera pans), wide enough to reach the horizon of any reasonable view.
    const Vec3 target = in.camera->target();
    const double period = 2.0 * in.groundTile;
    const double centreU = period * std::round(u.dot(target) / period);
    const double centreV = period * std::round(v.dot(target) / period);
    const double half = std::max(200.0 * in.groundTile, 4.0 * in.camera->distance());
    const double repeats = half / period;
    const Vec3 base = plane.planeOffset * n + centreU * u + centreV * v;
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, groundTexture_);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    glColor3f(1.0f, 1.0f, 1.0f);
    glNormal3d(n.x(), n.y(), n.z());
    glBegin(GL_QUADS);
    glTexCoord2d(-repeats, -repeats);
    vertex(base - half * u - half * v);
    glTexCoord2d(repeats, -repeats);
    vertex(base + half * u - half * v);
    glTexCoord2d(repeats, repeats);
    vertex(base + half * u + half * v);
    glTexCoord2d(-repeats, repeats);
    vertex(base - half * u + half * v);
    glEnd();
    glDisable(GL_TEXTURE_2D);
}

Renderer::~Renderer() {
    if (groundTexture_ != 0) glDeleteTextures(1, &groundTexture_);
}

void Renderer::render(const FrameInput& in) {
    // The scissor keeps the clear inside this viewport: side by side, the other view stays.
    glViewport(in.x, in.y, in.width, in.height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(in.x, in.y, in.width, in.height);
    glClearColor(kSkyTop[0], kSkyTop[1], kSkyTop[2], 1.0f);
    glClearDepth(1.0);
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    drawBackground();  // in identity matrices

    useFrameCamera(in);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glShadeModel(GL_FLAT);
    glDisable(GL_LIGHTING);

    const auto& shapes = *in.shapes;
    for (std::size_t i = 0; i < shapes.size(); ++i)
        if (shapes[i].isPlane()) {
            drawGround(shapes[i], in);
            if (in.shadows) drawShadows(shapes[i], in);
        }
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        if (shapes[i].isPlane()) continue;
        const bool lit = i < in.highlighted.size() && in.highlighted[i];
        drawMesh(shapes[i], i < in.colours.size() ? in.colours[i] : Colour{0.7f, 0.7f, 0.7f}, lit, in.outlines);
    }
    if (!in.contacts.empty()) drawContacts(in);
    if (in.spring) {
        glDisable(GL_LIGHTING);
        glDisable(GL_DEPTH_TEST);
        glLineWidth(2.0f);
        glColor3f(0.1f, 0.9f, 1.0f);
        glBegin(GL_LINES);
        vertex(in.spring->first);
        vertex(in.spring->second);
        glEnd();
        glPointSize(8.0f);
        glBegin(GL_POINTS);
        vertex(in.spring->second);
        glEnd();
        glEnable(GL_DEPTH_TEST);
    }
    glLineWidth(1.0f);
    glDisable(GL_LIGHTING);
    glDisable(GL_SCISSOR_TEST);
}

}  // namespace gdc::viewer

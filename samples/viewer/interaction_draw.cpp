// The debug drawing of interaction.hpp: wireframe bodies and bounding boxes, drawn with OpenGL 2.1
// fixed-function calls after the renderer's frame, without changing the renderer.
#include "interaction.hpp"

#include <GL/gl.h>

#include <algorithm>

namespace gdc::viewer {
namespace {

void vertex(const Vec3& v) { glVertex3d(v.x(), v.y(), v.z()); }

void drawBox(const Vec3& low, const Vec3& high) {
    // The 12 edges: along each axis, the 4 edges whose other two coordinates are at low or high.
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int corner = 0; corner < 4; ++corner) {
            Vec3 a = low;
            a[u] = (corner & 1) ? high[u] : low[u];
            a[v] = (corner & 2) ? high[v] : low[v];
            Vec3 b = a;
            b[axis] = high[axis];
            vertex(a);
            vertex(b);
        }
    }
}

}  // namespace

FrameInput rendererInput(const FrameInput& in, const DebugDraw& debug, std::vector<DrawShape>& planes) {
    if (!debug.wireframe || in.shapes == nullptr) return in;
    planes.clear();
    std::copy_if(in.shapes->begin(), in.shapes->end(), std::back_inserter(planes),
                 [](const DrawShape& shape) { return shape.isPlane(); });
    FrameInput out = in;
    out.shapes = &planes;
    out.colours.clear();  // planes are drawn in the ground's own colours
    out.highlighted.clear();
    return out;
}

void drawDebugOverlay(const FrameInput& in, const DebugDraw& debug) {
    if ((!debug.wireframe && !debug.bounds) || in.shapes == nullptr || in.camera == nullptr) return;
    // Into the frame's own viewport (side by side: one of two), clipped to it as the renderer is.
    useFrameCamera(in);
    glDisable(GL_LIGHTING);
    glDisable(GL_TEXTURE_2D);
    glEnable(GL_DEPTH_TEST);  // the ground (and, without wireframe, the bodies) hides what is behind
    glDepthFunc(GL_LEQUAL);
    const auto& shapes = *in.shapes;
    glBegin(GL_LINES);
    if (debug.wireframe) {
        for (std::size_t i = 0; i < shapes.size(); ++i) {
            if (shapes[i].isPlane()) continue;
            Colour c = i < in.colours.size() ? in.colours[i] : Colour{0.7f, 0.7f, 0.7f};
            if (i < in.highlighted.size() && in.highlighted[i])
                for (float& channel : c) channel = 0.5f * channel + 0.5f;
            glColor3f(c[0], c[1], c[2]);
            const ConvexMesh& mesh = *shapes[i].mesh;
            for (const auto& [a, b] : mesh.edges) {
                vertex(shapes[i].pose.apply(mesh.vertices[a]));
                vertex(shapes[i].pose.apply(mesh.vertices[b]));
            }
        }
    }
    if (debug.bounds) {
        glColor3f(0.1f, 0.95f, 0.95f);  // cyan: no body and no contact mark is drawn in it
        for (const auto& [low, high] : shapeBounds(shapes)) drawBox(low, high);
    }
    glEnd();
    glDisable(GL_SCISSOR_TEST);
}

}  // namespace gdc::viewer

#include "recorder.hpp"

#include "viewer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace gdc::viewer {

namespace {
// The simulated time of one headless frame: the same 1/60 s as the viewer's --frames, so a
// recording of N frames ends where a --frames N --screenshot run does.
constexpr double kFrameSeconds = 1.0 / 60.0;

// Every corner of the box [low, high] in front of the camera and inside the image, a margin
// (a fraction of the image) clear of its edges.
bool fits(const OrbitCamera& camera, const Vec3& low, const Vec3& high, int width, int height) {
    constexpr double kMargin = 0.04;
    const Vec3 forward = (camera.target() - camera.eye()).normalized();
    for (int i = 0; i < 8; ++i) {
        const Vec3 corner(i & 1 ? high.x() : low.x(), i & 2 ? high.y() : low.y(), i & 4 ? high.z() : low.z());
        if ((corner - camera.eye()).dot(forward) <= camera.nearPlane()) return false;
        const Eigen::Vector2d pixel = camera.project(corner, width, height);
        if (pixel.x() < kMargin * width || pixel.x() > (1.0 - kMargin) * width || pixel.y() < kMargin * height ||
            pixel.y() > (1.0 - kMargin) * height)
            return false;
    }
    return true;
}

// Frames the camera on everything the bodies have covered so far, down to the ground (z = 0,
// Scene::addGroundPlane), so a falling box keeps its landing spot in view and a growing tower its
// top. The box only grows, so the camera moves only when a body leaves the view, and never back.
class GrowingFrame {
public:
    void update(Viewer& viewer) {
        viewer.snapshot();  // brings the viewer's shapes up to the scene's current poses
        Vec3 low, high;
        if (!viewer.shapes().bounds(low, high)) return;
        low.z() = std::min(low.z(), 0.0);
        if (known_ && (low.array() >= low_.array()).all() && (high.array() <= high_.array()).all()) return;
        low_ = known_ ? low_.cwiseMin(low) : low;
        high_ = known_ ? high_.cwiseMax(high) : high;
        known_ = true;
        // frame() fits the box's bounding sphere into the vertical field of view, which leaves a
        // wide image mostly empty; come closer while the box's corners still fit the image (and
        // first back off should they not, which the margin can cause).
        OrbitCamera& camera = viewer.camera();
        camera.frame(low_, high_);
        const int width = viewer.windowWidth(), height = viewer.windowHeight();
        for (int i = 0; i < 40 && !fits(camera, low_, high_, width, height); ++i) camera.zoom(1.0 / 0.97);
        for (int i = 0; i < 40; ++i) {
            OrbitCamera closer = camera;
            closer.zoom(0.97);
            if (!fits(closer, low_, high_, width, height)) break;
            camera = closer;
        }
    }

private:
    bool known_ = false;
    Vec3 low_, high_;
};
}  // namespace

int record(Viewer& viewer, int frames, const RecordOptions& options) {
    if (options.every <= 0 || frames <= 0) return 0;
    std::error_code error;
    std::filesystem::create_directories(options.directory, error);
    if (error) throw std::runtime_error("cannot create " + options.directory + ": " + error.message());

    const double dt = viewer.scene().solver().dt;
    long stepsDone = 0;
    int written = 0;
    GrowingFrame view;
    for (int frame = 0; frame < frames; ++frame) {
        // Whole steps up to this frame's end, counted from the start rather than accumulated, so
        // rounding never adds or drops a step however long the run.
        const long stepsDue = long(std::floor((frame + 1) * kFrameSeconds / dt + 1e-9));
        if (stepsDue > stepsDone) {
            viewer.simulate(double(stepsDue - stepsDone) * dt);
            stepsDone = stepsDue;
        }
        if (frame % options.every != 0 && frame + 1 != frames) continue;
        view.update(viewer);
        viewer.draw();
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04d.png", written);
        writePng(viewer.capture(), (std::filesystem::path(options.directory) / name).string());
        viewer.present();
        ++written;
    }
    return written;
}

}  // namespace gdc::viewer

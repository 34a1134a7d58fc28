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
        viewer.camera().frame(low_, high_);
        // frame() fits the box's bounding sphere into the vertical field of view; a wide frame
        // has room to spare beside it, so come a little closer.
        viewer.camera().zoom(kCloser);
    }

private:
    static constexpr double kCloser = 0.8;
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

// Frame recording for headless runs: every K-th frame of a run written as a numbered PNG, so that
// scripts/animate.py can turn a scene into an animation for the report without a screen recorder.
//
// Only the public Viewer API is used (simulate, draw, capture, present), so the recorder does not
// depend on how the viewer lays out its window; frames that are not recorded are simulated but
// not drawn, which keeps a 40-frame animation of a 20 s scene cheap under software OpenGL.
#pragma once

#include <string>

namespace gdc::viewer {

class Viewer;

struct RecordOptions {
    int every = 0;          ///< write every `every`-th frame (0: no recording)
    std::string directory;  ///< where frame_0000.png, frame_0001.png, ... go (created if missing)
};

/// Runs `frames` frames of exactly 1/60 s of simulated time each (as `--frames` does without
/// `--realtime`, so a recording is reproducible) and writes frames 0, every, 2·every, ... and
/// always the last one. Returns how many PNGs were written. Throws std::runtime_error when the
/// directory or a file cannot be written.
int record(Viewer& viewer, int frames, const RecordOptions& options);

}  // namespace gdc::viewer

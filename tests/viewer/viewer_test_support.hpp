// What the viewer tests (viewer_test.cpp, interaction_test.cpp) share: a small hidden window's
// options and a body's position.
#pragma once

#include "viewer.hpp"

#include <ode/ode.h>

#include <string>

namespace gdc::viewer::test {

/// A hidden 480 × 270 window without the panel, showing `scene`.
inline ViewerOptions testOptions(const std::string& scene) {
    ViewerOptions options;
    options.scene = scene;
    options.width = 480;
    options.height = 270;
    options.visible = false;
    options.panel = false;
    return options;
}

inline Vec3 positionOf(dBodyID body) {
    const dReal* p = dBodyGetPosition(body);
    return Vec3(p[0], p[1], p[2]);
}

}  // namespace gdc::viewer::test

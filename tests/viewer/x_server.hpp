// A private X server for the tests that open a window: Xvfb (package xvfb) with Mesa's software
// OpenGL (llvmpipe), started once per test process and stopped when it exits.
#pragma once

#include <string>

namespace gdc::viewer::test {

/// Makes DISPLAY point at a running X server: our own Xvfb if it can be started, otherwise an
/// already set DISPLAY. Returns an empty string on success, else why there is no X server.
std::string ensureXServer();

/// Marks the calling test skipped (CTest matches this text) and says why.
void reportSkipped(const std::string& reason);

}  // namespace gdc::viewer::test

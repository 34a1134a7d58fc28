// Frames as images: read back from OpenGL, written and read as PNG (stb from libstb-dev), and
// the two statistics the headless test judges a frame by.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gdc::viewer {

/// 8-bit RGB, rows top to bottom.
struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;
    const std::uint8_t* pixel(int x, int y) const { return &rgb[3 * (std::size_t(y) * width + x)]; }
};

/// The current GL read buffer (back buffer before swap), flipped to top-to-bottom rows.
Image readFramebuffer(int width, int height);
/// Throws std::runtime_error if the file cannot be written.
void writePng(const Image& image, const std::string& path);
/// Throws std::runtime_error if the file cannot be read as an image.
Image readPng(const std::string& path);

struct ImageStatistics {
    double luminanceVariance = 0.0;  // over all pixels, luminance in [0, 255]
    /// Pixels whose channels spread by more than the threshold (max − min): the viewer draws
    /// sky and ground in greys, so these are bodies and overlays.
    long colouredPixels = 0;
};
ImageStatistics statistics(const Image& image, int saturationThreshold = 40);

}  // namespace gdc::viewer

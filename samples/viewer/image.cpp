#include "image.hpp"

#include <GL/gl.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace gdc::viewer {

Image readFramebuffer(int width, int height) {
    Image image{width, height, std::vector<std::uint8_t>(std::size_t(3) * width * height)};
    std::vector<std::uint8_t> bottomUp(image.rgb.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.data());
    const std::size_t row = std::size_t(3) * width;
    for (int y = 0; y < height; ++y)
        std::memcpy(&image.rgb[y * row], &bottomUp[(height - 1 - y) * row], row);
    return image;
}

void writePng(const Image& image, const std::string& path) {
    if (!stbi_write_png(path.c_str(), image.width, image.height, 3, image.rgb.data(), 3 * image.width))
        throw std::runtime_error("cannot write PNG '" + path + "'");
}

Image readPng(const std::string& path) {
    int width = 0, height = 0, channels = 0;
    std::uint8_t* data = stbi_load(path.c_str(), &width, &height, &channels, 3);
    if (data == nullptr) throw std::runtime_error("cannot read image '" + path + "': " + stbi_failure_reason());
    Image image{width, height, std::vector<std::uint8_t>(data, data + std::size_t(3) * width * height)};
    stbi_image_free(data);
    return image;
}

ImageStatistics statistics(const Image& image, int saturationThreshold) {
    ImageStatistics result;
    const std::size_t count = std::size_t(image.width) * image.height;
    if (count == 0) return result;
    double sum = 0.0, sumSquares = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t* p = &image.rgb[3 * i];
        const double luminance = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        sum += luminance;
        sumSquares += luminance * luminance;
        const int spread = std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]});
        if (spread > saturationThreshold) ++result.colouredPixels;
    }
    const double mean = sum / count;
    result.luminanceVariance = std::max(0.0, sumSquares / count - mean * mean);
    return result;
}

}  // namespace gdc::viewer

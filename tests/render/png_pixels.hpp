#pragma once
// A PNG read back with cairo, for checking pictures pixel by pixel.
#include <cairo.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sinew/render/colour_map.hpp"

namespace sinew::test {

struct PngPixels {
    int width = 0, height = 0;
    std::vector<std::uint32_t> argb;  // row-major, cairo's 0xAARRGGBB

    explicit PngPixels(const std::string& path) {
        cairo_surface_t* surface = cairo_image_surface_create_from_png(path.c_str());
        if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
            cairo_surface_destroy(surface);
            throw std::runtime_error(path + ": not a readable PNG");
        }
        cairo_surface_flush(surface);
        width = cairo_image_surface_get_width(surface);
        height = cairo_image_surface_get_height(surface);
        const int stride = cairo_image_surface_get_stride(surface);
        const unsigned char* data = cairo_image_surface_get_data(surface);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                argb.push_back(*reinterpret_cast<const std::uint32_t*>(data + y * stride + 4 * x));
        cairo_surface_destroy(surface);
    }

    Rgb at(int x, int y) const {
        const std::uint32_t p = argb[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
        return {((p >> 16) & 0xff) / 255.0, ((p >> 8) & 0xff) / 255.0, (p & 0xff) / 255.0};
    }
    bool isWhite(int x, int y) const { return (argb[static_cast<std::size_t>(y * width + x)] & 0xffffff) == 0xffffff; }

    // The largest channel difference between `c` and the pixel nearest to it within `radius` of (x, y).
    double findNearestColour(double x, double y, const Rgb& c, int radius) const {
        double best = 1e9;
        const int cx = static_cast<int>(std::floor(x)), cy = static_cast<int>(std::floor(y));
        for (int py = cy - radius; py <= cy + radius; ++py)
            for (int px = cx - radius; px <= cx + radius; ++px) {
                if (px < 0 || py < 0 || px >= width || py >= height) continue;
                const Rgb p = at(px, py);
                best = std::min(best, std::max({std::abs(p.r - c.r), std::abs(p.g - c.g), std::abs(p.b - c.b)}));
            }
        return best;
    }
};

}  // namespace sinew::test

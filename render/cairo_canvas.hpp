#pragma once
// A white cairo image to draw a picture or plot on, written as PNG through an OutputFileSet (so a failed
// write leaves no partial file), and the text and colour helpers both drawings use. Internal to render/.
#include <cairo.h>

#include <memory>
#include <string>

#include "sinew/render/colour_map.hpp"

namespace sinew::render_detail {

class Canvas {
public:
    // Throws sinew::Error naming `path` (the file it is for) when cairo cannot make the image.
    Canvas(int width, int height, const std::string& path);
    cairo_t* get() const { return context_.get(); }
    // Throws sinew::Error naming the path when drawing failed or the file cannot be written.
    void writePng(const std::string& path) const;

private:
    struct SurfaceDeleter {
        void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
    };
    struct ContextDeleter {
        void operator()(cairo_t* c) const { cairo_destroy(c); }
    };
    std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface_;
    std::unique_ptr<cairo_t, ContextDeleter> context_;
};

void setColour(cairo_t* cr, const Rgb& c);

enum class TextAlign { Left, Centre, Right };
// Text with its baseline at y, in DejaVu Sans at `size` px; `angle` in rad, counter-clockwise.
void drawText(cairo_t* cr, double x, double y, const std::string& text, double size,
              TextAlign align = TextAlign::Left, double angle = 0);

}  // namespace sinew::render_detail

#include "cairo_canvas.hpp"

#include <ostream>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"

namespace sinew::render_detail {

Canvas::Canvas(int width, int height, const std::string& path)
    : surface_(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height)) {
    if (cairo_surface_status(surface_.get()) != CAIRO_STATUS_SUCCESS)
        throw Error(path + ": cairo cannot make a " + std::to_string(width) + " x " + std::to_string(height) +
                    " image: " + cairo_status_to_string(cairo_surface_status(surface_.get())));
    context_.reset(cairo_create(surface_.get()));
    cairo_set_source_rgb(get(), 1, 1, 1);
    cairo_paint(get());
    cairo_select_font_face(get(), "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
}

void Canvas::writePng(const std::string& path) const {
    if (cairo_status(get()) != CAIRO_STATUS_SUCCESS)
        throw Error(path + ": drawing failed: " + cairo_status_to_string(cairo_status(get())));
    cairo_surface_flush(surface_.get());
    OutputFileSet files;
    std::ostream& out = files.open(path);
    const cairo_status_t status = cairo_surface_write_to_png_stream(
        surface_.get(),
        [](void* stream, const unsigned char* data, unsigned int length) {
            static_cast<std::ostream*>(stream)->write(reinterpret_cast<const char*>(data), length);
            return static_cast<std::ostream*>(stream)->good() ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
        },
        &out);
    if (status != CAIRO_STATUS_SUCCESS) throw Error(path + ": cannot write the PNG: " + cairo_status_to_string(status));
    files.commit();
}

void setColour(cairo_t* cr, const Rgb& c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

void drawText(cairo_t* cr, double x, double y, const std::string& text, double size, TextAlign align, double angle) {
    cairo_save(cr);
    cairo_set_font_size(cr, size);
    cairo_text_extents_t extents;
    cairo_text_extents(cr, text.c_str(), &extents);
    cairo_translate(cr, x, y);
    cairo_rotate(cr, -angle);
    const double shift = align == TextAlign::Left ? 0 : align == TextAlign::Centre ? extents.x_advance / 2 : extents.x_advance;
    cairo_move_to(cr, -shift, 0);
    cairo_show_text(cr, text.c_str());
    cairo_restore(cr);
}

}  // namespace sinew::render_detail

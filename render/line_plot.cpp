#include "sinew/render/line_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "cairo_canvas.hpp"
#include "sinew/core/error.hpp"

namespace sinew {
namespace {

using render_detail::drawText;
using render_detail::setColour;
using render_detail::TextAlign;

constexpr double kLeft = 84, kRight = 230, kTop = 42, kBottom = 58;  // px around the axes' box
constexpr Rgb kInk{0.15, 0.15, 0.15}, kGrid{0.88, 0.88, 0.88};
// matplotlib's tab10.
constexpr Rgb kTab10[10] = {{0.122, 0.467, 0.706}, {1.000, 0.498, 0.055}, {0.173, 0.627, 0.173}, {0.839, 0.153, 0.157},
                            {0.580, 0.404, 0.741}, {0.549, 0.337, 0.294}, {0.890, 0.467, 0.761}, {0.498, 0.498, 0.498},
                            {0.737, 0.741, 0.133}, {0.090, 0.745, 0.812}};

bool isPlotted(double x, double y, const LinePlotOptions& o) {
    return std::isfinite(x) && std::isfinite(y) && (!o.logX || x > 0) && (!o.logY || y > 0);
}

// The axis range: padded by 4% of the span (a flat series by 10% of its value, at least 1 either way), on a
// log axis by 4% of the decades spanned (at least one).
void fitRange(double low, double high, bool log, double& min, double& max) {
    if (log) {
        const double lo = std::log10(low), hi = std::log10(high), pad = 0.04 * std::max(hi - lo, 1.0);
        min = std::pow(10.0, lo - pad);
        max = std::pow(10.0, hi + pad);
        return;
    }
    if (high - low <= 0) {
        const double pad = std::max(std::abs(low) * 0.1, 1.0);
        low -= pad;
        high += pad;
    }
    const double pad = 0.04 * (high - low);
    min = low - pad;
    max = high + pad;
}

// Tick values: 1, 2 or 5 times a power of ten apart, four to ten of them; on a log axis the decades inside
// the range, or its ends where it holds none.
std::vector<double> calcTicks(double min, double max, bool log) {
    std::vector<double> ticks;
    if (log) {
        for (double e = std::ceil(std::log10(min)); e <= std::floor(std::log10(max)); ++e) ticks.push_back(std::pow(10.0, e));
        if (ticks.empty()) ticks = {min, max};
        return ticks;
    }
    const double raw = (max - min) / 6;
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    const double step = raw / power < 1.5 ? power : raw / power < 3.5 ? 2 * power : raw / power < 7.5 ? 5 * power : 10 * power;
    for (double t = std::ceil(min / step) * step; t <= max + 1e-9 * step; t += step)
        ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
    return ticks;
}

std::string formatTick(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

}  // namespace

Eigen::Vector2d PlotAxes::toPixel(double x, double y) const {
    auto fraction = [](double v, double lo, double hi, bool log) {
        return log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    };
    return {left + width * fraction(x, xMin, xMax, logX), top + height * (1 - fraction(y, yMin, yMax, logY))};
}

Rgb getSeriesColour(int i) { return kTab10[i % 10]; }

PlotAxes layoutLinePlot(const std::vector<PlotSeries>& series, const LinePlotOptions& options) {
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    for (const PlotSeries& s : series) {
        if (s.x.size() != s.y.size()) throw Error("plot series '" + s.label + "': x and y differ in length");
        for (std::size_t i = 0; i < s.x.size(); ++i)
            if (isPlotted(s.x[i], s.y[i], options)) {
                x0 = std::min(x0, s.x[i]);
                x1 = std::max(x1, s.x[i]);
                y0 = std::min(y0, s.y[i]);
                y1 = std::max(y1, s.y[i]);
            }
    }
    if (!(x0 <= x1)) throw Error("nothing to plot: no finite sample" + std::string(options.logX || options.logY ? " > 0 on the log axes" : ""));
    if (options.width < kLeft + kRight + 100 || options.height < kTop + kBottom + 100)
        throw Error("the plot is too small: at least " + formatTick(kLeft + kRight + 100) + " x " +
                    formatTick(kTop + kBottom + 100) + " px");
    PlotAxes axes;
    axes.left = kLeft;
    axes.top = kTop;
    axes.width = options.width - kLeft - kRight;
    axes.height = options.height - kTop - kBottom;
    axes.logX = options.logX;
    axes.logY = options.logY;
    fitRange(x0, x1, options.logX, axes.xMin, axes.xMax);
    fitRange(y0, y1, options.logY, axes.yMin, axes.yMax);
    return axes;
}

void writeLinePlotPng(const std::vector<PlotSeries>& series, const PlotAxes& axes, const LinePlotOptions& options,
                      const std::string& path) {
    render_detail::Canvas canvas(options.width, options.height, path);
    cairo_t* cr = canvas.get();
    const double right = axes.left + axes.width, bottom = axes.top + axes.height;
    // Grid and ticks.
    cairo_set_line_width(cr, 1);
    for (const double t : calcTicks(axes.xMin, axes.xMax, axes.logX)) {
        const double x = std::round(axes.toPixel(t, axes.yMin).x()) + 0.5;
        setColour(cr, kGrid);
        cairo_move_to(cr, x, axes.top);
        cairo_line_to(cr, x, bottom);
        cairo_stroke(cr);
        setColour(cr, kInk);
        cairo_move_to(cr, x, bottom);
        cairo_line_to(cr, x, bottom + 5);
        cairo_stroke(cr);
        drawText(cr, x, bottom + 19, formatTick(t), 12, TextAlign::Centre);
    }
    for (const double t : calcTicks(axes.yMin, axes.yMax, axes.logY)) {
        const double y = std::round(axes.toPixel(axes.xMin, t).y()) + 0.5;
        setColour(cr, kGrid);
        cairo_move_to(cr, axes.left, y);
        cairo_line_to(cr, right, y);
        cairo_stroke(cr);
        setColour(cr, kInk);
        cairo_move_to(cr, axes.left - 5, y);
        cairo_line_to(cr, axes.left, y);
        cairo_stroke(cr);
        drawText(cr, axes.left - 8, y + 4, formatTick(t), 12, TextAlign::Right);
    }
    // The series, clipped to the box.
    cairo_save(cr);
    cairo_rectangle(cr, axes.left, axes.top, axes.width, axes.height);
    cairo_clip(cr);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_width(cr, 1.8);
    for (std::size_t k = 0; k < series.size(); ++k) {
        const PlotSeries& s = series[k];
        const double dashes[] = {6, 3};
        cairo_set_dash(cr, dashes, k >= 10 ? 2 : 0, 0);
        setColour(cr, getSeriesColour(static_cast<int>(k)));
        bool drawing = false;
        for (std::size_t i = 0; i < s.x.size(); ++i) {
            if (!isPlotted(s.x[i], s.y[i], options)) {
                drawing = false;
                continue;
            }
            const Eigen::Vector2d p = axes.toPixel(s.x[i], s.y[i]);
            drawing ? cairo_line_to(cr, p.x(), p.y()) : cairo_move_to(cr, p.x(), p.y());
            drawing = true;
        }
        cairo_stroke(cr);
        if (options.markers)
            for (std::size_t i = 0; i < s.x.size(); ++i)
                if (isPlotted(s.x[i], s.y[i], options)) {
                    const Eigen::Vector2d p = axes.toPixel(s.x[i], s.y[i]);
                    cairo_arc(cr, p.x(), p.y(), 3.2, 0, 2 * M_PI);
                    cairo_fill(cr);
                }
    }
    cairo_restore(cr);
    // The box, labels, title and legend.
    setColour(cr, kInk);
    cairo_set_dash(cr, nullptr, 0, 0);
    // One pixel wide on pixel centres, so the box is crisp.
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, std::round(axes.left) + 0.5, std::round(axes.top) + 0.5, std::round(axes.width),
                    std::round(axes.height));
    cairo_stroke(cr);
    drawText(cr, axes.left + axes.width / 2, options.height - 14, options.xLabel, 13, TextAlign::Centre);
    drawText(cr, 20, axes.top + axes.height / 2, options.yLabel, 13, TextAlign::Centre, M_PI / 2);
    drawText(cr, axes.left, 26, options.title, 15);
    const int room = static_cast<int>(axes.height / 17);
    const int shown = static_cast<int>(series.size()) <= room ? static_cast<int>(series.size()) : room - 1;
    for (int k = 0; k < shown; ++k) {
        const double y = axes.top + 10 + 17 * k;
        const double dashes[] = {6, 3};
        cairo_set_dash(cr, dashes, k >= 10 ? 2 : 0, 0);
        setColour(cr, getSeriesColour(k));
        cairo_set_line_width(cr, 2);
        cairo_move_to(cr, right + 12, y - 4);
        cairo_line_to(cr, right + 36, y - 4);
        cairo_stroke(cr);
        setColour(cr, kInk);
        drawText(cr, right + 42, y, series[static_cast<std::size_t>(k)].label, 11);
    }
    if (shown < static_cast<int>(series.size()))
        drawText(cr, right + 12, axes.top + 10 + 17 * shown, "... and " + std::to_string(series.size() - shown) + " more", 11);
    canvas.writePng(path);
}

}  // namespace sinew

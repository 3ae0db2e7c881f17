#pragma once
// Line plots as PNG, drawn with cairo: series of (x, y) samples on linear or logarithmic axes, with ticks, a
// grid and a legend (docs/rendering.md). `sinew plot` draws storage columns over time and benchmark scaling
// curves with it.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sinew/render/colour_map.hpp"

namespace sinew {

struct PlotSeries {
    std::string label;
    std::vector<double> x, y;  // same length; a NaN sample breaks the line
};

struct LinePlotOptions {
    std::string title, xLabel, yLabel;
    bool logX = false, logY = false;  // logarithmic axes need positive values; others are left out
    bool markers = false;             // a dot at every sample
    int width = 960, height = 560;    // px
};

// Where the data go: the axes' box in pixels and the data range it spans.
struct PlotAxes {
    double left = 0, top = 0, width = 0, height = 0;  // px
    double xMin = 0, xMax = 1, yMin = 0, yMax = 1;    // data units (for log axes, the values, not their logs)
    bool logX = false, logY = false;
    Eigen::Vector2d toPixel(double x, double y) const;
};

// The colour of series i: matplotlib's tab10 cycle; from the eleventh series on the cycle repeats dashed.
Rgb getSeriesColour(int i);

// The axes for the series: their range, padded by 4% (on log axes, of the decades spanned).
// Throws sinew::Error when there is nothing to plot.
PlotAxes layoutLinePlot(const std::vector<PlotSeries>& series, const LinePlotOptions& options);

// Writes the plot at `path` (complete or not at all, as writePicturePng); errors name the path.
void writeLinePlotPng(const std::vector<PlotSeries>& series, const PlotAxes& axes, const LinePlotOptions& options,
                      const std::string& path);

}  // namespace sinew

// Plots read back from their PNG files: the axes' box drawn, and each curve's colour (matplotlib's tab10) at
// the pixel the axes map a known sample to; the series read from storage and benchmark files against the
// values written into them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "png_pixels.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/render/line_plot.hpp"
#include "sinew/render/plot_series.hpp"

namespace sinew {
namespace {

const Rgb kTabBlue{31 / 255.0, 119 / 255.0, 180 / 255.0}, kTabOrange{1.0, 127 / 255.0, 14 / 255.0};

std::string testPath(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sinew_test_line_plot";
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

// a = 2 t and b = 1 - t at t = 0, 0.1, ..., 1, and a column c that is not plotted.
std::string writeLines() {
    StorageTable table{"lines", false, {"a", "b", "c"}, {}, {}};
    for (int i = 0; i <= 10; ++i) {
        const double t = i / 10.0;
        table.times.push_back(t);
        table.rows.push_back({2 * t, 1 - t, 7.0});
    }
    const std::string path = testPath("lines.sto");
    writeStorageFile(table, path);
    return path;
}

TEST(LinePlot, StorageCurvesPassThroughTheirSamples) {
    const std::string path = writeLines();
    const std::vector<PlotSeries> series = readStorageSeries(path, {"a", "b"}, "");
    ASSERT_EQ(series.size(), 2u);
    EXPECT_EQ(series[0].label, "a");
    EXPECT_EQ(series[1].y[4], 1 - 0.4);
    LinePlotOptions options;
    options.xLabel = "time (s)";
    const PlotAxes axes = layoutLinePlot(series, options);
    const std::string png = testPath("lines.png");
    writeLinePlotPng(series, axes, options, png);
    const test::PngPixels pixels(png);
    EXPECT_EQ(pixels.width, options.width);
    EXPECT_EQ(pixels.height, options.height);
    // The box: its left edge inked all the way down, from the top to the bottom of the axes.
    int inked = 0;
    for (int y = static_cast<int>(axes.top) + 2; y < static_cast<int>(axes.top + axes.height) - 2; ++y)
        inked += pixels.findNearestColour(axes.left, y, {0.15, 0.15, 0.15}, 1) < 0.2;
    EXPECT_GE(inked, static_cast<int>(axes.height) - 6);
    // (0.5, 1.0) and (0.7, 0.3) are samples of a and b; (0.5, 0.8) is on neither.
    const Eigen::Vector2d a = axes.toPixel(0.5, 1.0), b = axes.toPixel(0.7, 0.3), none = axes.toPixel(0.5, 0.8);
    EXPECT_LT(pixels.findNearestColour(a.x(), a.y(), kTabBlue, 1), 0.03);
    EXPECT_LT(pixels.findNearestColour(b.x(), b.y(), kTabOrange, 1), 0.03);
    EXPECT_GT(pixels.findNearestColour(none.x(), none.y(), kTabBlue, 1), 0.3);
}

TEST(LinePlot, MissingColumnNamesFileAndColumn) {
    const std::string path = writeLines();
    try {
        readStorageSeries(path, {"a", "zz"}, "");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("missing 'zz'"), std::string::npos) << e.what();
    }
}

// Google Benchmark JSON as it is written: repetitions, aggregates (whose counters may be NaN), a skipped run.
std::string writeBenchmarks() {
    const std::string path = testPath("benchmarks.json");
    std::ofstream(path) << R"({"context": {}, "benchmarks": [
 {"name": "FD/sinew/chain10", "run_type": "iteration", "cpu_time": 1000, "time_unit": "ns", "links": 10},
 {"name": "FD/sinew/chain10", "run_type": "iteration", "cpu_time": 900, "time_unit": "ns", "links": 10},
 {"name": "FD/sinew/chain100", "run_type": "iteration", "cpu_time": 10, "time_unit": "us", "links": 100},
 {"name": "FD/sinew/chain100_mean", "run_name": "FD/sinew/chain100", "run_type": "aggregate", "cpu_time": 50, "time_unit": "us"},
 {"name": "FD/sinew/chain100_cv", "run_name": "FD/sinew/chain100", "run_type": "aggregate", "cpu_time": 0.01, "time_unit": "us", "allocations": NaN, "max": -Infinity},
 {"name": "FD/simbody/tree40_loops", "run_type": "iteration", "cpu_time": 0.2, "time_unit": "ms"},
 {"name": "FD/simbody/tree80_loops", "run_type": "iteration", "cpu_time": 0.5, "time_unit": "ms"},
 {"name": "FD/simbody/wholebody", "run_type": "iteration", "cpu_time": 0.2, "time_unit": "ms", "links": 100},
 {"name": "FD/simbody/tree99_loops", "error_occurred": true, "error_message": "skipped"}
]})";
    return path;
}

TEST(LinePlot, BenchmarkScalingCurves) {
    const std::string path = writeBenchmarks();
    const std::vector<PlotSeries> series = readBenchmarkScaling(path, "");
    ASSERT_EQ(series.size(), 2u);
    EXPECT_EQ(series[0].label, "FD/simbody/tree_loops");
    EXPECT_EQ(series[0].x, (std::vector<double>{40, 80}));  // sizes from the names
    EXPECT_EQ(series[0].y, (std::vector<double>{200, 500}));
    EXPECT_EQ(series[1].label, "FD/sinew/chain");
    EXPECT_EQ(series[1].x, (std::vector<double>{10, 100}));  // the links counters
    EXPECT_NEAR(series[1].y[0], 0.9, 1e-12);                // the fastest repetition, in us
    EXPECT_EQ(series[1].y[1], 10);
    EXPECT_EQ(readBenchmarkScaling(path, "sinew").size(), 1u);

    LinePlotOptions options;
    options.logX = options.logY = options.markers = true;
    const PlotAxes axes = layoutLinePlot(series, options);
    const std::string png = testPath("benchmarks.png");
    writeLinePlotPng(series, axes, options, png);
    const test::PngPixels pixels(png);
    // On log-log axes the line from (10, 0.9) to (100, 10) passes (sqrt(1000), sqrt(9)).
    const Eigen::Vector2d mid = axes.toPixel(std::sqrt(1000.0), 3.0);
    EXPECT_LT(pixels.findNearestColour(mid.x(), mid.y(), kTabOrange, 1), 0.03);
    const Eigen::Vector2d tree = axes.toPixel(40, 200);
    EXPECT_LT(pixels.findNearestColour(tree.x(), tree.y(), kTabBlue, 1), 0.03);
}

TEST(LinePlot, NotJsonNamesTheFile) {
    const std::string path = testPath("broken.json");
    std::ofstream(path) << "{\"benchmarks\": [";
    try {
        readBenchmarkScaling(path, "");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind(path + ": not JSON", 0), 0u) << e.what();
    }
}

}  // namespace
}  // namespace sinew

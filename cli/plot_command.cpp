#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>

#include "arguments.hpp"
#include "commands.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/render/line_plot.hpp"
#include "sinew/render/plot_series.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew plot FILE.sto [FILE.sto ...] [--columns A,B,...] [options] -o OUT.png\n"
    "       sinew plot --benchmark RESULTS.json [--filter REGEX] [options] -o OUT.png\n"
    "  Line plots as PNG (docs/rendering.md). Storage files: the chosen columns (all, up to 20, by default)\n"
    "  against time, several files in one plot. Benchmark JSON (Google Benchmark's --benchmark_out): the\n"
    "  scaling curves, CPU time per iteration against size (the `links` counter, else the number in the\n"
    "  benchmark's name), fastest repetition, log-log.\n"
    "  --columns A,B     the storage columns to plot\n"
    "  --filter REGEX    only the benchmarks whose names match\n"
    "  --title T         the plot's title (default: the file names)\n"
    "  --ylabel L        the y axis' label\n"
    "  --log-y           a logarithmic y axis (storage plots)\n"
    "  --size WxH        the image, px (default 960x560)\n"
    "  -o OUT.png        the plot\n";

// Storage files with more columns than this need --columns: a legend of hundreds says nothing.
constexpr std::size_t kMaxDefaultColumns = 20;

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items;
    std::stringstream stream(text);
    for (std::string item; std::getline(stream, item, ',');)
        if (!item.empty()) items.push_back(item);
    return items;
}

}  // namespace

int runPlot(const std::vector<std::string>& args) {
    std::string benchmarkPath, filter, outputPath, title, yLabel, first, columnsText, size;
    std::vector<std::string> storagePaths;
    LinePlotOptions options;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("--benchmark")) benchmarkPath = reader.value();
        else if (reader.is("--filter")) filter = reader.value();
        else if (reader.is("--columns")) columnsText = reader.value();
        else if (reader.is("--title")) title = reader.value();
        else if (reader.is("--ylabel")) yLabel = reader.value();
        else if (reader.is("--log-y")) options.logY = true;
        else if (reader.is("--size")) size = reader.value();
        else if (reader.is("-o", "--output")) outputPath = reader.value();
        else {
            first.clear();
            reader.takePositional({&first});
            storagePaths.push_back(first);
        }
    }
    if (reader.helpShown()) return 0;
    if (outputPath.empty() || (benchmarkPath.empty() == storagePaths.empty())) return reader.failWithUsage();
    if (std::filesystem::path(outputPath).extension() != ".png") throw Error("-o " + outputPath + ": the output must be a .png file");
    if (!size.empty()) {
        int width = 0, height = 0;
        char tail = 0;
        if (std::sscanf(size.c_str(), "%dx%d%c", &width, &height, &tail) != 2)
            throw Error("--size expects WIDTHxHEIGHT in px, got '" + size + "'");
        options.width = width;
        options.height = height;
    }

    std::vector<PlotSeries> series;
    if (!benchmarkPath.empty()) {
        series = readBenchmarkScaling(benchmarkPath, filter);
        if (series.empty())
            throw Error(benchmarkPath + ": no benchmark with a size in its name" +
                        (filter.empty() ? std::string() : " matching '" + filter + "'"));
        options.logX = options.logY = options.markers = true;
        options.xLabel = "size (links)";
        options.yLabel = yLabel.empty() ? "CPU time per iteration (us)" : yLabel;
        options.title = title.empty() ? std::filesystem::path(benchmarkPath).filename().string() +
                                            (filter.empty() ? "" : " (" + filter + ")")
                                      : title;
    } else {
        // With several files, each column is taken from the files that have it; each must be in one.
        const std::vector<std::string> columns = splitList(columnsText);
        std::vector<bool> found(columns.size(), false);
        for (const std::string& path : storagePaths) {
            const StorageTable table = readStorageFile(path, NonFinite::Allow);
            std::vector<std::string> here;
            for (std::size_t c = 0; c < columns.size(); ++c)
                if (storagePaths.size() == 1 ||
                    std::find(table.columns.begin(), table.columns.end(), columns[c]) != table.columns.end()) {
                    here.push_back(columns[c]);
                    found[c] = true;
                }
            if (columns.empty() && table.columns.size() > kMaxDefaultColumns)
                throw Error(path + " has " + std::to_string(table.columns.size()) + " columns; choose up to " +
                            std::to_string(kMaxDefaultColumns) + " with --columns A,B,...");
            if (!columns.empty() && here.empty()) continue;
            const std::string prefix = storagePaths.size() > 1 ? std::filesystem::path(path).stem().string() + ": " : "";
            for (PlotSeries& s : readStorageSeries(path, here, prefix)) series.push_back(std::move(s));
            options.title += (options.title.empty() ? "" : ", ") + std::filesystem::path(path).filename().string();
        }
        for (std::size_t c = 0; c < columns.size(); ++c)
            if (!found[c]) throw Error("--columns: no file has a column '" + columns[c] + "'");
        if (!title.empty()) options.title = title;
        options.xLabel = "time (s)";
        options.yLabel = yLabel;
    }
    const PlotAxes axes = layoutLinePlot(series, options);
    const std::filesystem::path parent = std::filesystem::path(outputPath).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    writeLinePlotPng(series, axes, options, outputPath);
    std::printf("%s: %zu curve%s\n", outputPath.c_str(), series.size(), series.size() == 1 ? "" : "s");
    return 0;
}

}  // namespace sinew::cli

#include "sinew/render/plot_series.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>

#include "sinew/core/error.hpp"
#include "sinew/io/storage_file.hpp"

namespace sinew {
namespace {

// Google Benchmark's time units, in us.
double toMicroseconds(const std::string& unit, const std::string& path, const std::string& name) {
    if (unit == "ns") return 1e-3;
    if (unit == "us") return 1.0;
    if (unit == "ms") return 1e3;
    if (unit == "s") return 1e6;
    throw Error(path + ": benchmark '" + name + "': unknown time_unit '" + unit + "'");
}

}  // namespace

std::vector<PlotSeries> readStorageSeries(const std::string& path, const std::vector<std::string>& columns,
                                          const std::string& prefix) {
    const StorageTable table = readStorageFile(path, NonFinite::Allow);
    const std::vector<std::string>& names = columns.empty() ? table.columns : columns;
    const std::vector<int> columnOf = matchStorageColumns(table, names, ExtraColumns::Allow);
    std::vector<PlotSeries> series;
    for (std::size_t c = 0; c < names.size(); ++c) {
        PlotSeries s{prefix.empty() ? names[c] : prefix + names[c], table.times, {}};
        for (const std::vector<double>& row : table.rows) s.y.push_back(row[static_cast<std::size_t>(columnOf[c])]);
        series.push_back(std::move(s));
    }
    return series;
}

std::vector<PlotSeries> readBenchmarkScaling(const std::string& path, const std::string& filter) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open");
    // Google Benchmark writes a counter's coefficient of variation over equal repetitions (0 / 0) as NaN,
    // which JSON has no word for; such values (aggregates', which are skipped) are read as null.
    static const std::regex nonFinite(R"(:(\s*)-?(NaN|Infinity)\b)");
    const std::string text =
        std::regex_replace(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()), nonFinite, ":$1null");
    nlohmann::json document;
    try {
        document = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path + ": not JSON: " + e.what());
    }
    if (!document.contains("benchmarks") || !document["benchmarks"].is_array())
        throw Error(path + ": no \"benchmarks\" array (not Google Benchmark JSON output)");
    std::regex wanted;
    try {
        wanted = std::regex(filter);
    } catch (const std::regex_error& e) {
        throw Error("--filter '" + filter + "': not a regular expression: " + e.what());
    }
    // The last part of a name, split round its size: prefix, digits, suffix.
    static const std::regex sized(R"(^(.*?)(\d+)([^/\d]*)$)");
    std::map<std::string, std::map<double, double>> curves;  // curve -> size -> fastest us
    for (const nlohmann::json& run : document["benchmarks"]) {
        const std::string name = run.value("run_name", run.value("name", std::string()));
        if (run.value("run_type", std::string()) == "aggregate" || run.value("error_occurred", false)) continue;
        if (!filter.empty() && !std::regex_search(name, wanted)) continue;
        std::smatch match;
        if (!std::regex_match(name, match, sized) || !run.contains("cpu_time")) continue;
        const double size = run.contains("links") ? run["links"].get<double>() : std::stod(match[2].str());
        const double us = run["cpu_time"].get<double>() * toMicroseconds(run.value("time_unit", std::string("ns")), path, name);
        std::map<double, double>& curve = curves[match[1].str() + match[3].str()];
        const auto found = curve.find(size);
        curve[size] = found == curve.end() ? us : std::min(found->second, us);
    }
    std::vector<PlotSeries> series;
    for (const auto& [label, points] : curves) {
        PlotSeries s{label, {}, {}};
        for (const auto& [size, us] : points) {
            s.x.push_back(size);
            s.y.push_back(us);
        }
        series.push_back(std::move(s));
    }
    return series;
}

}  // namespace sinew

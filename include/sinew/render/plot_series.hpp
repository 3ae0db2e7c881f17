#pragma once
// What `sinew plot` draws, read from files: storage (.sto/.mot) columns over time, and Google Benchmark
// results (JSON) as scaling curves, time per iteration against model size.
#include <string>
#include <vector>

#include "sinew/render/line_plot.hpp"

namespace sinew {

// The named columns of a storage file against time (all columns when `columns` is empty); a series'
// label is the column, prefixed by `prefix` where it is not empty. Errors name the file and the columns
// that are not there.
std::vector<PlotSeries> readStorageSeries(const std::string& path, const std::vector<std::string>& columns,
                                          const std::string& prefix);

// Google Benchmark results as curves: a benchmark named `A/B/name123suffix` is the point (123, CPU time per
// iteration in us) of the curve `A/B/name suffix`, or (its `links` counter, ...) where it has one; the
// fastest repetition counts, aggregates and errored runs are left out, and so are names without a size and
// names that do not contain `filter` (empty: all). Curves sorted by size. Errors name the file.
std::vector<PlotSeries> readBenchmarkScaling(const std::string& path, const std::string& filter);

}  // namespace sinew

#pragma once
// Per-frame clocks for the benchmarks that report frame-time statistics besides Google Benchmark's mean.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <numeric>
#include <vector>

namespace sinew {

inline double wallMilliseconds() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// This thread's CPU time: on the shared machine it leaves out the time the thread was preempted, which
// dominates the tail of the wall-clock frame times.
inline double cpuMilliseconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// The median of a run's frame times (of an even count, the upper middle one); `values` not empty.
inline double medianOf(std::vector<double> values) {
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
    return values[values.size() / 2];
}

// Their mean, which the few slow frames (a curvature refresh, an infeasible frame's phase 1) raise above the
// median; `values` not empty.
inline double meanOf(const std::vector<double>& values) {
    return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

}  // namespace sinew

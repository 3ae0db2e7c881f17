#pragma once
// Per-frame clocks for the benchmarks that report frame-time statistics besides Google Benchmark's mean.
#include <chrono>
#include <ctime>

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

}  // namespace sinew

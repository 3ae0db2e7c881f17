#include "progress.hpp"

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace sinew::cli {

Progress::Progress(std::string label, double total)
    : label_(std::move(label)), total_(total), terminal_(isatty(fileno(stderr)) != 0) {}

void Progress::update(double done) {
    const int percent = total_ > 0 ? static_cast<int>(std::clamp(100.0 * done / total_, 0.0, 100.0)) : 100;
    const int step = terminal_ ? 1 : 10;
    if (percent / step == lastShown_ / step && lastShown_ >= 0) return;
    lastShown_ = percent;
    if (terminal_) {
        const int width = 30, filled = percent * width / 100;
        std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label_.c_str(), filled, "##############################",
                     width - filled, "", percent);
    } else {
        std::fprintf(stderr, "%s %d%%\n", label_.c_str(), percent);
    }
    std::fflush(stderr);
}

void Progress::finish() {
    update(total_);
    if (terminal_) std::fprintf(stderr, "\n");
}

}  // namespace sinew::cli

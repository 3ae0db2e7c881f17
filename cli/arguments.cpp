#include "arguments.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "sinew/core/error.hpp"

namespace sinew::cli {

double parseNumber(const std::string& option, const std::string& text) {
    try {
        std::size_t used = 0;
        const double value = std::stod(text, &used);
        if (used == text.size() && std::isfinite(value)) return value;
    } catch (const std::exception&) {
    }
    throw Error(option + " expects a finite number, got '" + text + "'");
}

void checkLowpassOption(double cutoffHz, const StorageTable& motion, const std::string& motionPath) {
    if (cutoffHz < 0) return;
    if (cutoffHz == 0) throw Error("--lowpass expects a cut-off > 0 Hz (leave it out for no filtering)");
    double smallestStep = std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i < motion.times.size(); ++i)
        smallestStep = std::min(smallestStep, motion.times[i] - motion.times[i - 1]);
    const double nyquist = 0.5 / smallestStep;
    if (cutoffHz >= nyquist) {
        char text[160];
        std::snprintf(text, sizeof text, "--lowpass %g Hz is at or above the Nyquist frequency %g Hz of ", cutoffHz,
                      nyquist);
        throw Error(text + motionPath + " (half its sampling rate, from its smallest time step)");
    }
}

bool ArgumentReader::next() {
    if (started_) ++i_;
    started_ = true;
    if (i_ >= args_.size()) return false;
    if (is("--help", "-h")) {
        std::fputs(usage_, stdout);
        helpShown_ = true;
        return false;
    }
    return true;
}

double ArgumentReader::number() {
    // The option's name before value() moves past it.
    const std::string option = args_[i_];
    return parseNumber(option, value());
}

const std::string& ArgumentReader::value() {
    if (i_ + 1 >= args_.size()) throw Error(args_[i_] + " needs a value");
    return args_[++i_];
}

void ArgumentReader::takePositional(std::initializer_list<std::string*> slots) {
    const std::string& arg = args_[i_];
    if (!arg.empty() && arg[0] == '-') throw Error("unknown option '" + arg + "'\n" + usage_);
    for (std::string* slot : slots)
        if (slot->empty()) {
            *slot = arg;
            return;
        }
    throw Error("unexpected argument '" + arg + "'");
}

int ArgumentReader::failWithUsage() const {
    std::fputs(usage_, stderr);
    return 2;
}

}  // namespace sinew::cli

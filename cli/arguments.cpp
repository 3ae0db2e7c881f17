#include "arguments.hpp"

#include <cstdio>

#include "sinew/core/error.hpp"

namespace sinew::cli {

double parseNumber(const std::string& option, const std::string& text) {
    try {
        std::size_t used = 0;
        const double value = std::stod(text, &used);
        if (used == text.size()) return value;
    } catch (const std::exception&) {
    }
    throw Error(option + " expects a number, got '" + text + "'");
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

#include "number_text.hpp"

#include <charconv>
#include <cstdlib>
#include <string>

namespace sinew {

std::optional<double> parseNumber(std::string_view text) {
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc() && end == text.data() + text.size()) return value;
    // What from_chars leaves (a '+', hexadecimal, a magnitude it calls out of range) goes to strtod, which
    // also takes subnormals, unlike stod.
    const std::string copy(text);
    char* strtodEnd = nullptr;
    value = std::strtod(copy.c_str(), &strtodEnd);
    if (copy.empty() || strtodEnd != copy.c_str() + copy.size()) return std::nullopt;
    return value;
}

}  // namespace sinew

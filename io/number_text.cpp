#include "number_text.hpp"

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace sinew {
namespace {

// Clinger's fast path (Proc. PLDI 1990): a decimal of at most 19 digits whose digits, as an integer, are at
// most 2^53, with a power of ten up to 10^22, is one exact integer and one exact power, so one
// multiplication or division rounds it correctly: to the double from_chars returns. Most numbers in motion
// and model files are of this kind ("745.4661142", "-0.0075", "1e-3"). Anything else (more digits, larger
// exponents, other spellings) is left to from_chars and strtod. The digits are read in one tight loop per
// part, about half of from_chars' instructions on a force-plate file.
std::optional<double> parseShortDecimal(std::string_view text) {
    static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                              1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const char* p = text.data();
    const char* const end = p + text.size();
    const bool negative = p != end && *p == '-';
    if (negative) ++p;
    std::uint64_t digits = 0;
    auto isDigit = [](char c) { return static_cast<unsigned>(c - '0') < 10; };
    const char* const integerStart = p;
    while (p != end && isDigit(*p)) digits = digits * 10 + static_cast<std::uint64_t>(*p++ - '0');
    std::ptrdiff_t digitCount = p - integerStart, fractionDigits = 0;
    if (p != end && *p == '.') {
        const char* const fractionStart = ++p;
        while (p != end && isDigit(*p)) digits = digits * 10 + static_cast<std::uint64_t>(*p++ - '0');
        fractionDigits = p - fractionStart;
        digitCount += fractionDigits;
    }
    // More than 19 digits may have wrapped around.
    if (digitCount == 0 || digitCount > 19) return std::nullopt;
    std::ptrdiff_t exponent = -fractionDigits;
    if (p != end && (*p == 'e' || *p == 'E')) {
        ++p;
        const bool negativeExponent = p != end && *p == '-';
        if (p != end && (*p == '-' || *p == '+')) ++p;
        const char* const exponentStart = p;
        std::ptrdiff_t written = 0;
        while (p != end && isDigit(*p) && p - exponentStart < 4) written = written * 10 + (*p++ - '0');
        if (p == exponentStart) return std::nullopt;
        exponent += negativeExponent ? -written : written;
    }
    if (p != end || digits > (std::uint64_t{1} << 53) || exponent < -22 || exponent > 22) return std::nullopt;
    double value = static_cast<double>(digits);
    value = exponent < 0 ? value / kPowersOfTen[-exponent] : value * kPowersOfTen[exponent];
    return negative ? -value : value;
}

}  // namespace

std::optional<double> parseNumber(std::string_view text) {
    if (const std::optional<double> value = parseShortDecimal(text)) return value;
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

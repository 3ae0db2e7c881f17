#include "number_text.hpp"

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace sinew {
namespace {

// Clinger's fast path (Proc. PLDI 1990): a decimal with at most 2^53 as its digits and a power of ten up to
// 10^22 is one exact integer and one exact power, so a single multiplication or division rounds it
// correctly, to the double from_chars returns. Most numbers in motion and model files are of this kind
// ("745.4661142", "-0.0075", "1e-3"); anything else (more digits, larger exponents, other spellings) is
// left to from_chars and strtod.
std::optional<double> parseShortDecimal(std::string_view text) {
    static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                              1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    constexpr std::uint64_t kExactLimit = std::uint64_t{1} << 53;
    const char* p = text.data();
    const char* const end = p + text.size();
    const bool negative = p != end && *p == '-';
    if (negative) ++p;
    std::uint64_t digits = 0;
    int exponent = 0, digitCount = 0, significant = 0;
    auto readDigits = [&](bool fraction) {
        for (; p != end && *p >= '0' && *p <= '9'; ++p, ++digitCount) {
            if (digits == 0 && *p == '0') {  // leading zeros carry no digits
                if (fraction) --exponent;
                continue;
            }
            if (++significant > 19) return false;
            digits = digits * 10 + static_cast<std::uint64_t>(*p - '0');
            if (fraction) --exponent;
        }
        return true;
    };
    if (!readDigits(false)) return std::nullopt;
    if (p != end && *p == '.') {
        ++p;
        if (!readDigits(true)) return std::nullopt;
    }
    if (digitCount == 0) return std::nullopt;
    if (p != end && (*p == 'e' || *p == 'E')) {
        ++p;
        const bool negativeExponent = p != end && *p == '-';
        if (p != end && (*p == '-' || *p == '+')) ++p;
        int written = 0, exponentDigits = 0;
        for (; p != end && *p >= '0' && *p <= '9'; ++p) {
            if (++exponentDigits > 4) return std::nullopt;
            written = written * 10 + (*p - '0');
        }
        if (exponentDigits == 0) return std::nullopt;
        exponent += negativeExponent ? -written : written;
    }
    if (p != end || digits > kExactLimit) return std::nullopt;
    if (digits == 0) return negative ? -0.0 : 0.0;
    if (exponent < -22 || exponent > 22) return std::nullopt;
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

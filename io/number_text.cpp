#include "number_text.hpp"

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

namespace sinew {
namespace {

// Eight digits at once (SWAR, as in Lemire's fast_float): a file's fractions are mostly 7 to 10 digits.
bool areEightDigits(const char* p) {
    std::uint64_t bytes;
    std::memcpy(&bytes, p, sizeof bytes);
    return ((bytes & 0xF0F0F0F0F0F0F0F0) | (((bytes + 0x0606060606060606) & 0xF0F0F0F0F0F0F0F0) >> 4)) ==
           0x3333333333333333;
}

std::uint64_t readEightDigits(const char* p) {
    std::uint64_t bytes;
    std::memcpy(&bytes, p, sizeof bytes);
    if constexpr (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__) bytes = __builtin_bswap64(bytes);
    bytes -= 0x3030303030303030;
    bytes = (bytes * 10) + (bytes >> 8);  // pairs of digits
    bytes = (((bytes & 0x000000FF000000FF) * (100 + (1000000ULL << 32))) +
             (((bytes >> 16) & 0x000000FF000000FF) * (1 + (10000ULL << 32)))) >> 32;
    return bytes;
}

}  // namespace

const char* readShortDecimal(const char* p, const char* const end, double& result) {
    static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                              1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const bool negative = p != end && *p == '-';
    if (negative) ++p;
    std::uint64_t digits = 0;
    auto isDigit = [](char c) { return static_cast<unsigned>(c - '0') < 10; };
    const char* const integerStart = p;
    while (p != end && isDigit(*p)) digits = digits * 10 + static_cast<std::uint64_t>(*p++ - '0');
    std::ptrdiff_t digitCount = p - integerStart, fractionDigits = 0;
    if (p != end && *p == '.') {
        const char* const fractionStart = ++p;
        if (end - p >= 8 && areEightDigits(p)) digits = digits * 100000000 + readEightDigits(p), p += 8;
        while (p != end && isDigit(*p)) digits = digits * 10 + static_cast<std::uint64_t>(*p++ - '0');
        fractionDigits = p - fractionStart;
        digitCount += fractionDigits;
    }
    // More than 19 digits may have wrapped around.
    if (digitCount == 0 || digitCount > 19) return nullptr;
    std::ptrdiff_t exponent = -fractionDigits;
    if (p != end && (*p == 'e' || *p == 'E')) {
        ++p;
        const bool negativeExponent = p != end && *p == '-';
        if (p != end && (*p == '-' || *p == '+')) ++p;
        const char* const exponentStart = p;
        std::ptrdiff_t written = 0;
        while (p != end && isDigit(*p) && p - exponentStart < 4) written = written * 10 + (*p++ - '0');
        if (p == exponentStart) return nullptr;
        exponent += negativeExponent ? -written : written;
    }
    if (digits > (std::uint64_t{1} << 53) || exponent < -22 || exponent > 22) return nullptr;
    double value = static_cast<double>(digits);
    value = exponent < 0 ? value / kPowersOfTen[-exponent] : value * kPowersOfTen[exponent];
    result = negative ? -value : value;
    return p;
}

std::optional<double> parseNumber(std::string_view text) {
    double value = 0;
    const char* const shortEnd = readShortDecimal(text.data(), text.data() + text.size(), value);
    if (shortEnd && shortEnd == text.data() + text.size()) return value;
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

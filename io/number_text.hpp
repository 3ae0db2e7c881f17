#pragma once
// Numbers in the text files sinew reads: one parser, so that every reader accepts the same spellings.
#include <optional>
#include <string_view>

namespace sinew {

// The number the whole of `text` spells, as strtod reads it (leading '+', hexadecimal, inf and nan
// included); none when `text` is empty or spells something else. std::from_chars reads the common forms,
// many times faster; strtod the rest.
std::optional<double> parseNumber(std::string_view text);

// Clinger's fast path (Proc. PLDI 1990): a decimal of at most 19 digits whose digits, as an integer, are at
// most 2^53, with a power of ten up to 10^22, is one exact integer and one exact power, so one
// multiplication or division rounds it correctly: to the double from_chars returns. Most numbers in motion
// and model files are of this kind ("745.4661142", "-0.0075", "1e-3"). The number of that kind that begins
// at p (before end) into `result`, returning where it ends; nullptr where none begins there, when the caller
// must read it with parseNumber (more digits, larger exponents, other spellings). The digits are read in
// one tight loop per part, about half of from_chars' instructions on a force-plate file.
const char* readShortDecimal(const char* p, const char* end, double& result);

}  // namespace sinew

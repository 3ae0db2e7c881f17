#pragma once
// Numbers in the text files sinew reads: one parser, so that every reader accepts the same spellings.
#include <optional>
#include <string_view>

namespace sinew {

// The number the whole of `text` spells, as strtod reads it (leading '+', hexadecimal, inf and nan
// included); none when `text` is empty or spells something else. std::from_chars reads the common forms,
// many times faster; strtod the rest.
std::optional<double> parseNumber(std::string_view text);

}  // namespace sinew

// libFuzzer harness: the TRC marker-table reader.
#include <cstdint>

#include "fuzz_input.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/trc_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = sinew::fuzz::writeInput(data, size, ".trc");
    try {
        sinew::readTrcFile(path);
    } catch (const sinew::Error&) {
    }
    return 0;
}

// libFuzzer harness: the MuJoCo MJCF reader and converter.
#include <cstdint>

#include "fuzz_input.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/mjcf_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = sinew::fuzz::writeInput(data, size, ".xml");
    try {
        sinew::readMjcfModel(path);
    } catch (const sinew::Error&) {
    }
    return 0;
}

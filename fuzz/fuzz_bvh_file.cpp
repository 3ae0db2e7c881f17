// libFuzzer harness: the BVH motion-capture reader.
#include <cstdint>

#include "fuzz_input.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/bvh_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = sinew::fuzz::writeInput(data, size, ".bvh");
    try {
        sinew::readBvhFile(path);
    } catch (const sinew::Error&) {
    }
    return 0;
}

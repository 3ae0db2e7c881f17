// libFuzzer harness: the OpenSim ExternalLoads XML reader (its data file, when named, is read too).
#include <cstdint>

#include "fuzz_input.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/external_loads.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = sinew::fuzz::writeInput(data, size, ".xml");
    try {
        sinew::readExternalLoads(path);
    } catch (const sinew::Error&) {
    }
    return 0;
}

// libFuzzer harness: the OpenSim .osim reader and its conversion to a sinew Model.
#include <cstdint>

#include "fuzz_input.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/osim_model.hpp"
#include "sinew/io/osim_model_converter.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = sinew::fuzz::writeInput(data, size, ".osim");
    try {
        const sinew::OsimModel osim = sinew::readOsimModel(path);
        sinew::convertOsimModel(osim);
    } catch (const sinew::Error&) {
    }
    return 0;
}

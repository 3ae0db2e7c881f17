// libFuzzer harness: the OpenSim tool setup reader (InverseDynamicsTool, AnalyzeTool).
#include <cstdint>

#include "fuzz_input.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/tool_setup.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = sinew::fuzz::writeInput(data, size, ".xml");
    try {
        sinew::readToolSetup(path);
    } catch (const sinew::Error&) {
    }
    return 0;
}

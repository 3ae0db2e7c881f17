// libFuzzer harness: sinew's YAML model reader (text in, Model or sinew::Error out).
#include <cstdint>
#include <string>

#include "sinew/core/error.hpp"
#include "sinew/io/model_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        const sinew::Model model = sinew::readModelText(std::string(reinterpret_cast<const char*>(data), size), "fuzz.yaml");
        // A model that loads writes and reads back: the writer's checks are part of the door too.
        sinew::readModelText(sinew::writeModelText(model), "fuzz_written.yaml");
    } catch (const sinew::Error&) {
    }
    return 0;
}

#pragma once
// The readers under fuzzing take paths (and OpenSim files name others beside them), so each input is
// written to a file of this process's own, with the extension the reader expects. A reader may refuse the
// input with sinew::Error (that is its contract); anything else escaping, a crash, a sanitizer report, a
// leak or a hang is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

namespace sinew::fuzz {

inline std::string writeInput(const std::uint8_t* data, std::size_t size, const char* extension) {
    const std::string path = "/tmp/sinew_fuzz_" + std::to_string(::getpid()) + extension;
    FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) std::abort();
    if (size && std::fwrite(data, 1, size, file) != size) std::abort();
    std::fclose(file);
    return path;
}

}  // namespace sinew::fuzz

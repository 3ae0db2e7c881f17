// libFuzzer harness: the .mot/.sto reader in both non-finite modes, and the writer on what it read.
#include <cstdint>

#include "fuzz_input.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/storage_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = sinew::fuzz::writeInput(data, size, ".sto");
    for (const sinew::NonFinite mode : {sinew::NonFinite::Refuse, sinew::NonFinite::Allow}) {
        try {
            const sinew::StorageTable table = sinew::readStorageFile(path, mode);
            sinew::checkStorageMagnitudes(table, {}, 1e7, "fuzz");
            if (mode == sinew::NonFinite::Refuse) sinew::writeStorageFile(table, path + ".out");
        } catch (const sinew::Error&) {
        }
    }
    return 0;
}

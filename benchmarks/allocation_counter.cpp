#include "allocation_counter.hpp"

#include <cstddef>
#include <cstdlib>

// glibc's own entry points, which the interposed functions forward to.
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* __libc_calloc(std::size_t count, std::size_t size);
extern "C" void* __libc_realloc(void* pointer, std::size_t size);

namespace {
long long allocationCount = 0;
}  // namespace

extern "C" void* malloc(std::size_t size) noexcept {
    ++allocationCount;
    return __libc_malloc(size);
}

extern "C" void* calloc(std::size_t count, std::size_t size) noexcept {
    ++allocationCount;
    return __libc_calloc(count, size);
}

extern "C" void* realloc(void* pointer, std::size_t size) noexcept {
    ++allocationCount;
    return __libc_realloc(pointer, size);
}

namespace sinew_benchmarks {

long long getAllocationCount() { return allocationCount; }

}  // namespace sinew_benchmarks

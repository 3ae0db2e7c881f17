#include "allocation_counter.hpp"

#include <cstddef>
#include <cstdlib>

namespace {
long long allocationCount = 0;
}  // namespace

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kCounting = false;
#else
constexpr bool kCounting = true;

// glibc's own entry points, which the interposed functions forward to.
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* __libc_calloc(std::size_t count, std::size_t size);
extern "C" void* __libc_realloc(void* pointer, std::size_t size);

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
#endif

namespace sinew::test {

bool isCountingAllocations() { return kCounting; }

long long getAllocationCount() { return allocationCount; }

}  // namespace sinew::test

#pragma once
// Counts heap allocations, so tests and benchmarks can check the house rule (no allocation inside a calc*
// call or an integration step). allocation_counter.cpp interposes glibc's malloc, calloc and realloc for the
// whole program, which also catches operator new and Eigen's dynamic matrices. Not under AddressSanitizer,
// which owns the allocator. Not thread-safe: count on one thread.
namespace sinew::test {

// False where allocations are not counted (AddressSanitizer builds); the count then stays 0.
bool isCountingAllocations();

// Allocations (malloc, calloc, realloc calls) made by the program so far.
long long getAllocationCount();

}  // namespace sinew::test

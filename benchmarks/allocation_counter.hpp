#pragma once
// Counts heap allocations, so a benchmark can report how many one evaluation makes (the house rule: no
// allocation inside a calc* call). allocation_counter.cpp interposes glibc's malloc, calloc and realloc for
// the whole program, which also catches operator new and Eigen's dynamic matrices. Not thread-safe: the
// benchmarks run on one thread.
namespace sinew_benchmarks {

// Allocations (malloc, calloc, realloc calls) made by the program so far.
long long getAllocationCount();

}  // namespace sinew_benchmarks

#include "side_by_side.hpp"

#include <array>
#include <exception>

namespace sinew {

void runSideBySide(const std::function<void()>& first, const std::function<void()>& second) {
    std::array<std::exception_ptr, 2> errors;
    // An exception may not leave an OpenMP block: each is caught in its section and rethrown after.
    auto run = [&errors](const std::function<void()>& step, std::size_t slot) {
        try {
            step();
        } catch (...) {
            errors[slot] = std::current_exception();
        }
    };
#pragma omp parallel sections num_threads(2)
    {
#pragma omp section
        run(first, 0);
#pragma omp section
        run(second, 1);
    }
    for (const std::exception_ptr& error : errors)
        if (error) std::rethrow_exception(error);
}

}  // namespace sinew

#pragma once
// Asserting that bad input is refused with a message that starts at its location and names what is wrong.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew::test {

// Runs `action`, which must throw ErrorType whose message starts with `prefix` and contains every one of
// `words`; `input` is shown when nothing is thrown.
template <typename ErrorType = Error, typename Action>
::testing::AssertionResult throwsErrorAt(Action&& action, const std::string& prefix,
                                         const std::vector<std::string>& words, const std::string& input) {
    try {
        action();
    } catch (const ErrorType& e) {
        const std::string message = e.what();
        if (message.rfind(prefix, 0) != 0)
            return ::testing::AssertionFailure() << "expected the error at '" << prefix << "', got: " << message;
        for (const std::string& word : words)
            if (message.find(word) == std::string::npos)
                return ::testing::AssertionFailure() << "'" << word << "' is missing from: " << message;
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "the input was accepted:\n" << input;
}

}  // namespace sinew::test

#pragma once
// sinew's error types. Bad user input (model files, options, motions) throws one of these with a message
// naming where the problem is (file:line, link, wire, frame) and what was expected.
#include <stdexcept>
#include <string>

namespace sinew {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// An invalid model description. `where` is the location the caller knows (e.g. "arm.yaml:12"), possibly
// empty when the model was built in code.
class ModelError : public Error {
public:
    ModelError(std::string where, const std::string& what);
    const std::string& where() const { return where_; }
    const std::string& what_without_location() const { return what_; }

private:
    std::string where_;
    std::string what_;
};

}  // namespace sinew

#include "sinew/core/error.hpp"

namespace sinew {

ModelError::ModelError(std::string where, const std::string& what)
    : Error(where.empty() ? what : where + ": " + what), where_(std::move(where)), what_(what) {}

}  // namespace sinew

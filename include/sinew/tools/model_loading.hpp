#pragma once
// One entry point for the commands that accept either model format: an OpenSim .osim file (converted, with
// what was left out reported through `notes`) or a sinew YAML model.
#include <functional>
#include <string>

#include "sinew/core/model.hpp"

namespace sinew {

Model loadModel(const std::string& path, const std::function<void(const std::string&)>& notes);

}  // namespace sinew

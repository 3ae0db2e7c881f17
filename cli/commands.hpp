#pragma once
#include <string>
#include <vector>

namespace sinew::cli {

// Each returns the process exit code; arguments exclude the command name.
int runInfo(const std::vector<std::string>& args);
int runSimulate(const std::vector<std::string>& args);

}  // namespace sinew::cli

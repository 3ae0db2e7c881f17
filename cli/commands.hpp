#pragma once
#include <string>
#include <vector>

namespace sinew::cli {

// Each returns the process exit code; arguments exclude the command name.
int runInfo(const std::vector<std::string>& args);
int runSimulate(const std::vector<std::string>& args);
int runImport(const std::vector<std::string>& args);
int runExport(const std::vector<std::string>& args);
int runInverseDynamicsCommand(const std::vector<std::string>& args);
int runInverseKinematicsCommand(const std::vector<std::string>& args);
int runRunTool(const std::vector<std::string>& args);
int runMomentArms(const std::vector<std::string>& args);
int runTensions(const std::vector<std::string>& args);
int runWholeBody(const std::vector<std::string>& args);
int runRender(const std::vector<std::string>& args);
int runPlot(const std::vector<std::string>& args);

}  // namespace sinew::cli

#include <cstdio>
#include <optional>
#include <variant>

#include "arguments.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/tools/inverse_dynamics_tool.hpp"
#include "sinew/tools/inverse_kinematics_tool.hpp"
#include "sinew/tools/static_optimization_tool.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew run-tool SETUP.xml [-o DIR]\n"
    "  Runs an OpenSim tool setup file as it stands, like 'opensim-cmd run-tool': paths relative to the\n"
    "  setup file, its time range, cut-off frequency and external loads. Supported: InverseDynamicsTool,\n"
    "  InverseKinematicsTool (the .mot and <name>_ik_marker_errors.sto), and\n"
    "  AnalyzeTool with a StaticOptimization analysis (<name>_StaticOptimization_force.sto, _activation.sto,\n"
    "  and sinew's per-frame _report.sto).\n"
    "  -o DIR   write the results here instead of the setup's results_directory\n";

}  // namespace

int runRunTool(const std::vector<std::string>& args) {
    std::string setupPath, outputDir;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("-o", "--output")) outputDir = reader.value();
        else reader.takePositional({&setupPath});
    }
    if (reader.helpShown()) return 0;
    if (setupPath.empty()) return reader.failWithUsage();
    const auto printNote = [](const std::string& note) { std::printf("%s\n", note.c_str()); };
    std::optional<Progress> progress;
    const auto onFrame = [&](int frame, int frames) {
        if (!progress) progress.emplace("frames", frames);
        progress->update(frame);
    };
    const ToolSetup tool = readToolSetup(setupPath);
    if (const auto* inverseDynamics = std::get_if<InverseDynamicsSetup>(&tool)) {
        const InverseDynamicsSetup& setup = *inverseDynamics;
        const std::string written = runInverseDynamicsTool(setup, outputDir, printNote, onFrame);
        if (progress) progress->finish();
        std::printf("InverseDynamicsTool '%s' -> %s\n", setup.name.c_str(), written.c_str());
    } else if (const auto* inverseKinematics = std::get_if<InverseKinematicsSetup>(&tool)) {
        const std::string written = runInverseKinematicsTool(*inverseKinematics, outputDir, printNote, onFrame);
        if (progress) progress->finish();
        std::printf("InverseKinematicsTool '%s' -> %s\n", inverseKinematics->name.c_str(), written.c_str());
    } else {
        const AnalyzeSetup& setup = std::get<AnalyzeSetup>(tool);
        const std::vector<std::string> written = runStaticOptimizationTool(setup, outputDir, printNote, onFrame);
        if (progress) progress->finish();
        std::printf("AnalyzeTool '%s' (StaticOptimization) ->", setup.name.c_str());
        for (const std::string& file : written) std::printf(" %s", file.c_str());
        std::printf("\n");
    }
    return 0;
}

}  // namespace sinew::cli

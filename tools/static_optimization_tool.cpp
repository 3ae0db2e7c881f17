#include "sinew/tools/static_optimization_tool.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>

#include "sinew/core/error.hpp"
#include "sinew/io/osim_model.hpp"
#include "sinew/io/osim_model_converter.hpp"
#include "sinew/io/tool_setup.hpp"

namespace sinew {
namespace {

// The actuators OpenSim's StaticOptimization optimizes besides the muscles: CoordinateActuators that
// apply force, from the model (unless the force-set files replace its forces) and the force-set files.
std::vector<OsimCoordinateActuator> collectReserves(const AnalyzeSetup& setup, const OsimModel& osim) {
    std::vector<OsimCoordinateActuator> all;
    if (!setup.replaceForceSet) all = osim.coordinateActuators;
    for (const std::string& file : setup.forceSetFiles) {
        const OsimForceSet forceSet = readForceSetFile(file);
        if (!forceSet.pointActuators.empty() || !forceSet.torqueActuators.empty())
            throw ModelError(forceSet.file, "PointActuator and TorqueActuator reserves (residuals on a floating "
                                            "root) are not supported by sinew's static optimization yet");
        if (!forceSet.unsupported.empty())
            throw ModelError(forceSet.unsupported.front().where,
                             forceSet.unsupported.front().type + " '" + forceSet.unsupported.front().name +
                                 "' is not an actuator sinew's static optimization can use");
        all.insert(all.end(), forceSet.coordinateActuators.begin(), forceSet.coordinateActuators.end());
    }
    std::vector<OsimCoordinateActuator> applying;
    std::copy_if(all.begin(), all.end(), std::back_inserter(applying),
                 [](const OsimCoordinateActuator& a) { return a.limits.appliesForce; });
    return applying;
}

}  // namespace

std::vector<std::string> runStaticOptimizationTool(const AnalyzeSetup& setup, const std::string& outputDirectory,
                                                   const std::function<void(const std::string&)>& notes,
                                                   const std::function<void(int frame, int frames)>& onFrame) {
    if (!setup.staticOptimization)
        throw ModelError(setup.file, "AnalyzeTool '" + setup.name + "' has no StaticOptimization analysis");
    const auto& analysis = *setup.staticOptimization;
    const auto note = [&](const std::string& text) {
        if (notes) notes(text);
    };
    for (const OsimUnsupported& other : setup.unsupported)
        note("not run: " + other.type + " '" + other.name + "' (" + other.where + ")");
    if (!setup.statesFile.empty())
        throw ModelError(setup.file, "states_file is not supported yet: give the motion as coordinates_file");
    if (!setup.speedsFile.empty()) note("speeds_file is ignored: speeds are the coordinates' spline derivatives");
    if (setup.replaceForceSet && !setup.forceSetFiles.empty())
        throw ModelError(setup.file, "replace_force_set true would drop the muscles: sinew's static "
                                     "optimization needs them (set it false to add the reserves)");
    if (!analysis.useModelForceSet)
        throw ModelError(analysis.where, "use_model_force_set false (ideal actuators on every DOF instead of the "
                                         "muscles) is not supported");
    if (!analysis.on)
        throw ModelError(analysis.where, "StaticOptimization '" + analysis.name + "' is switched off (<on>false</on>)");
    if (analysis.activationExponent != 2)
        throw ModelError(analysis.where, "activation_exponent " + std::to_string(analysis.activationExponent) +
                                             " is not supported (the active-set QP minimizes squared activations)");
    if (analysis.stepInterval != 1) note("step_interval is ignored: every frame is reported");
    note("results are written with 17 significant digits (output_precision " +
         std::to_string(setup.outputPrecision) + " is not applied)");
    note("optimizer_convergence_criterion and optimizer_max_iterations do not apply: the active-set QP solves "
         "each frame to optimality");

    const OsimModel osim = readOsimModel(setup.modelFile);
    OsimConversion conversion = convertOsimModel(osim);
    for (const std::string& line : conversion.notImported) note("not imported: " + line);
    const Model& model = conversion.model;

    OsimStaticOptimizationOptions options;
    options.lowpassCutoffHz = setup.lowpassCutoffFrequencyForCoordinates;
    options.startTime = std::max(setup.initialTime, analysis.startTime);
    options.finalTime = std::min(setup.finalTime, analysis.endTime);
    options.reserves = collectReserves(setup, osim);
    options.useMusclePhysiology = analysis.useMusclePhysiology;
    options.onFrame = onFrame;
    const int numWires = model.getNumWires();
    options.minActivation.resize(numWires);
    options.maxActivation.resize(numWires);
    for (int w = 0; w < numWires; ++w) {
        const OsimPathForce* muscle = findPathForce(osim, model.getWire(w).name);
        if (!muscle) throw Error("static optimization: wire '" + model.getWire(w).name + "' is no force of " + osim.file);
        options.minActivation[w] = muscle->limits.minControl;
        options.maxActivation[w] = muscle->limits.maxControl;
    }

    std::optional<ExternalLoads> loads;
    if (!setup.externalLoadsFile.empty()) loads = readExternalLoads(setup.externalLoadsFile);
    const OsimStaticOptimizationResult result =
        runOsimStaticOptimization(model, readStorageFile(setup.coordinatesFile), loads ? &*loads : nullptr, options);
    if (result.flaggedFrames > 0)
        note(std::to_string(result.flaggedFrames) + " frames were not solved to optimality (status in the report)");

    const std::filesystem::path directory = outputDirectory.empty() ? setup.resultsDirectory : outputDirectory;
    std::filesystem::create_directories(directory);
    const std::string prefix = (directory / (setup.name + "_" + analysis.name + "_")).string();
    std::vector<std::string> written = {prefix + "force.sto", prefix + "activation.sto", prefix + "report.sto"};
    writeStorageFile(result.force, written[0]);
    writeStorageFile(result.activation, written[1]);
    writeStorageFile(result.report, written[2]);
    return written;
}

}  // namespace sinew

#include "sinew/tools/static_optimization_tool.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>

#include "sinew/core/error.hpp"
#include "sinew/io/osim_model.hpp"
#include "sinew/io/osim_model_converter.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/tools/coordinate_table.hpp"

namespace sinew {
namespace {

// Appends the actuators that apply force (OpenSim leaves the others out of the model).
template <typename Actuator>
void appendApplying(std::vector<Actuator>& to, const std::vector<Actuator>& from) {
    std::copy_if(from.begin(), from.end(), std::back_inserter(to), [](const Actuator& a) { return a.limits.appliesForce; });
}

// The actuators OpenSim's StaticOptimization optimizes besides the muscles: CoordinateActuators,
// PointActuators and TorqueActuators that apply force, from the model (unless the force-set files replace
// its forces) and the force-set files.
void collectReserves(const AnalyzeSetup& setup, const OsimModel& osim, OsimStaticOptimizationOptions& options) {
    if (!setup.replaceForceSet) {
        appendApplying(options.reserves, osim.coordinateActuators);
        appendApplying(options.pointActuators, osim.pointActuators);
        appendApplying(options.torqueActuators, osim.torqueActuators);
    }
    for (const std::string& file : setup.forceSetFiles) {
        const OsimForceSet forceSet = readForceSetFile(file);
        if (!forceSet.unsupported.empty())
            throw ModelError(forceSet.unsupported.front().where,
                             forceSet.unsupported.front().type + " '" + forceSet.unsupported.front().name +
                                 "' is not an actuator sinew's static optimization can use");
        appendApplying(options.reserves, forceSet.coordinateActuators);
        appendApplying(options.pointActuators, forceSet.pointActuators);
        appendApplying(options.torqueActuators, forceSet.torqueActuators);
    }
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
    const bool states = !setup.statesFile.empty();
    if (states) {
        // OpenSim's AnalyzeTool::loadStatesFromFile ignores these next to a states file.
        if (!setup.coordinatesFile.empty()) note("coordinates_file is ignored: states_file gives the motion");
        if (setup.lowpassCutoffFrequencyForCoordinates >= 0)
            note("lowpass_cutoff_frequency_for_coordinates does not apply to states_file (as in OpenSim)");
    }
    if (!setup.speedsFile.empty())
        note(states ? "speeds_file is ignored: states_file gives the speeds"
                    : "speeds_file is ignored: speeds are the coordinates' spline derivatives");
    if (setup.replaceForceSet && !setup.forceSetFiles.empty())
        throw ModelError(setup.file, "replace_force_set true would drop the muscles: sinew's static "
                                     "optimization needs them (set it false to add the reserves)");
    if (!analysis.useModelForceSet)
        throw ModelError(analysis.where, "use_model_force_set false (ideal actuators on every DOF instead of the "
                                         "muscles) is not supported");
    if (!analysis.on)
        throw ModelError(analysis.where, "StaticOptimization '" + analysis.name + "' is switched off (<on>false</on>)");
    if (analysis.activationExponent < 1)
        throw ModelError(analysis.where, "activation_exponent " + std::to_string(analysis.activationExponent) +
                                             " is below 1: the sum of activations^exponent is then not convex");
    note(std::string("optimizer_convergence_criterion and optimizer_max_iterations do not apply: ") +
         (analysis.activationExponent == 2 ? "the active-set QP solves each frame to optimality"
                                           : "Ipopt solves each frame to 1e-12 (activation_exponent other than 2)"));

    const OsimModel osim = readOsimModel(setup.modelFile);
    OsimConversion conversion = convertOsimModel(osim);
    reportOsimConversion(conversion, note);
    const Model& model = conversion.model;

    OsimStaticOptimizationOptions options;
    options.lowpassCutoffHz = setup.lowpassCutoffFrequencyForCoordinates;
    options.startTime = std::max(setup.initialTime, analysis.startTime);
    options.finalTime = std::min(setup.finalTime, analysis.endTime);
    collectReserves(setup, osim, options);
    options.motionIsStates = states;
    options.useMusclePhysiology = analysis.useMusclePhysiology;
    options.activationExponent = analysis.activationExponent;
    options.stepInterval = analysis.stepInterval;
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
    const StorageTable motion = states ? readStorageFile(setup.statesFile)
                                       : completeCoordinateTable(model, readStorageFile(setup.coordinatesFile), note);
    OsimStaticOptimizationResult result =
        runOsimStaticOptimization(model, motion, loads ? &*loads : nullptr, options);
    if (result.flaggedFrames > 0)
        note(std::to_string(result.flaggedFrames) + " frames were not solved to optimality (status in the report)");

    const std::filesystem::path directory = outputDirectory.empty() ? setup.resultsDirectory : outputDirectory;
    std::filesystem::create_directories(directory);
    const std::string prefix = (directory / (setup.name + "_" + analysis.name + "_")).string();
    std::vector<std::string> written = {prefix + "force.sto", prefix + "activation.sto", prefix + "report.sto"};
    // OpenSim prints its results with output_precision decimals (IO::SetPrecision, "%.Nlf"); sinew's own
    // report keeps every digit.
    result.force.decimals = result.activation.decimals = setup.outputPrecision;
    OutputFileSet outputs;
    writeStorageFile(result.force, outputs, written[0]);
    writeStorageFile(result.activation, outputs, written[1]);
    writeStorageFile(result.report, outputs, written[2]);
    outputs.commit();
    return written;
}

}  // namespace sinew

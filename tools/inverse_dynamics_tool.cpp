#include "sinew/tools/inverse_dynamics_tool.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <utility>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/force_element_loads.hpp"
#include "sinew/tools/measured_loads.hpp"
#include "sinew/tools/motion_frames.hpp"
#include "sinew/io/model_loading.hpp"
#include "side_by_side.hpp"

namespace sinew {
namespace {

// One per speed, as OpenSim names them: "<coordinate>_moment" for rotational coordinates, "<coordinate>_force"
// otherwise; a ball or free joint's angular speeds j_wx.. give j_wx_moment.., a free joint's linear ones
// j_vx_force...
std::vector<std::string> getGeneralizedForceNames(const Model& model) {
    std::vector<std::string> names = getSpeedNames(model);
    std::size_t k = 0;
    for (const Joint& joint : model.getJoints()) {
        for (int i = 0; i < joint.nu; ++i, ++k) {
            const bool quaternion = joint.type == JointType::Ball || joint.type == JointType::Free;
            const bool rotational =
                quaternion ? i < 3
                           : model.getCoordinates()[static_cast<std::size_t>(joint.qStart + i)].motionType == MotionType::Rotational;
            names[k] += rotational ? "_moment" : "_force";
        }
    }
    return names;
}

// `curves`, when given, were fitted to `loads` beforehand (the tool fits them beside the model's reading);
// otherwise they are fitted here beside the coordinates' processing, which is independent of them. So may
// the coordinates' table have been processed (`processed`, the tool's too).
StorageTable calcGeneralizedForceTable(const Model& model, const StorageTable& coordinates, const ExternalLoads* loads,
                                       std::optional<ExternalLoadCurves> curves, const ProcessedMotionTable* processed,
                                       const InverseDynamicsOptions& options) {
    std::optional<CoordinateTrajectory> trajectory;
    std::optional<MeasuredLoads> measured;
    auto processCoordinates = [&] {
        const CoordinateSamples samples = readCoordinateSamples(model, coordinates);
        trajectory = preprocessCoordinateSamples(model, samples, options.lowpassCutoffHz, options.startTime,
                                                 options.finalTime, processed);
    };
    auto resolveLoads = [&] {
        if (!loads) return;
        if (curves)
            measured.emplace(model, *loads, std::move(*curves));
        else
            measured.emplace(model, *loads);
    };
    if (curves) {
        processCoordinates();
        resolveLoads();
    } else {
        runSideBySide(processCoordinates, resolveLoads);
    }

    StorageTable result;
    result.name = "Inverse Dynamics Generalized Forces";
    result.columns = getGeneralizedForceNames(model);
    const int frames = static_cast<int>(trajectory->times.size());
    result.times.assign(trajectory->times.data(), trajectory->times.data() + frames);
    result.rows.resize(static_cast<std::size_t>(frames));
    // The frames are independent: two halves side by side, each with its own buffers. The first half's
    // thread reports progress, counting its own frames (1, 2, .. : the second half keeps pace), and the end
    // is reported once both are done.
    int framesReported = 0;
    auto runFrames = [&](int first, int end, bool reports) {
        Eigen::VectorXd tau(model.getNumU());
        ForceElementLoads elements(model);
        auto visit = [&](const MotionFrame& frame) {
            Data& data = frame.data;
            if (!frame.positionsAtQ) calcPositionKinematics(model, data, frame.q);
            calcInverseDynamicsAtPositions(model, data, frame.q, frame.u, frame.udot, frame.appliedLinkForces, tau);
            if (options.forceElements) elements.subtractFrom(data, tau);
            if (!tau.allFinite()) {
                Eigen::Index k = 0;
                while (std::isfinite(tau[k])) ++k;
                throw Error("inverse dynamics at t = " + std::to_string(frame.time) + " s (frame " +
                            std::to_string(frame.index + 1) + "): the generalized force '" +
                            result.columns[static_cast<std::size_t>(k)] + "' is not finite (speed " +
                            std::to_string(frame.u[k]) + ", acceleration " + std::to_string(frame.udot[k]) +
                            "; check the motion and external loads there)");
            }
            result.rows[static_cast<std::size_t>(frame.index)].assign(tau.data(), tau.data() + tau.size());
        };
        auto progress = [&](int frame, int) {
            if (reports && options.onFrame) options.onFrame(framesReported = frame, frames);
        };
        forEachMotionFrame(model, *trajectory, measured ? &*measured : nullptr, visit, progress, first, end);
    };
    runSideBySide([&] { runFrames(0, frames / 2, true); }, [&] { runFrames(frames / 2, frames, false); });
    if (options.onFrame && framesReported < frames) options.onFrame(frames, frames);
    return result;
}

}  // namespace

StorageTable runInverseDynamics(const Model& model, const StorageTable& coordinates, const ExternalLoads* loads,
                                const InverseDynamicsOptions& options) {
    return calcGeneralizedForceTable(model, coordinates, loads, std::nullopt, nullptr, options);
}

std::string runInverseDynamicsTool(const InverseDynamicsSetup& setup, const std::string& outputDirectory,
                                   const std::function<void(const std::string&)>& notes,
                                   const std::function<void(int frame, int frames)>& onFrame) {
    // The model is read beside the motion files, the loads' curves and the coordinates' processing. Only
    // the model's reading sends notes, so they come out in order.
    std::optional<Model> loadedModel;
    std::optional<ExternalLoads> loads;
    std::optional<ExternalLoadCurves> curves;
    std::optional<ProcessedMotionTable> processedCoordinates;
    StorageTable coordinateFile;
    runSideBySide([&] { loadedModel = loadModel(setup.modelFile, notes); },
                  [&] {
                      if (!setup.externalLoadsFile.empty()) loads = readExternalLoads(setup.externalLoadsFile);
                      coordinateFile = readStorageFile(setup.coordinatesFile);
                      // A fit that fails is left to be done again where the loads come in turn, after the
                      // coordinates' errors and the model's notes, and fails there with the same error.
                      try {
                          if (loads) curves.emplace(*loads);
                      } catch (const Error&) {
                          curves.reset();
                      }
                      // So is a failed processing of the coordinates; a column the model does not read may
                      // fail it, which the model's own columns then do not.
                      try {
                          processedCoordinates = preprocessMotionTable(coordinateFile, setup.lowpassCutoffFrequencyForCoordinates,
                                                                       setup.startTime, setup.endTime);
                      } catch (const Error&) {
                          processedCoordinates.reset();
                      }
                  });
    const Model& model = *loadedModel;
    if (notes) {
        const auto& excluded = setup.forcesToExclude;
        const bool musclesOut = std::any_of(excluded.begin(), excluded.end(), [](const std::string& name) {
            return name == "Muscles" || name == "All" || name == "Actuators";
        });
        if (!musclesOut && model.getNumWires() > 0)
            notes("forces_to_exclude does not name Muscles, but sinew's inverse dynamics always leaves the wires out");
    }
    if (notes && setup.coordinatesInDegrees)
        notes("coordinates_in_degrees (OpenSim 3) is ignored: the motion file's inDegrees header decides, as in OpenSim 4");
    if (notes && loads && !loads->modelKinematicsFile.empty())
        notes("external_loads_model_kinematics_file is ignored: the points are taken as given in their frames");
    InverseDynamicsOptions options;
    const auto& excluded = setup.forcesToExclude;
    options.forceElements = std::find(excluded.begin(), excluded.end(), "All") == excluded.end();
    if (notes && options.forceElements)
        for (const std::string& name : excluded)
            if (name != "Muscles" && name != "Actuators")
                notes("forces_to_exclude names '" + name + "': sinew excludes Muscles, Actuators or All, and the "
                      "model's other force elements act");
    options.lowpassCutoffHz = setup.lowpassCutoffFrequencyForCoordinates;
    options.startTime = setup.startTime;
    options.finalTime = setup.endTime;
    options.onFrame = onFrame;
    const StorageTable coordinates = completeCoordinateTable(model, coordinateFile, notes);
    const StorageTable result =
        calcGeneralizedForceTable(model, coordinates, loads ? &*loads : nullptr, std::move(curves),
                                  processedCoordinates ? &*processedCoordinates : nullptr, options);
    const std::filesystem::path directory = outputDirectory.empty() ? setup.resultsDirectory : outputDirectory;
    std::filesystem::create_directories(directory);
    const std::string path = (directory / setup.outputGenForceFile).string();
    writeStorageFile(result, path);
    return path;
}

}  // namespace sinew

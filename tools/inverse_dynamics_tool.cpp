#include "sinew/tools/inverse_dynamics_tool.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <utility>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/force_element_loads.hpp"
#include "sinew/tools/measured_loads.hpp"
#include "sinew/tools/motion_frames.hpp"
#include "sinew/io/model_loading.hpp"

namespace sinew {
namespace {

// work() while `first` runs on its thread. Should work throw, first's error, if it has one, is the one
// reported, as it would be were the two run in order.
template <typename T, typename Work>
auto runAlongside(std::future<T>& first, Work work) {
    try {
        return work();
    } catch (...) {
        first.get();
        throw;
    }
}

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

}  // namespace

StorageTable runInverseDynamics(const Model& model, const StorageTable& coordinates, const ExternalLoads* loads,
                                const InverseDynamicsOptions& options) {
    // The loads' splines (one per data column, over every row of the file) and the coordinates' processing
    // are independent: the loads are fitted on a second thread.
    std::future<std::optional<MeasuredLoads>> fitLoads = std::async(std::launch::async, [&] {
        std::optional<MeasuredLoads> fitted;
        if (loads) fitted.emplace(model, *loads);
        return fitted;
    });
    // An error in the coordinates, the earlier step, is the one reported (the future waits for the fit).
    const CoordinateSamples samples = readCoordinateSamples(model, coordinates);
    const CoordinateTrajectory trajectory = preprocessCoordinateSamples(model, samples, options.lowpassCutoffHz,
                                                                        options.startTime, options.finalTime);
    const std::optional<MeasuredLoads> measured = fitLoads.get();

    StorageTable result;
    result.name = "Inverse Dynamics Generalized Forces";
    result.columns = getGeneralizedForceNames(model);
    Data data(model);
    Eigen::VectorXd tau(model.getNumU());
    ForceElementLoads elements(model);
    forEachMotionFrame(
        model, trajectory, measured ? &*measured : nullptr,
        [&](const MotionFrame& frame) {
            calcInverseDynamics(model, data, frame.q, frame.u, frame.udot, frame.appliedLinkForces, tau);
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
            result.times.push_back(frame.time);
            result.rows.emplace_back(tau.data(), tau.data() + tau.size());
        },
        options.onFrame);
    return result;
}

std::string runInverseDynamicsTool(const InverseDynamicsSetup& setup, const std::string& outputDirectory,
                                   const std::function<void(const std::string&)>& notes,
                                   const std::function<void(int frame, int frames)>& onFrame) {
    // The .osim and the motion files are read at once: the model on a second thread. Its notes come first,
    // as they would in order, and so does its error.
    std::future<Model> modelLoad = std::async(std::launch::async, [&] { return loadModel(setup.modelFile, notes); });
    const auto [loads, coordinateFile] = runAlongside(modelLoad, [&] {
        std::optional<ExternalLoads> externalLoads;
        if (!setup.externalLoadsFile.empty()) externalLoads = readExternalLoads(setup.externalLoadsFile);
        return std::make_pair(std::move(externalLoads), readStorageFile(setup.coordinatesFile));
    });
    const Model model = modelLoad.get();
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
    const StorageTable result = runInverseDynamics(model, coordinates, loads ? &*loads : nullptr, options);
    const std::filesystem::path directory = outputDirectory.empty() ? setup.resultsDirectory : outputDirectory;
    std::filesystem::create_directories(directory);
    const std::string path = (directory / setup.outputGenForceFile).string();
    writeStorageFile(result, path);
    return path;
}

}  // namespace sinew

// Inverse dynamics per frame on OpenSim's gait2354 walking example (../shared/data/opensim), the case
// OpenSim 4.4.1 was timed on (1.34 ms per frame, ../shared/data/opensim/README.md). Registered only when
// the data are present.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <iostream>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/inverse_dynamics_tool.hpp"
#include "sinew/tools/measured_loads.hpp"
#include "sinew/io/model_loading.hpp"

namespace sinew {
namespace {

const std::filesystem::path kGaitSetup =
    std::filesystem::path(SINEW_SHARED_DIR) / "data/opensim/gait2354/subject01_Setup_InverseDynamics.xml";

// The whole tool as `sinew run-tool` runs it (reading the files, filtering, splines, every frame), per frame.
void runTool(benchmark::State& state) {
    const InverseDynamicsSetup setup = readInverseDynamicsSetup(kGaitSetup.string());
    const std::string output = (std::filesystem::temp_directory_path() / "sinew_bench_id").string();
    double seconds = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        runInverseDynamicsTool(setup, output, {});
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    const StorageTable result = readStorageFile((std::filesystem::path(output) / setup.outputGenForceFile).string());
    const double frames = static_cast<double>(result.times.size());
    state.counters["frames"] = frames;
    state.counters["ms_per_frame"] = 1e3 * seconds / (static_cast<double>(state.iterations()) * frames);
}

// One frame's dynamics alone (kinematics, measured loads, recursive Newton-Euler), as a real-time caller
// that already has q, u, udot would run it.
void runFrame(benchmark::State& state) {
    const InverseDynamicsSetup setup = readInverseDynamicsSetup(kGaitSetup.string());
    const Model model = loadModel(setup.modelFile, {});
    const ExternalLoads loads = readExternalLoads(setup.externalLoadsFile);
    const MeasuredLoads measured(model, loads);
    const CoordinateSamples samples = readCoordinateSamples(model, readStorageFile(setup.coordinatesFile));
    const CoordinateTrajectory trajectory = preprocessCoordinateSamples(
        model, samples, setup.lowpassCutoffFrequencyForCoordinates, setup.startTime, setup.endTime);
    Data data(model);
    std::vector<SpatialVector> linkForces(static_cast<std::size_t>(model.getNumLinks()));
    Eigen::VectorXd q, u, udot, tau(model.getNumU());
    Eigen::Index frame = 0;
    for (auto _ : state) {
        q = trajectory.q.row(frame).transpose();
        u = trajectory.qdot.row(frame).transpose();
        udot = trajectory.qddot.row(frame).transpose();
        calcAppliedLinkForces(model, &measured, data, trajectory.times[frame], q, linkForces);
        calcInverseDynamics(model, data, q, u, udot, linkForces, tau);
        benchmark::DoNotOptimize(tau.data());
        frame = (frame + 1) % trajectory.times.size();
    }
    state.counters["links"] = model.getNumLinks();
    state.counters["dof"] = model.getNumU();
}

const bool kRegistered = [] {
    if (!std::filesystem::exists(kGaitSetup)) {
        std::cerr << "InverseDynamics benchmarks skipped: " << kGaitSetup << " is absent\n";
        return false;
    }
    benchmark::RegisterBenchmark("InverseDynamics/tool/gait2354", runTool)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("InverseDynamics/frame/gait2354", runFrame)->Unit(benchmark::kMicrosecond);
    return true;
}();

}  // namespace
}  // namespace sinew

// Inverse kinematics per frame: InverseKinematics/gait10dof/<warm|cold> on OpenSim's Gait10dof18musc walk
// (subject01_walk.trc, the setup's 31 weighted markers, 151 frames at 60 Hz). "warm": each frame starts from
// the previous frame's solution, as `sinew ik` runs; "cold": from the model's default pose. The peer is
// OpenSim's own run of the same setup, not available here, so only sinew is timed. Registered only when
// ../shared is present.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "sinew/io/model_loading.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/io/trc_file.hpp"
#include "sinew/tools/inverse_kinematics.hpp"

namespace sinew {
namespace {

const std::filesystem::path kGait10 =
    std::filesystem::path(SINEW_SHARED_DIR) / "data/opensim-models/Pipelines/Gait10dof18musc/OutputReference";

void timeFrames(benchmark::State& state, bool warm) {
    const InverseKinematicsSetup setup = readInverseKinematicsSetup((kGait10 / "IK/walk_Setup_IK.xml").string());
    const Model model = loadModel(setup.modelFile, {});
    const MarkerTable capture = readTrcFile(setup.markerFile);
    std::vector<MarkerTask> tasks;
    std::vector<Eigen::Index> columns;
    for (const InverseKinematicsTaskSetup& task : setup.markerTasks) {
        const auto column = std::find(capture.markers.begin(), capture.markers.end(), task.name);
        if (!task.apply || task.weight == 0 || column == capture.markers.end()) continue;
        tasks.push_back({task.name, task.weight});
        columns.push_back(column - capture.markers.begin());
    }
    std::vector<InverseKinematicsTargets> frames;
    for (const Eigen::Matrix3Xd& positions : capture.positions) {
        InverseKinematicsTargets targets;
        targets.markers.resize(3, static_cast<Eigen::Index>(tasks.size()));
        for (std::size_t t = 0; t < tasks.size(); ++t) targets.markers.col(static_cast<Eigen::Index>(t)) = positions.col(columns[t]);
        frames.push_back(std::move(targets));
    }
    InverseKinematicsSolver solver(model, loadMarkers(setup.modelFile, model), tasks, {});
    Eigen::VectorXd q = model.getDefaultQ();
    std::size_t k = 0;
    double iterations = 0;
    for (auto _ : state) {
        if (!warm || k % frames.size() == 0) q = model.getDefaultQ();
        iterations += solver.solve(frames[k % frames.size()], q).iterations;
        ++k;
    }
    state.counters["links"] = model.getNumLinks();
    state.counters["dof"] = model.getNumU();
    state.counters["markers"] = static_cast<double>(tasks.size());
    state.counters["iterations"] = iterations / static_cast<double>(state.iterations());
}

const bool kRegistered = [] {
    if (!std::filesystem::exists(kGait10 / "IK/walk_Setup_IK.xml")) {
        std::cerr << "InverseKinematics/gait10dof benchmarks skipped: " << kGait10 << " is absent\n";
        return false;
    }
    for (bool warm : {false, true})
        benchmark::RegisterBenchmark(warm ? "InverseKinematics/gait10dof/warm" : "InverseKinematics/gait10dof/cold",
                                     [warm](benchmark::State& state) { timeFrames(state, warm); })
            ->Unit(benchmark::kMillisecond);
    return true;
}();

}  // namespace
}  // namespace sinew

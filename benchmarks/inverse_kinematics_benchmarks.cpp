// Inverse kinematics per frame: InverseKinematics/gait10dof/<warm|cold> on OpenSim's Gait10dof18musc walk
// (subject01_walk.trc, the setup's 31 weighted markers, 151 frames at 60 Hz). "warm": each frame starts from
// the previous frame's solution, as `sinew ik` runs; "cold": from the model's default pose. The peer is
// OpenSim's own run of the same setup, not available here, so only sinew is timed. Registered only when
// ../shared is present.
//
// InverseKinematics/whole_body/bvh_warm: the shipped whole-body model fitted to a synthetic BVH capture drawn
// from itself (makeModelBvh: 240 frames at 120 Hz of every ball joint swinging up to 0.3 rad at 1 Hz, the
// shipped map's 18 joint centres and orientations), each frame warm-started from the last, as `sinew ik
// MODEL CAPTURE.bvh` runs: always registered. InverseKinematics/whole_body/kick_warm: the same on CMU's kick
// 11_01.bvh (prepareBvhFit: the model and the map scaled to the subject), when ../shared is present. Both
// also report cpu_median_ms, the median frame in the thread's CPU time (the time is the mean, which the
// frames that refresh the curvature raise).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include <cmath>

#include "frame_clock.hpp"

#include "sinew/core/kinematics.hpp"
#include "sinew/io/bvh_map.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/io/trc_file.hpp"
#include "sinew/tools/bvh_inverse_kinematics.hpp"
#include "sinew/tools/bvh_targets.hpp"
#include "sinew/tools/inverse_kinematics.hpp"
#include "sinew/tools/inverse_kinematics_tool.hpp"
#include "sinew/tools/model_bvh.hpp"

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

const std::filesystem::path kWholeBody = std::filesystem::path(SINEW_SOURCE_DIR) / "models/whole_body";
const std::filesystem::path kKick = std::filesystem::path(SINEW_SHARED_DIR) / "data/cmu_mocap/11_01.bvh";

// Every ball joint swinging about its own random axis, up to 0.3 rad, at 1 Hz.
std::vector<Eigen::VectorXd> makeSwing(const Model& model, int frames, double frameTime) {
    Eigen::VectorXd amplitude = Eigen::VectorXd::Zero(model.getNumU());
    unsigned state = 12345;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Joint& joint = model.getJoint(i);
        if (joint.type != JointType::Ball) continue;
        for (int k = 0; k < 3; ++k) {
            state = state * 1103515245u + 12345u;
            amplitude[joint.uStart + k] = 0.3 * (static_cast<double>(state >> 16 & 0x7fff) / 0x7fff - 0.5) * 2 / std::sqrt(3.0);
        }
    }
    std::vector<Eigen::VectorXd> q;
    for (int f = 0; f < frames; ++f)
        q.push_back(integrateCoordinates(model, model.getDefaultQ(), amplitude * std::sin(2 * M_PI * f * frameTime), 1.0));
    return q;
}

void timeBvhFrames(benchmark::State& state, const Model& model, const BvhTargets& targets) {
    std::vector<InverseKinematicsTargets> frames;
    for (std::size_t f = 0; f < targets.capture.positions.size(); ++f)
        frames.push_back({targets.capture.positions[f], Eigen::VectorXd(),
                          targets.orientations.empty() ? std::vector<Eigen::Matrix3d>() : targets.orientations[f]});
    std::vector<MarkerTask> tasks;
    for (const Marker& marker : targets.markers) tasks.push_back({marker.name, 1});
    InverseKinematicsSolver solver(model, targets.markers, tasks, {}, {}, targets.orientationTasks);
    // The first frame solved before the clock starts: the warm frames are timed.
    Eigen::VectorXd q = alignFreeRoot(model, targets.markers, frames[0].markers, model.getDefaultQ());
    solver.solve(frames[0], q);
    std::size_t k = 1;
    double iterations = 0, rms = 0;
    std::vector<double> frameMs;
    for (auto _ : state) {
        const double start = cpuMilliseconds();
        const InverseKinematicsReport report = solver.solve(frames[k], q);
        frameMs.push_back(cpuMilliseconds() - start);
        iterations += report.iterations;
        rms += report.rmsMarkerError;
        k = k + 1 < frames.size() ? k + 1 : 1;
        if (k == 1) {
            state.PauseTiming();
            q = alignFreeRoot(model, targets.markers, frames[0].markers, model.getDefaultQ());
            solver.solve(frames[0], q);
            state.ResumeTiming();
        }
    }
    state.counters["dof"] = model.getNumU();
    state.counters["targets"] = static_cast<double>(tasks.size() + targets.orientationTasks.size());
    state.counters["iterations"] = iterations / static_cast<double>(state.iterations());
    state.counters["rms_m"] = rms / static_cast<double>(state.iterations());
    state.counters["cpu_median_ms"] = medianOf(frameMs);
}

const bool kWholeBodyRegistered = [] {
    benchmark::RegisterBenchmark("InverseKinematics/whole_body/bvh_warm", [](benchmark::State& state) {
        const Model model = loadModel((kWholeBody / "whole_body.yaml").string(), {});
        const BvhMap map = readBvhMap((kWholeBody / "bvh_map.yaml").string());
        timeBvhFrames(state, model, makeBvhTargets(makeModelBvh(model, map, makeSwing(model, 240, 1.0 / 120), 1.0 / 120), map, model));
    })->Unit(benchmark::kMillisecond);
    if (!std::filesystem::exists(kKick)) {
        std::cerr << "InverseKinematics/whole_body/kick_warm skipped: " << kKick << " is absent\n";
        return true;
    }
    benchmark::RegisterBenchmark("InverseKinematics/whole_body/kick_warm", [](benchmark::State& state) {
        const Model model = loadModel((kWholeBody / "whole_body.yaml").string(), {});
        const BvhMap map = readBvhMap((kWholeBody / "bvh_map.yaml").string());
        // Scaled, with the map's points scaled with it, as `sinew ik` fits it.
        const BvhFit fit = prepareBvhFit(model, readBvhFile(kKick.string()), map, true);
        timeBvhFrames(state, fit.model, fit.targets);
    })->Unit(benchmark::kMillisecond);
    return true;
}();

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

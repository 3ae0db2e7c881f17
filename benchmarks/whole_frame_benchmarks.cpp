// The paper's whole frame from motion capture on the shipped whole-body model: WholeFrame/<lp|qp>/kick, per
// frame of CMU's kick 11_01.bvh (when ../shared has it), inverse kinematics warm-started from the previous
// frame's solution (solveInverseKinematics: the fit and the virtual links' balance) then
// TensionAnalysis::calcFrame (inverse dynamics, wire paths and Jacobian, the distribution with the support
// foot's contact unknowns), as `sinew ik` then `sinew tensions --method lp|qp --max-tension 1e6 --lowpass 6`
// run them. The motion is prepared once beforehand as those commands prepare it: the model scaled to the
// subject, the whole capture fitted, the fit's coordinates low-pass filtered at 6 Hz and splined for speeds
// and accelerations, the contact frames detected. A timed frame's distribution uses that processed frame (a
// causal pipeline would differentiate its own recent fits; the work per frame is the same). Counters:
// ik_ms and tensions_ms, the two parts' medians in the thread's CPU time, ik_mean_ms and tensions_mean_ms
// their means; the model's sizes.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "frame_clock.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/tools/bvh_inverse_kinematics.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/motion_contacts.hpp"
#include "sinew/tools/motion_frames.hpp"
#include "sinew/tools/tension_analysis.hpp"

namespace sinew {
namespace {

const std::filesystem::path kWholeBody = std::filesystem::path(SINEW_SOURCE_DIR) / "models/whole_body";
const std::filesystem::path kKick = std::filesystem::path(SINEW_SHARED_DIR) / "data/cmu_mocap/11_01.bvh";

struct Kick {
    BvhInverseKinematics fit;
    BvhFit problem;                                 // the same model, its targets
    std::vector<InverseKinematicsTargets> targets;  // per frame, in the fit's task order
    CoordinateTrajectory trajectory;
    std::vector<Eigen::VectorXd> q, u, udot;  // the processed frames
    StorageTable contactTable;
    std::unique_ptr<MotionContacts> contacts;
};

const Kick& getKick() {
    static const std::unique_ptr<Kick> kick = [] {
        auto prepared = std::make_unique<Kick>();
        const Model model = loadModel((kWholeBody / "whole_body.yaml").string(), {});
        const BvhMap map = readBvhMap((kWholeBody / "bvh_map.yaml").string());
        const BvhMotion motion = readBvhFile(kKick.string());
        prepared->problem = prepareBvhFit(model, motion, map, true);
        prepared->fit = runBvhInverseKinematics(prepared->problem, {});
        const BvhTargets& targets = prepared->problem.targets;
        for (std::size_t f = 0; f < targets.capture.positions.size(); ++f)
            prepared->targets.push_back({targets.capture.positions[f], Eigen::VectorXd(), targets.orientations[f]});
        const Model& fitted = prepared->fit.model;
        prepared->trajectory = preprocessCoordinateSamples(
            fitted, readCoordinateSamples(fitted, makeInverseKinematicsTable(fitted, prepared->fit.result)), 6,
            -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
        forEachMotionFrame(fitted, prepared->trajectory, nullptr, [&](const MotionFrame& frame) {
            prepared->q.push_back(frame.q);
            prepared->u.push_back(frame.u);
            prepared->udot.push_back(frame.udot);
        });
        prepared->contacts = std::make_unique<MotionContacts>(fitted, prepared->trajectory, ContactDetectionOptions{},
                                                              prepared->contactTable);
        return prepared;
    }();
    return *kick;
}

void timeWholeFrames(benchmark::State& state, const char* method) {
    const Kick& kick = getKick();
    const Model& model = kick.fit.model;
    const std::size_t frames = kick.targets.size();
    if (kick.q.size() != frames || kick.fit.result.motion.q.size() != frames) {
        state.SkipWithError("the processed motion's frames are not the capture's");
        return;
    }
    // The tasks runInverseKinematics sets for a BVH capture: every joint centre at weight 1, the frames.
    std::vector<MarkerTask> tasks;
    for (const Marker& marker : kick.problem.targets.markers) tasks.push_back({marker.name, 1});
    InverseKinematicsSolver solver(model, kick.problem.targets.markers, tasks, {}, {}, kick.problem.targets.orientationTasks);
    TensionAnalysisOptions options;
    options.method = method;
    options.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), 1e6);
    options.columns.push_back(kick.contacts->getColumns());
    TensionAnalysis analysis(model, options);
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    std::vector<double> ikMs, tensionMs;
    std::size_t k = 1;
    for (auto _ : state) {
        const double start = cpuMilliseconds();
        const InverseKinematicsMotion fitted = solveInverseKinematics(solver, kick.fit.result.motion.q[k - 1], {kick.targets[k]});
        const double fittedAt = cpuMilliseconds();
        kick.contacts->prepareFrame(static_cast<int>(k));
        const TensionFrame& frame = analysis.calcFrame(kick.q[k], kick.u[k], kick.udot[k], noLoads);
        const double solvedAt = cpuMilliseconds();
        benchmark::DoNotOptimize(&fitted);
        benchmark::DoNotOptimize(&frame);
        ikMs.push_back(fittedAt - start);
        tensionMs.push_back(solvedAt - fittedAt);
        if (++k == frames) {
            k = 1;
            analysis.reset();
        }
    }
    state.counters["ik_ms"] = medianOf(ikMs);
    state.counters["tensions_ms"] = medianOf(tensionMs);
    state.counters["ik_mean_ms"] = meanOf(ikMs);
    state.counters["tensions_mean_ms"] = meanOf(tensionMs);
    state.counters["frames"] = static_cast<double>(frames);
    state.counters["links"] = model.getNumLinks();
    state.counters["dof"] = model.getNumU();
    state.counters["wires"] = model.getNumWires();
}

const bool kRegistered = [] {
    if (!std::filesystem::exists(kKick)) {
        std::cerr << "WholeFrame/<lp|qp>/kick skipped: " << kKick << " is absent\n";
        return false;
    }
    for (const char* method : {"lp", "qp"})
        benchmark::RegisterBenchmark((std::string("WholeFrame/") + method + "/kick").c_str(),
                                     [method](benchmark::State& state) { timeWholeFrames(state, method); })
            ->Unit(benchmark::kMillisecond);
    return true;
}();

}  // namespace
}  // namespace sinew

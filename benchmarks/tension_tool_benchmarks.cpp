// Wire tensions from motion, the whole frame: Tensions/<lp|qp|so>/<arm26|gait2354>/<cold|warm>. One frame is
// TensionAnalysis::calcFrame (inverse dynamics, wire paths and Jacobian, the distribution) on OpenSim's
// example motions (../shared/data/opensim), prepared as `sinew tensions` prepares them: coordinates low-pass
// filtered at the setups' 6 Hz, quintic splines, measured loads per link. That preparation is done once,
// outside the timing, as it is per motion rather than per frame. Frames are visited in order; the analysis
// is reset when the motion wraps round, as after any jump. "warm": one analysis carries its warm start from
// frame to frame; "cold": reset() before each frame. Registered only when the data are present.
//
// OpenSim 4.4.1 on arm26 static optimization: 6.6 ms per frame (../shared/data/opensim/README.md).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/data.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/measured_loads.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/tools/tension_analysis.hpp"

namespace sinew {
namespace {

const std::filesystem::path kOpenSimData = std::filesystem::path(SINEW_SHARED_DIR) / "data/opensim";
const std::filesystem::path kArmSetup = kOpenSimData / "arm26/arm26_Setup_StaticOptimization.xml";
const std::filesystem::path kGaitSetup = kOpenSimData / "gait2354/subject01_Setup_InverseDynamics.xml";

// One motion's frames, ready for calcFrame.
struct Motion {
    std::unique_ptr<Model> model;
    std::vector<Eigen::VectorXd> q, u, udot;
    std::vector<std::vector<SpatialVector>> linkForces;  // one per link per frame (Data::F_G convention)
};

Motion prepareMotion(const std::string& modelFile, const std::string& coordinatesFile,
                     const std::string& externalLoadsFile, double lowpassCutoffHz, double startTime, double finalTime) {
    Motion motion;
    motion.model = std::make_unique<Model>(loadModel(modelFile, {}));
    const Model& model = *motion.model;
    const CoordinateSamples samples = readCoordinateSamples(model, readStorageFile(coordinatesFile));
    const CoordinateTrajectory trajectory =
        preprocessCoordinateSamples(model, samples, lowpassCutoffHz, startTime, finalTime);
    std::optional<MeasuredLoads> measured;
    if (!externalLoadsFile.empty()) measured.emplace(model, readExternalLoads(externalLoadsFile));
    Data data(model);
    for (Eigen::Index i = 0; i < trajectory.times.size(); ++i) {
        motion.q.push_back(trajectory.q.row(i).transpose());
        motion.u.push_back(trajectory.qdot.row(i).transpose());
        motion.udot.push_back(trajectory.qddot.row(i).transpose());
        std::vector<SpatialVector> forces(static_cast<std::size_t>(model.getNumLinks()));
        calcAppliedLinkForces(model, measured ? &*measured : nullptr, data, trajectory.times[i], motion.q.back(), forces);
        motion.linkForces.push_back(std::move(forces));
    }
    return motion;
}

// arm26's static optimization setup: the elbow-flexion motion, 6 Hz, 0 to 1 s.
const Motion& getArm26() {
    static const Motion motion = [] {
        const AnalyzeSetup setup = readAnalyzeSetup(kArmSetup.string());
        return prepareMotion(setup.modelFile, setup.coordinatesFile, setup.externalLoadsFile,
                             setup.lowpassCutoffFrequencyForCoordinates, setup.initialTime, setup.finalTime);
    }();
    return motion;
}

// gait2354's inverse dynamics setup: walking with the ground reactions, 6 Hz, 0.4 to 1.6 s. No wire reaches
// the pelvis's six DOFs: their generalized force is each frame's unactuated residual.
const Motion& getGait2354() {
    static const Motion motion = [] {
        const InverseDynamicsSetup setup = readInverseDynamicsSetup(kGaitSetup.string());
        return prepareMotion(setup.modelFile, setup.coordinatesFile, setup.externalLoadsFile,
                             setup.lowpassCutoffFrequencyForCoordinates, setup.startTime, setup.endTime);
    }();
    return motion;
}

void timeFrames(benchmark::State& state, const Motion& motion, const std::string& method, bool warm) {
    const Model& model = *motion.model;
    TensionAnalysisOptions options;
    options.method = method;
    TensionAnalysis analysis(model, options);
    const std::size_t frames = motion.q.size();
    double iterations = 0, unactuatedDofs = 0;
    int notOptimal = 0;
    std::size_t k = 0;
    for (auto _ : state) {
        if (!warm || k == 0) analysis.reset();
        const TensionFrame& frame = analysis.calcFrame(motion.q[k], motion.u[k], motion.udot[k], motion.linkForces[k]);
        benchmark::DoNotOptimize(frame.tension.data());
        iterations += frame.iterations;
        notOptimal += frame.status != DistributionStatus::Optimal;
        for (char unactuated : frame.unactuated) unactuatedDofs += unactuated;
        k = (k + 1) % frames;
    }
    const double n = static_cast<double>(state.iterations());
    state.counters["links"] = model.getNumLinks();
    state.counters["dof"] = model.getNumU();
    state.counters["wires"] = model.getNumWires();
    state.counters["frames"] = static_cast<double>(frames);
    state.counters["unactuated_dof"] = unactuatedDofs / n;
    state.counters["iterations"] = iterations / n;
    state.counters["not_optimal_share"] = notOptimal / n;  // of the frames timed
}

const bool kRegistered = [] {
    for (const std::filesystem::path& setup : {kArmSetup, kGaitSetup})
        if (!std::filesystem::exists(setup)) {
            std::cerr << "Tensions/<method>/<arm26|gait2354> benchmarks skipped: " << setup << " is absent\n";
            return false;
        }
    const std::pair<const char*, const Motion& (*)()> motions[] = {{"arm26", getArm26}, {"gait2354", getGait2354}};
    for (const std::string method : {"lp", "qp", "so"})
        for (const auto& [name, getMotion] : motions)
            for (bool warm : {false, true}) {
                const std::string id = "Tensions/" + method + "/" + name + (warm ? "/warm" : "/cold");
                benchmark::RegisterBenchmark(id.c_str(), [method, getMotion, warm](benchmark::State& state) {
                    timeFrames(state, getMotion(), method, warm);
                })->Unit(benchmark::kMillisecond);
            }
    return true;
}();

}  // namespace
}  // namespace sinew

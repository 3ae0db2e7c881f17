// Tension distribution per frame: Tensions/<lp|qp|so>/<model>/<cold|warm>. One frame is the distribution
// step alone (the wire Jacobian and the problem's values are computed beforehand, outside the timing), on a
// smooth sequence of poses whose generalized forces come from known tensions and loop forces plus a smooth
// perturbation that the bounds do not let the wires follow exactly, so warm starts meet what they would in
// a motion. "warm": one solver for the sequence; "cold": a fresh solver per frame. Frames are visited
// forwards then backwards, so consecutive frames are always neighbours.
//
// Besides Google Benchmark's mean, each run reports the median and the largest time of a frame
// (median_ms, max_ms), the model's sizes, the mean solver iterations, active wires, Z = ½|tau - A x|², and
// the frames that did not come back optimal.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/random_model.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/lp_solver.hpp"
#include "sinew/tensions/static_optimization.hpp"
#include "sinew/tensions/wire_problem.hpp"

namespace {

constexpr int kFrames = 200;
constexpr double kFrameTime = 0.005;  // s: 200 frames, 1 s of motion

// The frames of one model: problems (values filled), known forces, and what SO needs.
struct Sequence {
    std::unique_ptr<sinew::Model> model;
    Eigen::VectorXd maxTension;
    std::vector<sinew::DistributionProblem> frames;
    std::vector<Eigen::VectorXd> forceMultiplier;  // (numWires) per frame, for SO
};

// The whole-body-sized random model of the forward-dynamics benchmarks (benchmark_models.cpp, "wholebody"):
// a random tree of 53 links, ball joints, free root, 4 loops, 547 wires.
sinew::Model makeWholeBody() {
    sinew::RandomModelOptions options;
    options.numLinks = 53;
    options.topology = sinew::RandomModelOptions::Topology::RandomTree;
    options.rootJoint = sinew::JointType::Free;
    options.pinFraction = 0;
    options.numLoops = 4;
    options.numWires = 547;
    options.maxViaPoints = 1;
    options.seed = 1;
    return sinew::generateRandomModel(options);
}

const Sequence& getWholeBody() {
    static const Sequence sequence = [] {
        Sequence s;
        s.model = std::make_unique<sinew::Model>(makeWholeBody());
        const sinew::Model& model = *s.model;
        const int numWires = model.getNumWires();
        std::mt19937 rng(2);
        std::uniform_real_distribution<double> unit(0, 1);
        s.maxTension.resize(numWires);
        Eigen::VectorXd phase(numWires), perturbationPhase(numWires);
        for (int w = 0; w < numWires; ++w) {
            s.maxTension[w] = 200 + 1300 * unit(rng);
            phase[w] = 2 * M_PI * unit(rng);
            perturbationPhase[w] = 2 * M_PI * unit(rng);
        }
        const sinew::WireProblemBuilder builder(model, s.maxTension);
        sinew::Data data(model);
        const Eigen::VectorXd u = sinew::generateRandomSpeeds(model, rng, 1.0);
        Eigen::MatrixXd J(numWires, model.getNumU());
        for (int k = 0; k < kFrames; ++k) {
            const double t = k * kFrameTime;
            const Eigen::VectorXd q = sinew::integrateCoordinates(model, model.getDefaultQ(), u, t);
            sinew::calcPositionKinematics(model, data, q);
            sinew::calcWirePaths(model, data);
            sinew::calcWireJacobian(model, data, J);
            sinew::DistributionProblem problem = builder.makeProblem();
            builder.update(data, J, Eigen::VectorXd::Zero(model.getNumU()), problem);
            // Known tensions, 5 to 75 % of the maximum, and loop forces of tens of newtons.
            Eigen::VectorXd x(problem.getNumVariables());
            for (int w = 0; w < numWires; ++w)
                x[w] = s.maxTension[w] * (0.4 + 0.2 * std::sin(2 * M_PI * t + phase[w]) +
                                          0.15 * std::sin(3 * M_PI * t + perturbationPhase[w]));
            for (int f = 0; f < problem.numFree; ++f) x[numWires + f] = 30 * std::cos(2 * M_PI * t + f);
            problem.target = problem.A * x;
            s.frames.push_back(std::move(problem));
            s.forceMultiplier.push_back((0.8 + 0.2 * (phase.array() + 4 * t).cos()).matrix());
        }
        return s;
    }();
    return sequence;
}

int frameAt(std::int64_t i) {  // 0, 1, ..., 199, 198, ..., 1, 0, 1, ...
    const int period = 2 * (kFrames - 1);
    const int k = static_cast<int>(i % period);
    return k < kFrames ? k : period - k;
}

struct FrameStatistics {
    std::vector<double> ms;
    double iterations = 0, active = 0, torqueError = 0;
    int notOptimal = 0;

    void add(double milliseconds, const sinew::DistributionResult& r) {
        ms.push_back(milliseconds);
        iterations += r.iterations, active += r.activeVariables, torqueError += r.torqueError;
        notOptimal += r.status != sinew::DistributionStatus::Optimal;
    }
    void report(benchmark::State& state, const Sequence& s) {
        const sinew::DistributionProblem& p = s.frames.front();
        state.counters["dof"] = p.getNumRows();
        state.counters["wires"] = s.model->getNumWires();
        state.counters["free"] = p.numFree;
        state.counters["nonzeros"] = static_cast<double>(p.A.nonZeros());
        if (ms.empty()) return;
        const double n = static_cast<double>(ms.size());
        std::sort(ms.begin(), ms.end());
        state.counters["median_ms"] = ms[ms.size() / 2];
        state.counters["max_ms"] = ms.back();
        state.counters["iterations"] = iterations / n;
        state.counters["active_wires"] = active / n;
        state.counters["Z"] = torqueError / n;
        state.counters["not_optimal"] = notOptimal;
    }
};

// Times solve(frame) -> result per frame; `reset` before each frame when cold.
template <class Solve, class Reset>
void timeFrames(benchmark::State& state, bool warm, Solve&& solve, Reset&& reset) {
    const Sequence& s = getWholeBody();
    FrameStatistics statistics;
    std::int64_t i = 0;
    for (auto _ : state) {
        const int k = frameAt(i++);
        const auto start = std::chrono::steady_clock::now();
        if (!warm) reset();
        const sinew::DistributionResult& result = solve(static_cast<std::size_t>(k));
        const auto stop = std::chrono::steady_clock::now();
        statistics.add(std::chrono::duration<double, std::milli>(stop - start).count(), result);
        benchmark::DoNotOptimize(result.x.data());
    }
    statistics.report(state, s);
}

void lp(benchmark::State& state, bool warm) {
    const Sequence& s = getWholeBody();
    sinew::LpSolver solver;
    sinew::DistributionResult result;
    timeFrames(
        state, warm, [&](std::size_t k) -> const sinew::DistributionResult& { return solver.solve(s.frames[k], result), result; },
        [&] { solver.reset(); });
}

void qp(benchmark::State& state, bool warm) {
    const Sequence& s = getWholeBody();
    sinew::ActiveSetSolver solver;
    sinew::DistributionResult result;
    timeFrames(
        state, warm, [&](std::size_t k) -> const sinew::DistributionResult& { return solver.solve(s.frames[k], result), result; },
        [&] { solver.reset(); });
}

// OpenSim's static optimization with a reserve (optimal force 1 N m or N, unbounded) on every DOF.
void so(benchmark::State& state, bool warm) {
    const Sequence& s = getWholeBody();
    sinew::StaticOptimizationSettings settings;
    settings.maxIsometricForce = s.maxTension;
    for (int i = 0; i < s.frames.front().getNumRows(); ++i) settings.reserves.push_back({"reserve", i, 1.0});
    sinew::StaticOptimization solver(settings);
    sinew::StaticOptimizationResult result;
    timeFrames(
        state, warm,
        [&](std::size_t k) -> const sinew::DistributionResult& {
            solver.solve(s.frames[k], s.forceMultiplier[k], result);
            return result.distribution;
        },
        [&] { solver.reset(); });
}

BENCHMARK_CAPTURE(lp, warm, true)->Name("Tensions/lp/wholebody/warm")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(lp, cold, false)->Name("Tensions/lp/wholebody/cold")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(qp, warm, true)->Name("Tensions/qp/wholebody/warm")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(qp, cold, false)->Name("Tensions/qp/wholebody/cold")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(so, warm, true)->Name("Tensions/so/wholebody/warm")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(so, cold, false)->Name("Tensions/so/wholebody/cold")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

// Wire tensions on the whole-body-sized random model, per frame:
//
// - Tensions/<lp|qp|so>/wholebody/<cold|warm>: the distribution step alone (the wire Jacobian and the
//   problem's values are computed beforehand, outside the timing). The generalized forces come from known
//   tensions and loop forces plus a smooth perturbation that the bounds do not let the wires follow exactly,
//   so warm starts meet what they would in a motion. "warm": one solver for the sequence, its first frame
//   solved before the timing (a real-time loop pays that cold start once); "cold": a fresh solver per frame.
// - Tensions/<lp|qp|so>/wholebody/frame: the whole frame, TensionAnalysis::calcFrame (inverse dynamics,
//   wire paths and Jacobian, the problem's values, the warm-started distribution), on the same poses with
//   the motion's own speeds and accelerations, under applied loads (as measured loads would be given)
//   chosen so that inverse dynamics gives exactly what the frame's known tensions and loop forces produce.
//   Without them most frames are infeasible: the random wires do not span every direction of every joint,
//   and the LP then adds a phase-1 solve per frame.
//
// The sequence is a smooth motion of 200 frames over 1 s; frames are visited forwards then backwards, so
// consecutive frames are always neighbours. Besides Google Benchmark's mean, each run reports the median,
// 99th percentile and largest time of a frame in wall-clock time (median_ms, p99_ms, max_ms) and in the
// thread's CPU time (cpu_median_ms, ...), the model's sizes, the mean solver iterations, active wires,
// Z = ½|tau - A x|² (for the frame: over the distributed DOFs), and the frames not optimal; the warm LP
// also the share of frames its own warm path solved without Clp.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "frame_clock.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "support/random_model.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/lp_solver.hpp"
#include "sinew/tensions/static_optimization.hpp"
#include "sinew/tensions/wire_problem.hpp"
#include "sinew/tools/tension_analysis.hpp"

namespace {

using sinew::cpuMilliseconds;
using sinew::wallMilliseconds;

constexpr int kFrames = 200;
constexpr double kFrameTime = 0.005;  // s: 200 frames, 1 s of motion

// The frames of one model: the motion, its problems (values filled), known forces, and what SO needs.
struct Sequence {
    std::unique_ptr<sinew::Model> model;
    Eigen::VectorXd maxTension;
    std::vector<Eigen::VectorXd> q, u, udot;
    std::vector<std::vector<sinew::SpatialVector>> loads;  // per frame, one per link (Data::F_G convention)
    std::vector<sinew::DistributionProblem> frames;
    std::vector<Eigen::VectorXd> forceMultiplier;  // (numWires) per frame, for SO
};

// The whole-body-sized random model of the forward-dynamics benchmarks (benchmark_models.cpp, "wholebody":
// a random tree of 53 links, ball joints, free root, 4 loops, 547 wires) plus 6 virtual links, each where a
// forked wire meets (two heads in, one tail out: 18 more wires). A virtual link's six DOF rows are equality
// rows (its equilibrium) of the problem.
sinew::Model makeWholeBody() {
    sinew::RandomModelOptions options;
    options.numLinks = 53;
    options.topology = sinew::RandomModelOptions::Topology::RandomTree;
    options.rootJoint = sinew::JointType::Free;
    options.pinFraction = 0;
    options.numLoops = 4;
    options.numWires = 547;
    options.maxViaPoints = 1;
    options.numVirtualLinks = 6;
    options.seed = 1;
    return sinew::generateRandomModel(options);
}

// Applied loads, one spatial force per link, under which inverse dynamics at (q, u, udot) gives exactly
// `target`. Link i carries W_i less its children's W (moved to its origin), so joint i sees its subtree's
// sum, W_i: the least-norm spatial force whose generalized force on joint i is tau_i - target_i (tau: the
// inverse dynamics without loads; applied forces lower what the joints must supply).
std::vector<sinew::SpatialVector> makeLoadsGiving(const sinew::Model& model, sinew::Data& data, const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& u, const Eigen::VectorXd& udot,
                                                  const Eigen::VectorXd& target) {
    const std::size_t numLinks = static_cast<std::size_t>(model.getNumLinks());
    std::vector<sinew::SpatialVector> loads(numLinks, sinew::SpatialVector::Zero());
    Eigen::VectorXd tau(model.getNumU()), column(model.getNumU());
    sinew::calcInverseDynamics(model, data, q, u, udot, loads, tau);  // and the kinematics at q
    std::vector<sinew::SpatialVector> W(numLinks);
    for (std::size_t i = 0; i < numLinks; ++i) {
        const sinew::Joint& joint = model.getJoint(static_cast<int>(i));
        Eigen::MatrixXd jointRows(joint.nu, 6);  // generalized forces of joint i per unit spatial force on link i
        for (int c = 0; c < 6; ++c) {
            for (sinew::SpatialVector& F : data.scratchF_G) F.setZero();
            data.scratchF_G[i][c] = 1;
            sinew::calcGeneralizedForcesFromLinkForces(model, data, column);
            jointRows.col(c) = column.segment(joint.uStart, joint.nu);
        }
        W[i] = jointRows.completeOrthogonalDecomposition().solve(
            tau.segment(joint.uStart, joint.nu) - target.segment(joint.uStart, joint.nu));
    }
    for (std::size_t i = 0; i < numLinks; ++i) {
        loads[i] += W[i];
        const int parent = model.getJoint(static_cast<int>(i)).parent;
        if (parent == sinew::kGround) continue;
        const std::size_t p = static_cast<std::size_t>(parent);
        loads[p].head<3>() -= W[i].head<3>() + (data.p_GB[i] - data.p_GB[p]).cross(W[i].tail<3>());
        loads[p].tail<3>() -= W[i].tail<3>();
    }
    return loads;
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
        // Speeds u0 cos(2 pi t + speedPhase) per DOF (rad/s, m/s), integrated at each step's midpoint.
        const Eigen::VectorXd u0 = sinew::generateRandomSpeeds(model, rng, 1.0);
        Eigen::VectorXd speedPhase(model.getNumU());
        for (int i = 0; i < model.getNumU(); ++i) speedPhase[i] = 2 * M_PI * unit(rng);
        const auto speeds = [&](double t) { return u0.cwiseProduct((2 * M_PI * t + speedPhase.array()).cos().matrix()); };
        Eigen::VectorXd q = model.getDefaultQ();
        Eigen::MatrixXd J(numWires, model.getNumU());
        for (int k = 0; k < kFrames; ++k) {
            const double t = k * kFrameTime;
            if (k > 0) q = sinew::integrateCoordinates(model, q, speeds(t - 0.5 * kFrameTime), kFrameTime);
            s.q.push_back(q);
            s.u.push_back(speeds(t));
            s.udot.push_back(-2 * M_PI * u0.cwiseProduct((2 * M_PI * t + speedPhase.array()).sin().matrix()));
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
            s.loads.push_back(makeLoadsGiving(model, data, s.q.back(), s.u.back(), s.udot.back(), problem.target));
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

// What one frame gave, for the counters.
struct FrameOutcome {
    int iterations = 0, activeWires = 0;
    double torqueError = 0;
    sinew::DistributionStatus status = sinew::DistributionStatus::Failed;
};

FrameOutcome describe(const sinew::DistributionResult& r) {
    return {r.iterations, r.activeVariables, r.torqueError, r.status};
}

FrameOutcome describe(const sinew::TensionFrame& f) {
    double distributedError = 0;  // Z over the DOFs the wires and loops reach
    for (Eigen::Index r = 0; r < f.residual.size(); ++r)
        if (!f.unactuated[static_cast<std::size_t>(r)]) distributedError += 0.5 * f.residual[r] * f.residual[r];
    return {f.iterations, f.activeWires, distributedError, f.status};
}

struct FrameStatistics {
    std::vector<double> wallMs, cpuMs;
    double iterations = 0, active = 0, torqueError = 0;
    int notOptimal = 0;

    void add(double wall, double cpu, const FrameOutcome& frame) {
        wallMs.push_back(wall);
        cpuMs.push_back(cpu);
        iterations += frame.iterations, active += frame.activeWires, torqueError += frame.torqueError;
        notOptimal += frame.status != sinew::DistributionStatus::Optimal;
    }
    static void reportTimes(benchmark::State& state, const std::string& prefix, std::vector<double>& ms) {
        std::sort(ms.begin(), ms.end());
        state.counters[prefix + "median_ms"] = ms[ms.size() / 2];
        state.counters[prefix + "p99_ms"] = ms[ms.size() * 99 / 100];
        state.counters[prefix + "max_ms"] = ms.back();
    }
    void report(benchmark::State& state, const Sequence& s) {
        const sinew::DistributionProblem& p = s.frames.front();
        state.counters["links"] = s.model->getNumLinks();
        state.counters["virtual_links"] = static_cast<double>(std::count_if(
            s.model->getLinks().begin(), s.model->getLinks().end(), [](const sinew::Link& l) { return l.isVirtual; }));
        state.counters["loops"] = s.model->getNumLoops();
        state.counters["dof"] = p.getNumRows();
        state.counters["equality_rows"] = static_cast<double>(std::count(p.isEquality.begin(), p.isEquality.end(), true));
        state.counters["wires"] = s.model->getNumWires();
        state.counters["free"] = p.numFree;
        state.counters["nonzeros"] = static_cast<double>(p.A.nonZeros());
        if (wallMs.empty()) return;
        const double n = static_cast<double>(wallMs.size());
        reportTimes(state, "", wallMs);
        reportTimes(state, "cpu_", cpuMs);
        state.counters["iterations"] = iterations / n;
        state.counters["active_wires"] = active / n;
        state.counters["Z"] = torqueError / n;
        state.counters["not_optimal"] = notOptimal;
    }
};

// Times solve(frame) per frame; `reset` before each frame when cold. Warm: frame 0 is solved before the
// timing.
template <class Solve, class Reset>
void timeFrames(benchmark::State& state, bool warm, Solve&& solve, Reset&& reset) {
    const Sequence& s = getWholeBody();
    FrameStatistics statistics;
    if (warm) solve(0);
    std::int64_t i = warm ? 1 : 0;
    for (auto _ : state) {
        const int k = frameAt(i++);
        const double wall = wallMilliseconds(), cpu = cpuMilliseconds();
        if (!warm) reset();
        const auto& result = solve(static_cast<std::size_t>(k));
        const double cpuStop = cpuMilliseconds(), wallStop = wallMilliseconds();
        statistics.add(wallStop - wall, cpuStop - cpu, describe(result));
        benchmark::DoNotOptimize(&result);
    }
    statistics.report(state, s);
}

void lp(benchmark::State& state, bool warm) {
    const Sequence& s = getWholeBody();
    sinew::LpSolver solver;
    sinew::DistributionResult result;
    int solves = 0;
    timeFrames(
        state, warm,
        [&](std::size_t k) -> const sinew::DistributionResult& { return ++solves, solver.solve(s.frames[k], result), result; },
        [&] { solver.reset(); });
    // The share of frames the warm dual simplex solved without Clp (docs/tensions.md, "The warm path").
    if (warm) state.counters["warm_path_share"] = solver.getWarmFrames() / static_cast<double>(solves);
}

void qp(benchmark::State& state, bool warm) {
    const Sequence& s = getWholeBody();
    sinew::ActiveSetSolver solver;
    sinew::DistributionResult result;
    timeFrames(
        state, warm, [&](std::size_t k) -> const sinew::DistributionResult& { return solver.solve(s.frames[k], result), result; },
        [&] { solver.reset(); });
}

// A reserve (optimal force 1 N m or N, unbounded) on every DOF, as OpenSim's static optimization setups add.
std::vector<sinew::ReserveActuator> makeReserves(int numDofs) {
    std::vector<sinew::ReserveActuator> reserves(static_cast<std::size_t>(numDofs));
    for (int i = 0; i < numDofs; ++i) {
        reserves[static_cast<std::size_t>(i)].name = "reserve" + std::to_string(i);
        reserves[static_cast<std::size_t>(i)].dof = i;
    }
    return reserves;
}

// OpenSim's static optimization with a reserve on every DOF.
void so(benchmark::State& state, bool warm) {
    const Sequence& s = getWholeBody();
    sinew::StaticOptimizationSettings settings;
    settings.maxIsometricForce = s.maxTension;
    settings.reserves = makeReserves(s.frames.front().getNumRows());
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

// The whole frame with a warm-started TensionAnalysis; SO with max isometric force alone (the random
// model's wires are spring-dampers, not muscles) and a reserve on every DOF.
void frame(benchmark::State& state, const char* method) {
    const Sequence& s = getWholeBody();
    const sinew::Model& model = *s.model;
    sinew::TensionAnalysisOptions options;
    options.method = method;
    options.maxTension = s.maxTension;
    options.useMusclePhysiology = false;
    if (std::string(method) == "so") options.reserves = makeReserves(model.getNumU());
    sinew::TensionAnalysis analysis(model, options);
    timeFrames(
        state, true,
        [&](std::size_t k) -> const sinew::TensionFrame& { return analysis.calcFrame(s.q[k], s.u[k], s.udot[k], s.loads[k]); },
        [&] { analysis.reset(); });
}

BENCHMARK_CAPTURE(lp, warm, true)->Name("Tensions/lp/wholebody/warm")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(lp, cold, false)->Name("Tensions/lp/wholebody/cold")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(qp, warm, true)->Name("Tensions/qp/wholebody/warm")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(qp, cold, false)->Name("Tensions/qp/wholebody/cold")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(so, warm, true)->Name("Tensions/so/wholebody/warm")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(so, cold, false)->Name("Tensions/so/wholebody/cold")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(frame, lp, "lp")->Name("Tensions/lp/wholebody/frame")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(frame, qp, "qp")->Name("Tensions/qp/wholebody/frame")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(frame, so, "so")
    ->Name("Tensions/so/wholebody/frame")
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

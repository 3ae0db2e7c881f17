// sinew's benchmarks: one forward-dynamics evaluation by sinew (ForwardDynamics/sinew/<model>, the default
// schedule; ForwardDynamics/sinew_balanced/<model>, the balanced one) and by Simbody
// (ForwardDynamics/simbody/<model>, the wires as the plugin's elements; ForwardDynamics/simbody_fused/<model>,
// the wires as one lean element) at the same state of the same model in the same run, so the ratios do not
// depend on the machine; on bare ball-joint trees also a hand-written articulated-body algorithm
// (ForwardDynamics/aba/<model>, the floor); and what the wires cost on the sinew side, the dense wire Jacobian
// (WireJacobian/<model>), the sparse J^T the tension problems take (WireJacobianSparse/<model>) or the
// generalized forces of all tensions without forming J (WireForces/<model>). Where libmujoco is installed,
// MuJoCo's mj_forward on the same model written as MJCF (ForwardDynamics/mujoco/<model>).
//
// Every benchmark is registered once per row of the model table (benchmark_models.hpp); the model sizes go
// into each result's counters and into the run's context, so a JSON file says what was measured.
// scripts/bench.sh runs this program and scripts/plot_scaling.py pairs and plots the results.
#include "sinew/plugin/ndebug_guard.hpp"

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <algorithm>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "support/allocation_counter.hpp"
#include "benchmark_models.hpp"
#include "reference_aba.hpp"
#include "sinew/core/assembly_schedule.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/mjcf_model_writer.hpp"
#ifdef SINEW_HAVE_MUJOCO
#include "mujoco_peer.hpp"
#endif

namespace sinew_benchmarks {
namespace {

// sinew and Simbody must compute the same accelerations before their times mean anything.
constexpr double kUdotTolerance = 1e-6;

// Prepares the fixture's state and checks the two engines agree there; false (and the benchmark skipped
// with the reason) when they do not.
bool prepareAgreedState(benchmark::State& state, ModelFixture* fixture) {
    fixture->prepare();
    state.counters["udot_rel_diff"] = fixture->getUdotDifference();
    // 1 where the loops locked the perturbed pose and the state is at the default pose instead.
    state.counters["default_pose"] = fixture->projectionFellBack() ? 1 : 0;
    if (!(fixture->getUdotDifference() <= kUdotTolerance)) {
        state.SkipWithError(("sinew's and Simbody's udot differ by " + std::to_string(fixture->getUdotDifference()) +
                             " (relative) at the benchmark state")
                                .c_str());
        return false;
    }
    return true;
}

// The heap allocations of one evaluation after a first one (which may size caches), as the counter
// `allocations`; untimed.
template <class Evaluate>
void countAllocations(benchmark::State& state, Evaluate&& evaluate) {
    evaluate();
    const long long before = sinew::test::getAllocationCount();
    evaluate();
    state.counters["allocations"] = static_cast<double>(sinew::test::getAllocationCount() - before);
}

// Everything an integrator step needs from sinew for udot: link poses and velocities, wire paths, speeds
// and tensions, the wires' forces on the links, and the assembly-disassembly forward dynamics. The buffers
// (Data, the schedule and its ForwardDynamicsData) are built once, outside the timing loop. One thread, as
// Simbody runs.
void timeSinewForwardDynamics(benchmark::State& state, ModelFixture* fixture, sinew::AssemblySchedule::Kind kind,
                              int threads = 1) {
    fixture->setCounters(state);
    if (!prepareAgreedState(state, fixture)) return;
    const sinew::Model& model = fixture->getModel();
    const Eigen::VectorXd& q = fixture->getQ();
    const Eigen::VectorXd& u = fixture->getU();
    const Eigen::VectorXd& tau = fixture->getTau();
    sinew::Data data(model);
    const sinew::AssemblySchedule schedule(model, kind);
    sinew::ForwardDynamicsData fd(model, schedule);
    sinew::VirtualLinkEquilibriumData equilibrium(model);
    Eigen::VectorXd tensions(model.getNumWires());
    auto evaluate = [&] {
        sinew::calcPositionKinematics(model, data, q);
        sinew::calcVelocityKinematics(model, data, u);
        sinew::calcWirePaths(model, data);
        sinew::calcWireSpeeds(model, data);
        // Warm-started from q's virtual-link poses, as Simbody's force element is from its last solve.
        sinew::calcVirtualLinkEquilibrium(model, data, 0.0, equilibrium);
        sinew::calcWireTensions(model, data, 0.0, tensions);
        sinew::calcWireLinkForces(model, data, tensions);
        sinew::calcForwardDynamics(model, schedule, data, tau, data.F_G, fd, threads);
    };
    countAllocations(state, evaluate);
    // This schedule's own answer, checked as prepareAgreedState checked the default one's.
    const double udotDifference = fixture->calcUdotDifferenceFromSimbody(fd.udot);
    state.counters["udot_rel_diff"] = udotDifference;
    if (!(udotDifference <= kUdotTolerance)) {
        state.SkipWithError("this schedule's udot differs from Simbody's at the benchmark state");
        return;
    }
    for (auto _ : state) {
        evaluate();
        benchmark::DoNotOptimize(fd.udot.data());
        benchmark::ClobberMemory();
    }
    // The handles of the largest subassembly: an operation costs their square, so loops that stay open
    // across much of the tree show here.
    state.counters["max_handles"] = schedule.getMaxHandles();
    state.counters["threads"] = threads;
}

// The default schedule, Automatic: Serial (tips to root) unless Balanced does clearly less work.
void benchmarkSinewForwardDynamics(benchmark::State& state, ModelFixture* fixture) {
    timeSinewForwardDynamics(state, fixture, sinew::AssemblySchedule::Kind::Automatic);
}

// The Balanced schedule (pairs of neighbouring subassemblies, level by level), still on one thread: it
// closes loops sooner where the Serial schedule carries many open loops up a long chain.
void benchmarkSinewBalancedForwardDynamics(benchmark::State& state, ModelFixture* fixture) {
    timeSinewForwardDynamics(state, fixture, sinew::AssemblySchedule::Kind::Balanced);
}

// The Balanced schedule with each level's operations shared between the machine's cores (at least 2): the
// O(log N) form of the paper. Timed in wall-clock time (registered with UseRealTime).
void benchmarkSinewParallelForwardDynamics(benchmark::State& state, ModelFixture* fixture) {
    timeSinewForwardDynamics(state, fixture, sinew::AssemblySchedule::Kind::Balanced,
                             std::max(2, static_cast<int>(std::thread::hardware_concurrency())));
}

// Simbody's peer: writing q invalidates the Position stage and all above it, as an integrator step does,
// so realize recomputes kinematics, the wires, gravity, the articulated-body pass and the loop
// multipliers; tau sits in a Force::DiscreteForces, which q does not invalidate.
void timeSimbodyForwardDynamics(benchmark::State& state, const SimTK::MultibodySystem& system,
                                const SimTK::State& prepared) {
    SimTK::State s = prepared;
    const SimTK::Vector q = s.getQ();
    auto evaluate = [&] {
        s.updQ() = q;
        system.realize(s, SimTK::Stage::Acceleration);
    };
    countAllocations(state, evaluate);
    for (auto _ : state) {
        evaluate();
        benchmark::DoNotOptimize(&s.getUDot()[0]);
        benchmark::ClobberMemory();
    }
}

// The wires as the plugin's WireForce elements, one per wire.
void benchmarkSimbodyForwardDynamics(benchmark::State& state, ModelFixture* fixture) {
    fixture->setCounters(state);
    if (!prepareAgreedState(state, fixture)) return;
    timeSimbodyForwardDynamics(state, fixture->getSimbodyModel().getSystem(), fixture->getSimbodyState());
}

// The floor for a bare tree: a hand-written articulated-body algorithm (reference_aba.hpp), checked against
// Simbody's udot as sinew is.
void benchmarkReferenceAba(benchmark::State& state, ModelFixture* fixture) {
    fixture->setCounters(state);
    if (!prepareAgreedState(state, fixture)) return;
    ReferenceAba aba(fixture->getModel());
    Eigen::VectorXd udot(fixture->getModel().getNumU());
    aba.calcAccelerations(fixture->getQ(), fixture->getU(), fixture->getTau(), udot);
    const double udotDifference = fixture->calcUdotDifferenceFromSimbody(udot);
    state.counters["udot_rel_diff"] = udotDifference;
    if (!(udotDifference <= kUdotTolerance)) {
        state.SkipWithError("the reference ABA's udot differs from Simbody's at the benchmark state");
        return;
    }
    for (auto _ : state) {
        aba.calcAccelerations(fixture->getQ(), fixture->getU(), fixture->getTau(), udot);
        benchmark::DoNotOptimize(udot.data());
        benchmark::ClobberMemory();
    }
}

// The wires as one FusedWireForce.
void benchmarkFusedSimbodyForwardDynamics(benchmark::State& state, ModelFixture* fixture) {
    fixture->setCounters(state);
    if (!prepareAgreedState(state, fixture)) return;
    fixture->prepareFused();
    state.counters["udot_rel_diff"] = fixture->getFusedUdotDifference();
    if (!(fixture->getFusedUdotDifference() <= kUdotTolerance)) {
        state.SkipWithError("sinew's and the fused Simbody system's udot differ at the benchmark state");
        return;
    }
    timeSimbodyForwardDynamics(state, fixture->getFusedSimbodyModel().getSystem(), fixture->getFusedSimbodyState());
}

#ifdef SINEW_HAVE_MUJOCO
// MuJoCo's peer (mujoco_peer.hpp). Its model differs from sinew's where the writer's notes say: a tendon's
// spring also pushes when shorter than its rest length, where sinew's wire goes slack, and connects are soft
// constraints. So its udot is held to Simbody's only where neither applies (no loops, no slack wire); elsewhere
// the difference is the counter udot_rel_diff, and the geometry (tendon lengths against sinew's wire
// lengths) is what is checked.
void benchmarkMujocoForwardDynamics(benchmark::State& state, ModelFixture* fixture) {
    fixture->setCounters(state);
    if (!prepareAgreedState(state, fixture)) return;
    const sinew::Model& model = fixture->getModel();
    std::unique_ptr<MujocoPeer> loaded;
    try {
        loaded = std::make_unique<MujocoPeer>(model, fixture->getQ(), fixture->getU(), fixture->getTau());
    } catch (const std::runtime_error& error) {
        // MuJoCo's XML parser (tinyxml2) refuses bodies nested deeper than about 100: the long chains.
        state.SkipWithError(error.what());
        return;
    }
    MujocoPeer& peer = *loaded;
    peer.evaluate();
    sinew::Data data(model);
    sinew::calcPositionKinematics(model, data, fixture->getQ());
    sinew::calcVelocityKinematics(model, data, fixture->getU());
    sinew::calcWirePaths(model, data);
    sinew::calcWireSpeeds(model, data);
    Eigen::VectorXd tensions(model.getNumWires());
    sinew::calcWireTensions(model, data, 0.0, tensions);
    const int slackWires = static_cast<int>((tensions.array() <= 0).count());
    const double udotDifference = fixture->calcUdotDifferenceFromSimbody(peer.getUdot());
    state.counters["slack_wires"] = slackWires;
    state.counters["constraint_rows"] = peer.getNumConstraintRows();
    state.counters["udot_rel_diff"] = udotDifference;
    if (!(peer.calcTendonLengthDifference(data.wireLength) <= 1e-9)) {
        state.SkipWithError("MuJoCo's tendon lengths differ from sinew's wire lengths at the benchmark state");
        return;
    }
    if (model.getNumLoops() == 0 && slackWires == 0 && !(udotDifference <= kUdotTolerance)) {
        state.SkipWithError("MuJoCo's udot differs from Simbody's on a model where their dynamics are the same");
        return;
    }
    for (auto _ : state) {
        peer.evaluate();
        benchmark::ClobberMemory();
    }
}
#endif

// The part both wire benchmarks start from: link poses and wire paths at q.
void calcWireGeometry(const sinew::Model& model, sinew::Data& data, const Eigen::VectorXd& q) {
    sinew::calcPositionKinematics(model, data, q);
    sinew::calcWirePaths(model, data);
}

void benchmarkWireJacobian(benchmark::State& state, ModelFixture* fixture) {
    fixture->setCounters(state);
    fixture->prepare();
    const sinew::Model& model = fixture->getModel();
    sinew::Data data(model);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    for (auto _ : state) {
        calcWireGeometry(model, data, fixture->getQ());
        sinew::calcWireJacobian(model, data, J);
        benchmark::DoNotOptimize(J.data());
        benchmark::ClobberMemory();
    }
}

// J^T in the sparse form the tension problems take: the wires' span links only, no dense zeroing.
void benchmarkSparseWireJacobian(benchmark::State& state, ModelFixture* fixture) {
    fixture->setCounters(state);
    fixture->prepare();
    const sinew::Model& model = fixture->getModel();
    sinew::Data data(model);
    Eigen::SparseMatrix<double> Jt = sinew::makeWireJacobianTransposePattern(model);
    state.counters["nonzeros"] = static_cast<double>(Jt.nonZeros());
    for (auto _ : state) {
        calcWireGeometry(model, data, fixture->getQ());
        sinew::calcWireJacobianTranspose(model, data, Jt);
        benchmark::DoNotOptimize(Jt.valuePtr());
        benchmark::ClobberMemory();
    }
}

void benchmarkWireForces(benchmark::State& state, ModelFixture* fixture) {
    fixture->setCounters(state);
    fixture->prepare();
    const sinew::Model& model = fixture->getModel();
    sinew::Data data(model);
    // Fixed tensions (0 to 100 N): the pass's cost does not depend on them.
    Eigen::VectorXd tensions = 50.0 * (Eigen::VectorXd::Random(model.getNumWires()).array() + 1.0);
    Eigen::VectorXd tau(model.getNumU());
    for (auto _ : state) {
        calcWireGeometry(model, data, fixture->getQ());
        sinew::calcWireGeneralizedForces(model, data, tensions, tau);
        benchmark::DoNotOptimize(tau.data());
        benchmark::ClobberMemory();
    }
}

// Which models a kind of benchmark runs on.
enum class Scope {
    All,
    ModelsWithWires,   // a peer that differs from another only in how it computes the wires
    WireBenchmarkModels,  // ModelSpec::wireBenchmarks
    BareBallTrees,        // no loops, no wires, ball joints under a ball or free root: the reference ABA's
    MjcfWritable          // models the MJCF writer accepts (no virtual links, custom joints, wrapping...)
};

struct BenchmarkKind {
    const char* prefix;  // the result is named prefix + model name
    void (*run)(benchmark::State&, ModelFixture*);
    Scope scope;
    bool wallClock = false;  // several threads: wall-clock time, not the main thread's CPU time
};

constexpr BenchmarkKind kBenchmarkKinds[] = {
    {"ForwardDynamics/sinew/", benchmarkSinewForwardDynamics, Scope::All},
    {"ForwardDynamics/sinew_balanced/", benchmarkSinewBalancedForwardDynamics, Scope::All},
    {"ForwardDynamics/sinew_parallel/", benchmarkSinewParallelForwardDynamics, Scope::All, true},
    {"ForwardDynamics/simbody/", benchmarkSimbodyForwardDynamics, Scope::All},
    {"ForwardDynamics/simbody_fused/", benchmarkFusedSimbodyForwardDynamics, Scope::ModelsWithWires},
    {"ForwardDynamics/aba/", benchmarkReferenceAba, Scope::BareBallTrees},
#ifdef SINEW_HAVE_MUJOCO
    {"ForwardDynamics/mujoco/", benchmarkMujocoForwardDynamics, Scope::MjcfWritable},
#endif
    {"WireJacobian/", benchmarkWireJacobian, Scope::WireBenchmarkModels},
    {"WireJacobianSparse/", benchmarkSparseWireJacobian, Scope::WireBenchmarkModels},
    {"WireForces/", benchmarkWireForces, Scope::WireBenchmarkModels},
};

bool runsOn(const BenchmarkKind& kind, const ModelSpec& spec, const ModelFixture& fixture) {
    switch (kind.scope) {
        case Scope::All: return true;
        // The fused element has no virtual-link equilibrium.
        case Scope::ModelsWithWires: return fixture.getModel().getNumWires() > 0 && fixture.getCensus().virtualLinks == 0;
        case Scope::WireBenchmarkModels: return spec.wireBenchmarks;
        case Scope::BareBallTrees: {
            const sinew::Model& model = fixture.getModel();
            bool ballJoints = true;
            for (const sinew::Joint& joint : model.getJoints())
                ballJoints = ballJoints && (joint.type == sinew::JointType::Ball ||
                                            (joint.type == sinew::JointType::Free && joint.parent == sinew::kGround));
            return ballJoints && model.getNumLoops() == 0 && model.getNumWires() == 0;
        }
        case Scope::MjcfWritable:
            try {
                sinew::requireMjcfWritable(fixture.getModel());
                return true;
            } catch (const sinew::Error&) {
                return false;
            }
    }
    return true;
}

}  // namespace
}  // namespace sinew_benchmarks

int main(int argc, char** argv) {
    using namespace sinew_benchmarks;
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

    // Fixtures outlive RunSpecifiedBenchmarks; the registered benchmarks hold pointers to them.
    std::vector<std::unique_ptr<ModelFixture>> fixtures;
    for (const ModelSpec& spec : getModelTable()) {
        fixtures.push_back(std::make_unique<ModelFixture>(spec.build()));
        ModelFixture* fixture = fixtures.back().get();
        benchmark::AddCustomContext("model " + spec.name,
                                    "family=" + spec.family + " variant=" + spec.variant + " " + fixture->describe());
        for (const BenchmarkKind& kind : kBenchmarkKinds) {
            if (!runsOn(kind, spec, *fixture)) continue;
            benchmark::internal::Benchmark* registered =
                benchmark::RegisterBenchmark((kind.prefix + spec.name).c_str(), kind.run, fixture)
                    ->Unit(benchmark::kMicrosecond);
            if (kind.wallClock) registered->UseRealTime();
        }
    }

    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

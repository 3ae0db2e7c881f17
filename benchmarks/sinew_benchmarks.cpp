// sinew's benchmarks: what the wires cost on the sinew side (the full wire Jacobian, or the generalized forces
// of all tensions without forming it) next to its peer, one Simbody forward-dynamics evaluation with the same
// wires, on the same model and configuration in the same run, so the ratio does not depend on the machine.
//
// Every benchmark is registered once per row of the model table (getModelTable); the model sizes go into each
// result's counters and into the run's context, so a JSON file says what was measured.
#include "sinew/simbody/ndebug_guard.hpp"

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "sinew/core/census.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/random_model.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/simbody/simbody_model.hpp"

namespace {

struct ModelSpec {
    std::string name;
    std::function<sinew::Model()> build;
};

// Random trees of the paper's scale: ten wires per link and a few loop closures. No virtual links, because
// Simbody cannot compute accelerations for massless free bodies and the peer must run on the same model.
sinew::Model makeRandomModel(int numLinks, int numLoops) {
    sinew::RandomModelOptions options;
    options.numLinks = numLinks;
    options.rootJoint = sinew::JointType::Free;
    options.numLoops = numLoops;
    options.numWires = 10 * numLinks;
    options.numVirtualLinks = 0;
    options.seed = 1;
    return sinew::generateRandomModel(options);
}

const std::vector<ModelSpec>& getModelTable() {
    static const std::vector<ModelSpec> table = {
        {"arm26", [] { return sinew::readModelFile(SINEW_SOURCE_DIR "/models/arm26.yaml"); }},
        {"random50", [] { return makeRandomModel(50, 4); }},
        {"random200", [] { return makeRandomModel(200, 10); }},
    };
    return table;
}

// One model's fixture, shared by all of that model's benchmarks: the model, its census, one random state
// (q, u) and random tensions. The Simbody system is built on first use, so a --benchmark_filter that leaves
// out the Simbody benchmarks does not pay for building it.
class ModelFixture {
public:
    explicit ModelFixture(sinew::Model model) : model_(std::move(model)), census_(sinew::calcCensus(model_)) {
        std::mt19937 rng(2024);
        q_ = sinew::generateRandomCoordinates(model_, rng);
        u_ = sinew::generateRandomSpeeds(model_, rng);
        std::uniform_real_distribution<double> tension(0.0, 100.0);  // N
        tensions_.resize(model_.getNumWires());
        for (Eigen::Index w = 0; w < tensions_.size(); ++w) tensions_[w] = tension(rng);
    }

    const sinew::Model& getModel() const { return model_; }
    const Eigen::VectorXd& getQ() const { return q_; }
    const Eigen::VectorXd& getU() const { return u_; }
    const Eigen::VectorXd& getTensions() const { return tensions_; }

    const sinew::SimbodyModel& getSimbodyModel() {
        if (!simbody_) simbody_ = std::make_unique<sinew::SimbodyModel>(model_);
        return *simbody_;
    }

    void setCounters(benchmark::State& state) const {
        state.counters["links"] = census_.links;
        state.counters["dof"] = census_.dof;
        state.counters["wires"] = census_.wires;
        state.counters["wire_points"] = census_.wirePoints;
        state.counters["loops"] = census_.loops;
    }

    std::string describe() const {
        return "links=" + std::to_string(census_.links) + " dof=" + std::to_string(census_.dof) +
               " nq=" + std::to_string(model_.getNumQ()) + " wires=" + std::to_string(census_.wires) +
               " wire_points=" + std::to_string(census_.wirePoints) + " loops=" + std::to_string(census_.loops) +
               " virtual_links=" + std::to_string(census_.virtualLinks);
    }

private:
    sinew::Model model_;
    sinew::Census census_;
    Eigen::VectorXd q_, u_, tensions_;
    std::unique_ptr<sinew::SimbodyModel> simbody_;
};

// The part both sinew benchmarks start from: link poses and wire paths at q.
void calcWireGeometry(const sinew::Model& model, sinew::Data& data, const Eigen::VectorXd& q) {
    sinew::calcPositionKinematics(model, data, q);
    sinew::calcWirePaths(model, data);
}

void benchmarkWireJacobian(benchmark::State& state, ModelFixture* fixture) {
    const sinew::Model& model = fixture->getModel();
    sinew::Data data(model);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    for (auto _ : state) {
        calcWireGeometry(model, data, fixture->getQ());
        sinew::calcWireJacobian(model, data, J);
        benchmark::DoNotOptimize(J.data());
        benchmark::ClobberMemory();
    }
    fixture->setCounters(state);
}

void benchmarkWireForces(benchmark::State& state, ModelFixture* fixture) {
    const sinew::Model& model = fixture->getModel();
    sinew::Data data(model);
    Eigen::VectorXd tau(model.getNumU());
    for (auto _ : state) {
        calcWireGeometry(model, data, fixture->getQ());
        sinew::calcWireGeneralizedForces(model, data, fixture->getTensions(), tau);
        benchmark::DoNotOptimize(tau.data());
        benchmark::ClobberMemory();
    }
    fixture->setCounters(state);
}

void benchmarkSimbodyForwardDynamics(benchmark::State& state, ModelFixture* fixture) {
    const sinew::SimbodyModel& simbody = fixture->getSimbodyModel();
    const SimTK::MultibodySystem& system = simbody.getSystem();
    SimTK::State s = simbody.makeState(fixture->getQ(), fixture->getU(), SimTK::Stage::Acceleration);
    // The loops are not assembled at a random q; Simbody still computes accelerations (the constraint errors
    // only enter the multipliers' right-hand side), but check they are numbers before timing them.
    for (int i = 0; i < s.getNU(); ++i) {
        if (!std::isfinite(s.getUDot()[i])) {
            state.SkipWithError("Simbody's accelerations are not finite at the benchmark state");
            return;
        }
    }
    const SimTK::Vector q = s.getQ();
    for (auto _ : state) {
        // Writing q invalidates the Position stage and all above it, as an integrator step does, so realize
        // recomputes kinematics, wire forces, the articulated-body pass and the loop multipliers.
        s.updQ() = q;
        system.realize(s, SimTK::Stage::Acceleration);
        benchmark::DoNotOptimize(&s.getUDot()[0]);
        benchmark::ClobberMemory();
    }
    fixture->setCounters(state);
}

struct BenchmarkKind {
    const char* prefix;  // the result is named prefix + model name
    void (*run)(benchmark::State&, ModelFixture*);
};

constexpr BenchmarkKind kBenchmarkKinds[] = {
    {"WireJacobian/", benchmarkWireJacobian},
    {"WireForces/", benchmarkWireForces},
    {"ForwardDynamics/simbody/", benchmarkSimbodyForwardDynamics},
};

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

    // Fixtures outlive RunSpecifiedBenchmarks; the registered benchmarks hold pointers to them.
    std::vector<std::unique_ptr<ModelFixture>> fixtures;
    for (const ModelSpec& spec : getModelTable()) {
        fixtures.push_back(std::make_unique<ModelFixture>(spec.build()));
        ModelFixture* fixture = fixtures.back().get();
        benchmark::AddCustomContext("model " + spec.name, fixture->describe());
        for (const BenchmarkKind& kind : kBenchmarkKinds)
            benchmark::RegisterBenchmark((kind.prefix + spec.name).c_str(), kind.run, fixture)
                ->Unit(benchmark::kMicrosecond);
    }

    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

#pragma once
// The models sinew's benchmarks run on, and one fixture per model: the model, its census, and a state
// (q, u, tau) that sinew and Simbody both evaluate, so their timings pair up.
//
// Families (docs/performance.md): chain<N> and tree<N> (a chain, a binary tree) of N in {10, 30, 100, 300,
// 1000} links, free root and ball joints, bare or with `_loops` (max(1, N/50) ball closures) and/or
// `_wires` (10 wires per link, 2 or 3 points each); `wholebody`, a random tree of the human body's size
// (53 links, 4 loops, 547 wires), with `_bare`, `_loops` and `_wires` variants; and `arm26` from models/.
#include "sinew/plugin/ndebug_guard.hpp"

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sinew/core/census.hpp"
#include "sinew/core/model.hpp"
#include "sinew/plugin/simbody_model.hpp"

namespace sinew_benchmarks {

struct ModelSpec {
    std::string name;      // e.g. chain100_loops_wires
    std::string family;    // chain, tree, wholebody or arm26
    std::string variant;   // bare, loops, wires or loops_wires
    bool wireBenchmarks;   // also time the wire Jacobian and wire forces (models whose wires matter)
    std::function<sinew::Model()> build;
};

// Every model, smallest first within a family.
std::vector<ModelSpec> getModelTable();

// One model's fixture, shared by all of that model's benchmarks. The model is built at once (it is cheap
// and its census goes into the run's context); the Simbody system and the benchmark state are built on
// first use, so a --benchmark_filter that leaves a model out does not pay for them.
class ModelFixture {
public:
    explicit ModelFixture(sinew::Model model);
    ModelFixture(const ModelFixture&) = delete;
    ModelFixture& operator=(const ModelFixture&) = delete;
    ~ModelFixture();

    const sinew::Model& getModel() const { return model_; }
    const sinew::Census& getCensus() const { return census_; }

    // Builds the Simbody system and the benchmark state if not done yet: q from the default pose moved
    // along random speeds for 0.2 s and projected onto the loops by Simbody (the default pose where the
    // projection fails), loop-consistent random u, random tau (N m or N, uniform in [-5, 5]), gravity and
    // the wires' tensions from their force laws. Then evaluates both engines once and compares their udot.
    void prepare();
    const Eigen::VectorXd& getQ() const { return q_; }      // (nq)
    const Eigen::VectorXd& getU() const { return u_; }      // (nu)
    const Eigen::VectorXd& getTau() const { return tau_; }  // (nu) generalized forces besides the wires'
    // Simbody's state at (q, u) with tau applied, realized to Acceleration.
    const SimTK::State& getSimbodyState() const { return *simbodyState_; }
    const sinew::SimbodyModel& getSimbodyModel() const { return *simbody_; }
    // max |udot_sinew - udot_Simbody| over the acceleration scale (the larger of Simbody's udot and the udot
    // without the loops, as in tests/plugin/test_forward_dynamics.cpp).
    double getUdotDifference() const { return udotDifference_; }
    // max |udot - udot_Simbody| over that scale, for another evaluation's udot (nu) at the state.
    double calcUdotDifferenceFromSimbody(const Eigen::VectorXd& udot) const;
    bool projectionFellBack() const { return projectionFellBack_; }

    // The same for the `simbody_fused` peer (fused_wire_force.hpp): the same model, state and tau, the
    // wires as one FusedWireForce. Needs prepare(); built on first use.
    void prepareFused();
    const sinew::SimbodyModel& getFusedSimbodyModel() const { return *fused_; }
    const SimTK::State& getFusedSimbodyState() const { return *fusedState_; }
    double getFusedUdotDifference() const { return fusedUdotDifference_; }

    // links, dof, wires, wire_points and loops as the benchmark's counters.
    void setCounters(benchmark::State& state) const;
    std::string describe() const;

private:
    sinew::Model model_;
    sinew::Census census_;
    bool prepared_ = false;
    std::unique_ptr<sinew::SimbodyModel> simbody_;
    std::unique_ptr<SimTK::State> simbodyState_;
    Eigen::VectorXd q_, u_, tau_;
    double udotDifference_ = 0;
    bool projectionFellBack_ = false;
    Eigen::VectorXd udotSinew_;    // (nu) sinew's udot at the state
    Eigen::VectorXd udotSimbody_;  // (nu) Simbody's
    double udotScale_ = 1;         // the acceleration scale the differences are relative to

    std::unique_ptr<sinew::SimbodyModel> fused_;
    std::unique_ptr<SimTK::State> fusedState_;
    double fusedUdotDifference_ = 0;
};

}  // namespace sinew_benchmarks

#pragma once
// OpenSim's static optimization (StaticOptimization analysis) on a wire problem (wire_problem.hpp):
//
//     min Σ_w |a_w|^p + Σ_r |c_r|^p   s.t.  Σ_w A_w F_w a_w + Σ_r e_dof(r) F_r c_r + G λ = tau  (every row exact),
//                                       minActivation <= a <= maxActivation, reserve controls within theirs,
//
// with F_w = maxIsometricForce_w × forceMultiplier_w (the force-length × force-velocity multipliers of the
// frame, given per wire) and F_r a reserve's optimal force: the wire problem rewritten in activations, then
// solved by StaticOptimizationSolver (static_optimization_solver.hpp). A motion's frames get the same
// problem from TensionProblemBuilder (tension_problem.hpp) with the "so" method; this class takes a wire
// problem made elsewhere.
#include <Eigen/Core>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/distribution_problem.hpp"
#include "sinew/tensions/reserve_columns.hpp"
#include "sinew/tensions/static_optimization_solver.hpp"

namespace sinew {

struct StaticOptimizationSettings {
    Eigen::VectorXd maxIsometricForce;  // (numWires) N, > 0
    // (numWires) activation bounds, OpenSim's min_control / max_control of each muscle (Muscle's default
    // [0, 1]); empty: [0, 1] for every wire.
    Eigen::VectorXd minActivation, maxActivation;
    std::vector<ReserveActuator> reserves;
    // OpenSim's activation_exponent p >= 1: the cost Σ |a|^p (reserve controls alike). 2: the active-set QP;
    // others: Ipopt.
    double activationExponent = 2;
};

struct StaticOptimizationResult {
    DistributionResult distribution;  // in the solver's variables: [activations; reserve controls; loop forces]
    Eigen::VectorXd activation;       // (numWires)
    Eigen::VectorXd tension;          // (numWires) N, activation × maxIsometricForce × forceMultiplier
    Eigen::VectorXd reserveControl;   // (reserves)
    Eigen::VectorXd reserveForce;     // (reserves) N m or N, control × optimal force
    Eigen::VectorXd loopForce;        // (numFree of the wire problem)
};

// Fills empty activation bounds with [0, 1]; throws sinew::Error naming the wire or reserve whose settings
// are invalid, or an exponent below 1.
void validateStaticOptimizationSettings(StaticOptimizationSettings& settings);

class StaticOptimization {
public:
    // Throws sinew::Error naming the wire or reserve whose settings are invalid, or an exponent below 1 (sizes
    // are checked per frame). `options` are the active set's (p = 2).
    explicit StaticOptimization(StaticOptimizationSettings settings, ActiveSetOptions options = {});

    // One frame. `wireProblem`: rows, target tau, wire columns (generalized force per newton) and free
    // columns as a WireProblemBuilder makes them; its bounds, costs and weights are not used.
    // forceMultiplier (numWires) >= 0: a wire with multiplier 0 cannot pull. reserveColumns (rows x
    // reserves), optional: each reserve's generalized force per unit of its force at this frame (e_dof for
    // a DOF reserve, J^T F for a body one); without it each reserve acts on its dof alone.
    void solve(const DistributionProblem& wireProblem, const Eigen::VectorXd& forceMultiplier,
               StaticOptimizationResult& result, const Eigen::MatrixXd* reserveColumns = nullptr);
    void reset() { solver_.reset(); }

private:
    StaticOptimizationSettings settings_;
    StaticOptimizationSolver solver_;
    DistributionProblem problem_;  // the activation problem, its values rewritten each frame

    // problem_.A's pattern is the wire problem's (kept in wirePattern_) and each reserve's DOF, or, for a
    // body reserve when frames give reserve columns, every row; rebuilt only when that changes.
    bool hasPatternOf(const DistributionProblem& wireProblem, bool denseReserves) const;
    void buildPattern(const DistributionProblem& wireProblem, bool denseReserves);
    Eigen::SparseMatrix<double> wirePattern_;
    bool denseReserves_ = false;
};

}  // namespace sinew

#pragma once
// OpenSim's static optimization (StaticOptimization analysis) on a wire problem (wire_problem.hpp):
//
//     min Σ_w a_w^2 + Σ_r c_r^2   s.t.  Σ_w A_w F_w a_w + Σ_r e_dof(r) F_r c_r + G λ = tau  (every row exact),
//                                       minActivation <= a <= maxActivation, reserve controls within theirs,
//
// with F_w = maxIsometricForce_w × forceMultiplier_w (the force-length × force-velocity multipliers of the
// frame, given per wire) and F_r a reserve's optimal force. It is the active-set QP (active_set_solver.hpp)
// in activation variables: weights 2, all rows equalities, loop forces free.
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/distribution_problem.hpp"

namespace sinew {

// A generalized force on one DOF (OpenSim's CoordinateActuator used as a reserve).
struct ReserveActuator {
    std::string name;
    int dof = 0;                // row (index into u)
    double optimalForce = 1;    // N m or N per unit control, > 0
    double minControl = -std::numeric_limits<double>::infinity();
    double maxControl = std::numeric_limits<double>::infinity();
};

struct StaticOptimizationSettings {
    Eigen::VectorXd maxIsometricForce;  // (numWires) N, > 0
    // (numWires) activation bounds, OpenSim's min_control / max_control of each muscle (Muscle's default
    // [0, 1]); empty: [0, 1] for every wire.
    Eigen::VectorXd minActivation, maxActivation;
    std::vector<ReserveActuator> reserves;
    double activationExponent = 2;  // OpenSim's activation_exponent; 2 is what the active-set QP solves
};

struct StaticOptimizationResult {
    DistributionResult distribution;  // in the solver's variables: [activations; reserve controls; loop forces]
    Eigen::VectorXd activation;       // (numWires)
    Eigen::VectorXd tension;          // (numWires) N, activation × maxIsometricForce × forceMultiplier
    Eigen::VectorXd reserveControl;   // (reserves)
    Eigen::VectorXd reserveForce;     // (reserves) N m or N, control × optimal force
    Eigen::VectorXd loopForce;        // (numFree of the wire problem)
};

class StaticOptimization {
public:
    // Throws sinew::Error naming the wire or reserve whose settings are invalid (sizes are checked per frame).
    explicit StaticOptimization(StaticOptimizationSettings settings, ActiveSetOptions options = {});

    // One frame. `wireProblem`: rows, target tau, wire columns (generalized force per newton) and free
    // columns as a WireProblemBuilder makes them; its bounds, costs and weights are not used.
    // forceMultiplier (numWires) >= 0: a wire with multiplier 0 cannot pull.
    void solve(const DistributionProblem& wireProblem, const Eigen::VectorXd& forceMultiplier,
               StaticOptimizationResult& result);
    void reset() { solver_.reset(); }

private:
    StaticOptimizationSettings settings_;
    ActiveSetSolver solver_;
    DistributionProblem problem_;  // the activation problem, rebuilt in place each frame
};

}  // namespace sinew

#pragma once
// OpenSim's static optimization (StaticOptimization analysis) on a wire problem (wire_problem.hpp):
//
//     min Σ_w |a_w|^p + Σ_r |c_r|^p   s.t.  Σ_w A_w F_w a_w + Σ_r e_dof(r) F_r c_r + G λ = tau  (every row exact),
//                                       minActivation <= a <= maxActivation, reserve controls within theirs,
//
// with F_w = maxIsometricForce_w × forceMultiplier_w (the force-length × force-velocity multipliers of the
// frame, given per wire) and F_r a reserve's optimal force. For p = 2 (OpenSim's default) it is the
// active-set QP (active_set_solver.hpp) in activation variables: weights 2, all rows equalities, loop forces
// free. Other exponents p >= 1 (convex) are solved by Ipopt (ipopt_solver.hpp), milliseconds per frame.
// Frames no activations within their bounds can meet are Infeasible with the phase-1 reserve and the
// least-squares activations (infeasible_frame.hpp).
#include <Eigen/Core>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sinew/core/body_actuator.hpp"
#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/distribution_problem.hpp"
#include "sinew/tensions/ipopt_solver.hpp"

namespace sinew {

// A generalized force on one DOF (OpenSim's CoordinateActuator used as a reserve), or with `body` a force
// or torque on links (PointActuator, TorqueActuator: residuals on a floating root), whose generalized force
// per unit control depends on the state: its column is then given to each solve (reserveColumns).
struct ReserveActuator {
    std::string name;
    int dof = 0;                // row (index into u); unused with `body`
    double optimalForce = 1;    // N m or N per unit control, > 0
    double minControl = -std::numeric_limits<double>::infinity();
    double maxControl = std::numeric_limits<double>::infinity();
    std::optional<BodyActuator> body = std::nullopt;
};

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
    ActiveSetSolver solver_;
    double infeasibilityTolerance_;
    std::unique_ptr<IpoptSolver> ipopt_;  // p != 2
    DistributionProblem problem_;  // the activation problem, its values rewritten each frame

    // problem_.A's pattern is the wire problem's (kept in wirePattern_) and each reserve's DOF, or, for a
    // body reserve when frames give reserve columns, every row; rebuilt only when that changes.
    bool hasPatternOf(const DistributionProblem& wireProblem, bool denseReserves) const;
    void buildPattern(const DistributionProblem& wireProblem, bool denseReserves);
    Eigen::SparseMatrix<double> wirePattern_;
    bool denseReserves_ = false;
};

}  // namespace sinew

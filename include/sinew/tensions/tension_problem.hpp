#pragma once
// One frame's tension problem from the frame's generalized forces (docs/tensions-from-motion.md), in named
// stages, so that a tool builds the problem and solves it and never writes its rows:
//
//   1. wire paths and the wire Jacobian J at the frame's configuration;
//   2. A = [-J^T, extra blocks, loop columns], target tau (wire_problem.hpp; the paper's Eq. 8);
//   3. the unactuated rows (unactuated_rows.hpp): their targets, the unactuated residual (part of Eq. 10's Z);
//   4. methods in activations (static optimization, WireVariables::Activation): each wire's force per unit
//      activation from its force law (ForceLaw::calcActiveForceMultiplier, at the paths' lengths and speeds),
//      the wire columns scaled by it, every row exact, the cost Σ |x|^p (weights p).
//
// The LP (Eq. 11-12) and QP (Eq. 14) take the problem in tensions as stage 3 leaves it (solve, below).
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/tensions/distribution_problem.hpp"
#include "sinew/tensions/problem_columns.hpp"
#include "sinew/tensions/tension_method_registry.hpp"
#include "sinew/tensions/tension_solver.hpp"
#include "sinew/tensions/unactuated_rows.hpp"
#include "sinew/tensions/wire_problem.hpp"

namespace sinew {

struct TensionProblemSettings {
    WireVariables variables = WireVariables::Tension;
    WireProblemOptions problem;  // LP band, LP cost, QP regulariser
    // (numWires) N, > 0: each tension's upper bound; in activations, each wire's max isometric force.
    Eigen::VectorXd maxTension;
    // Activations: (numWires) bounds (empty: [0, 1]); the cost exponent p >= 1; and whether a wire's force
    // per activation is max isometric force times its law's active force multiplier (OpenSim's
    // use_muscle_physiology; every wire's law must then have a max isometric force) or that force alone.
    Eigen::VectorXd minActivation, maxActivation;
    double activationExponent = 2;
    bool useMusclePhysiology = true;
    // A row whose largest |generalized force per unit variable| is below this times the frame's largest is
    // unactuated (relative).
    double unactuatedThreshold = 1e-9;
    // Extra bounded blocks after the wires' columns (problem_columns.hpp), in this order.
    std::vector<std::shared_ptr<ProblemColumns>> columns;
};

// One frame's problem and what the stages found; sized by makeProblem().
struct TensionProblem {
    DistributionProblem distribution;
    std::vector<char> unactuated;        // (nu) 1 on rows no variable reaches at this frame
    double unactuatedResidual = 0;       // |tau - target| over those rows
    Eigen::VectorXd forceMultiplier;     // (numWires) activations: the laws' multipliers (1 without physiology)
    Eigen::VectorXd forcePerActivation;  // (numWires) N: max isometric force × multiplier
};

class TensionProblemBuilder {
public:
    // Throws sinew::Error naming the wire or setting that does not fit the model.
    TensionProblemBuilder(const Model& model, TensionProblemSettings settings);

    TensionProblem makeProblem() const;
    // Stages 1-4 for a frame whose generalized forces are tau (nu): `data` holds the position and velocity
    // kinematics at the frame's (q, u), as calcInverseDynamics leaves them; its wire paths, speeds and
    // scratch buffers are overwritten. Allocates nothing.
    void build(Data& data, const Eigen::VectorXd& tau, TensionProblem& problem);

    // Solves the built problem by `solver`. The equality rows a block adds at a frame (the root's force rows
    // with a foot down, contact_columns.hpp) give way first: a frame Infeasible with a reserve on one of them
    // (a ground force the feet cannot give: pulling, or beyond friction) is solved again with those rows as
    // tolerance rows, so that what the ground lacks shows as the root's residual and never unbalances a
    // virtual link. (Activations: every row is exact anyway.)
    void solve(TensionSolver& solver, TensionProblem& problem, DistributionResult& result) const;

    // The wires' tensions (N) of a solution x of `problem`.
    void calcTensions(const TensionProblem& problem, const Eigen::VectorXd& x, Eigen::VectorXd& tension) const;

    const TensionProblemSettings& getSettings() const { return settings_; }
    const WireProblemBuilder& getWireProblemBuilder() const { return wires_; }

private:
    void calcForceMultipliers(Data& data, TensionProblem& problem) const;
    void rewriteInActivations(TensionProblem& problem) const;

    const Model& model_;
    TensionProblemSettings settings_;
    WireProblemBuilder wires_;
    UnactuatedRows unactuatedRows_;
    Eigen::SparseMatrix<double> Jt_;  // J^T (nu x numWires) in makeWireJacobianTransposePattern's pattern
};

}  // namespace sinew

#pragma once
// Wire tensions from motion, one frame at a time (docs/tensions-from-motion.md): inverse dynamics gives the
// generalized forces tau the motion needs, the wire Jacobian J what each tension produces (-J^T), and a
// tension solver shares tau among the wires: the LP (least total tension within a torque band), the QP
// (least squares, the paper's Z = ½|tau + J^T f|²) or OpenSim's static optimization (least squared
// activations, rows exact). DOFs no wire or loop can reach (a floating root's six) are not distributed:
// their generalized force is the frame's unactuated residual, reported, never hidden; with measured
// external loads it is what the loads leave unexplained.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"
#include "sinew/tensions/distribution_problem.hpp"
#include "sinew/tensions/problem_columns.hpp"
#include "sinew/tensions/reserve_columns.hpp"
#include "sinew/tensions/tension_problem.hpp"
#include "sinew/tensions/tension_solver.hpp"
#include "sinew/tools/force_element_loads.hpp"

namespace sinew {

struct TensionAnalysisOptions {
    // A TensionMethodRegistry name (tension_method_registry.hpp): "lp", "qp", "so" (static optimization),
    // "ipopt", or a registered one.
    std::string method = "qp";
    WireProblemOptions problem;  // LP band, LP cost, QP regulariser
    // (numWires) N: the LP / QP upper bound of each tension. Empty: each wire's max isometric force, which
    // every wire's law then needs (a muscle law); a wire with another law must be given one here.
    Eigen::VectorXd maxTension;
    // Static optimization: (numWires) activation bounds (empty: [0, 1]).
    Eigen::VectorXd minActivation, maxActivation;
    // Reserve actuators, on DOFs or (ReserveActuator::body) forces and torques on links, e.g. a floating
    // root's residuals: the first column block after the wires (reserve_columns.hpp), in every method.
    std::vector<ReserveActuator> reserves;
    // Further column blocks (problem_columns.hpp), after the reserves, in this order.
    std::vector<std::shared_ptr<ProblemColumns>> columns;
    // Static optimization: a wire's force per unit activation is max isometric force times the fibre's
    // active force-length, force-velocity (at full activation) and cos(pennation), as OpenSim's
    // use_muscle_physiology; false: max isometric force alone.
    bool useMusclePhysiology = true;
    // Static optimization and Ipopt: the cost Σ x^exponent (OpenSim's activation_exponent, >= 1; 2 is the
    // active-set QP, others are solved by Ipopt).
    double activationExponent = 2;
    // A DOF whose largest |generalized force per unit variable| over all wires, loops and blocks is below
    // this times the frame's largest is unactuated (N m/N or N/N, relative).
    double unactuatedThreshold = 1e-9;
};

// What one frame gives. Every vector is sized at construction; no field is ever NaN after a frame whose
// inputs were finite.
struct TensionFrame {
    DistributionStatus status = DistributionStatus::Failed;
    Eigen::VectorXd tau;          // (nu) inverse dynamics generalized forces, N m or N
    Eigen::VectorXd tension;      // (numWires) N
    Eigen::VectorXd activation;   // (numWires) static optimization; zero otherwise
    Eigen::VectorXd reserveForce; // (reserves) static optimization, N m or N
    // (nu) tau - (wires + loops + reserves); on unactuated DOFs tau itself, except a root DOF of a model with
    // virtual links: there, what moving the body and its virtual links rigidly needs (loads on virtual links,
    // if any, are balanced through their wires).
    Eigen::VectorXd residual;
    // (nu) infeasible frames (every method): the phase-1 LP's smallest generalized force per DOF that makes
    // the frame feasible; zero otherwise.
    Eigen::VectorXd reserve;
    std::vector<char> unactuated; // (nu) 1 on DOFs no wire or loop reaches at this frame
    double torqueError = 0;       // Z = ½ |residual|² (Eq. 10) over every DOF, unactuated ones included
    double unactuatedResidual = 0;  // |residual| over the unactuated DOFs
    int activeWires = 0;          // wires pulling (above their lower bound)
    int iterations = 0;           // simplex pivots or active-set steps
    bool usedIpopt = false;       // solved by Ipopt (the active set's fallback, or an exponent other than 2)
};

// One analysis per motion (and per thread): it keeps the solver's warm start from frame to frame and
// every buffer, so calcFrame allocates nothing but what the solvers themselves do. Per frame: inverse
// dynamics, then the frame's problem (TensionProblemBuilder), then the method's solver.
class TensionAnalysis {
public:
    // Throws sinew::Error naming the wire, reserve, method or option that does not fit the model.
    TensionAnalysis(const Model& model, TensionAnalysisOptions options);
    TensionAnalysis(const TensionAnalysis&) = delete;
    TensionAnalysis& operator=(const TensionAnalysis&) = delete;

    // One frame: q (nq), u and udot (nu), and the measured loads as one spatial force per link (Data::F_G
    // convention; all zero when there are none). The result stays valid until the next call.
    const TensionFrame& calcFrame(const Eigen::VectorXd& q, const Eigen::VectorXd& u, const Eigen::VectorXd& udot,
                                  const std::vector<SpatialVector>& appliedLinkForces);
    // The next frame starts cold (no warm start): for timing, or after a jump in the motion.
    void reset() { solver_->reset(); }

    const Model& getModel() const { return model_; }
    const TensionAnalysisOptions& getOptions() const { return options_; }
    // True for methods in activations (static optimization): TensionFrame::activation is filled.
    bool solvesActivations() const { return builder_.getSettings().variables == WireVariables::Activation; }
    // The last frame's solver answer: x = [wires; reserves; options.columns' blocks; loop forces].
    const DistributionResult& getSolution() const { return result_; }
    // Where options.columns[k]'s variables start in x.
    int getColumnStart(int k) const {
        return builder_.getWireProblemBuilder().getBlockStart(k + (options_.reserves.empty() ? 0 : 1));
    }
    // The force per unit activation (N) of each wire at the last frame (static optimization).
    const Eigen::VectorXd& getForcePerActivation() const { return problem_.forcePerActivation; }

private:
    void readSolution();

    const Model& model_;
    TensionAnalysisOptions options_;
    Data data_;
    TensionProblemBuilder builder_;
    TensionProblem problem_;
    std::unique_ptr<TensionSolver> solver_;
    DistributionResult result_;
    TensionFrame frame_;
    ForceElementLoads forceElements_;
};

}  // namespace sinew

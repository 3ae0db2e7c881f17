#pragma once
// Wire tensions from motion, one frame at a time (docs/tensions-from-motion.md): inverse dynamics gives the
// generalized forces tau the motion needs, the wire Jacobian J what each tension produces (-J^T), and a
// tension solver shares tau among the wires: the LP (least total tension within a torque band), the QP
// (least squares, the paper's Z = ½|tau + J^T f|²) or OpenSim's static optimization (least squared
// activations, rows exact). DOFs no wire or loop can reach (a floating root's six) are not distributed:
// their generalized force is the frame's unactuated residual, reported, never hidden; with measured
// external loads it is what the loads leave unexplained.
#include <Eigen/Core>
#include <Eigen/LU>
#include <memory>
#include <string>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"
#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/distribution_problem.hpp"
#include "sinew/tensions/lp_solver.hpp"
#include "sinew/tensions/static_optimization.hpp"
#include "sinew/tensions/wire_problem.hpp"

namespace sinew {

enum class TensionMethod { Lp, Qp, StaticOptimization };
const char* toString(TensionMethod method);
// "lp", "qp" or "so"; throws sinew::Error naming what it got otherwise.
TensionMethod parseTensionMethod(const std::string& name);

struct TensionAnalysisOptions {
    TensionMethod method = TensionMethod::Qp;
    WireProblemOptions problem;  // LP band, LP cost, QP regulariser
    // (numWires) N: the LP / QP upper bound of each tension. Empty: each wire's max isometric force, which
    // every wire then needs (thelen2003_muscle); a wire with another law must be given one here.
    Eigen::VectorXd maxTension;
    // Static optimization: (numWires) activation bounds (empty: [0, 1]) and reserve actuators, on DOFs or
    // (ReserveActuator::body) forces and torques on links, e.g. a floating root's residuals.
    Eigen::VectorXd minActivation, maxActivation;
    std::vector<ReserveActuator> reserves;
    // Static optimization: a wire's force per unit activation is max isometric force times the fibre's
    // active force-length, force-velocity (at full activation) and cos(pennation), as OpenSim's
    // use_muscle_physiology; false: max isometric force alone.
    bool useMusclePhysiology = true;
    // Static optimization: the cost Σ activation^exponent (OpenSim's activation_exponent, >= 1; 2 is the
    // active-set QP, others are solved by Ipopt).
    double activationExponent = 2;
    // A DOF whose largest |generalized force per newton| over all wires and loops is below this times the
    // frame's largest is unactuated (N m/N or N/N, relative).
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
    double torqueError = 0;       // Z = ½ |residual|² over every DOF, unactuated ones included
    double unactuatedResidual = 0;  // |residual| over the unactuated DOFs
    int activeWires = 0;          // wires pulling (above their lower bound)
    int iterations = 0;           // simplex pivots or active-set steps
    bool usedIpopt = false;       // solved by Ipopt (the active set's fallback, or an exponent other than 2)
};

// One analysis per motion (and per thread): it keeps the solver's warm start from frame to frame and
// every buffer, so calcFrame allocates nothing but what the solvers themselves do.
class TensionAnalysis {
public:
    // Throws sinew::Error naming the wire or option that does not fit the model.
    TensionAnalysis(const Model& model, TensionAnalysisOptions options);
    TensionAnalysis(const TensionAnalysis&) = delete;
    TensionAnalysis& operator=(const TensionAnalysis&) = delete;

    // One frame: q (nq), u and udot (nu), and the measured loads as one spatial force per link (Data::F_G
    // convention; all zero when there are none). The result stays valid until the next call.
    const TensionFrame& calcFrame(const Eigen::VectorXd& q, const Eigen::VectorXd& u, const Eigen::VectorXd& udot,
                                  const std::vector<SpatialVector>& appliedLinkForces);
    // The next frame starts cold (no warm start): for timing, or after a jump in the motion.
    void reset();

    const Model& getModel() const { return model_; }
    const TensionAnalysisOptions& getOptions() const { return options_; }
    // The force per unit activation (N) of each wire at the last frame (static optimization).
    const Eigen::VectorXd& getForcePerActivation() const { return forcePerActivation_; }

private:
    void calcReserveColumns();
    void markUnactuated();
    void judgeByRigidMotion(int rootLink, Eigen::VectorXd& rowSize);
    void calcForceMultipliers();

    const Model& model_;
    TensionAnalysisOptions options_;
    Data data_;
    Eigen::VectorXd maxIsometricForce_;  // (numWires) N; static optimization
    WireProblemBuilder builder_;
    DistributionProblem problem_;
    Eigen::MatrixXd J_;                  // (numWires x nu)
    Eigen::VectorXd forceMultiplier_;    // (numWires) static optimization
    Eigen::VectorXd forcePerActivation_; // (numWires) N
    Eigen::MatrixXd reserveColumns_;     // (nu x reserves) generalized force per unit reserve force
    std::vector<int> virtualLinksOnGround_;  // virtual links whose joints hang from ground
    std::vector<Eigen::FullPivLU<JointMotion>> virtualLinkMotion_;  // their motion subspaces, factorized per frame
    Eigen::MatrixXd rigidMotion_;            // (nu x 6) workspace: per root mobility, u moving everything rigidly
    Eigen::VectorXd unbalanced_;             // (nu) per DOF, the generalized force no wire could balance if unactuated
    std::unique_ptr<LpSolver> lp_;
    std::unique_ptr<ActiveSetSolver> qp_;
    std::unique_ptr<StaticOptimization> so_;
    DistributionResult distribution_;
    StaticOptimizationResult soResult_;
    TensionFrame frame_;
};

}  // namespace sinew

#include "sinew/tools/tension_analysis.hpp"

#include "sinew/core/error.hpp"
#include "sinew/core/inverse_dynamics.hpp"

namespace sinew {
namespace {

// options.maxTension, or each wire's strength (its own, else its law's max isometric force).
Eigen::VectorXd getWireStrengths(const Model& model, const TensionAnalysisOptions& options) {
    const int numWires = model.getNumWires();
    if (options.maxTension.size() > 0) {
        if (options.maxTension.size() != numWires)
            throw Error("tensions: " + std::to_string(options.maxTension.size()) + " maximum tensions given for " +
                        std::to_string(numWires) + " wires");
        return options.maxTension;
    }
    Eigen::VectorXd strength(numWires);
    for (int w = 0; w < numWires; ++w) {
        const Wire& wire = model.getWire(w);
        const std::optional<double> wireStrength = getWireStrength(wire);
        if (!wireStrength)
            throw Error("tensions: wire '" + wire.name + "' has no strength and force law '" + wire.lawSpec.type +
                        "', which has no max isometric force: give the wire a strength, or every wire's maximum "
                        "tension");
        strength[w] = *wireStrength;
    }
    return strength;
}

TensionProblemSettings makeProblemSettings(const Model& model, const TensionAnalysisOptions& options,
                                           WireVariables variables) {
    TensionProblemSettings settings;
    settings.variables = variables;
    settings.problem = options.problem;
    settings.maxTension = getWireStrengths(model, options);
    settings.minActivation = options.minActivation;
    settings.maxActivation = options.maxActivation;
    settings.activationExponent = options.activationExponent;
    settings.useMusclePhysiology = options.useMusclePhysiology;
    settings.unactuatedThreshold = options.unactuatedThreshold;
    if (!options.reserves.empty()) settings.columns.push_back(std::make_shared<ReserveColumns>(model, options.reserves));
    settings.columns.insert(settings.columns.end(), options.columns.begin(), options.columns.end());
    if (model.getNumWires() == 0) throw Error("tensions: model '" + model.getName() + "' has no wires");
    return settings;
}

WireVariables getVariables(const TensionAnalysisOptions& options) {
    return TensionMethodRegistry::global().get(options.method).variables;
}

std::unique_ptr<TensionSolver> makeSolver(const TensionAnalysisOptions& options) {
    TensionMethodSettings settings;
    settings.activationExponent = options.activationExponent;
    return TensionMethodRegistry::global().get(options.method).makeSolver(settings);
}

}  // namespace

TensionAnalysis::TensionAnalysis(const Model& model, TensionAnalysisOptions options)
    : model_(model),
      options_(std::move(options)),
      data_(model),
      builder_(model, makeProblemSettings(model, options_, getVariables(options_))),
      problem_(builder_.makeProblem()),
      solver_(makeSolver(options_)),
      forceElements_(model) {
    const int nu = model.getNumU(), numWires = model.getNumWires();
    frame_.tau.setZero(nu);
    frame_.tension.setZero(numWires);
    frame_.activation.setZero(numWires);
    frame_.reserveForce.setZero(static_cast<Eigen::Index>(options_.reserves.size()));
    frame_.residual.setZero(nu);
    frame_.reserve.setZero(nu);
    frame_.unactuated.assign(static_cast<std::size_t>(nu), 0);
}

// The frame's report from the solver's answer: tensions (and activations) of the wires, the reserves'
// forces, and on unactuated DOFs the whole generalized force as residual.
void TensionAnalysis::readSolution() {
    TensionFrame& frame = frame_;
    const int numWires = model_.getNumWires();
    const Eigen::VectorXd& x = result_.x;
    builder_.calcTensions(problem_, x, frame.tension);
    const bool activations = solvesActivations();
    // A wire pulls above its lower bound (by more than roundoff for the activations of an interior point).
    const double margin = activations ? 1e-9 : 0;
    if (activations) frame.activation = x.head(numWires);
    frame.activeWires = 0;
    for (int w = 0; w < numWires; ++w) frame.activeWires += x[w] > problem_.distribution.lower[w] + margin;
    const int reserveStart = builder_.getWireProblemBuilder().getBlockStart(0);
    for (std::size_t r = 0; r < options_.reserves.size(); ++r)
        frame.reserveForce[static_cast<Eigen::Index>(r)] =
            x[reserveStart + static_cast<Eigen::Index>(r)] * options_.reserves[r].optimalForce;
    frame.status = result_.status;
    frame.iterations = result_.iterations;
    frame.usedIpopt = result_.usedIpopt;
    frame.reserve = result_.reserve;
    frame.residual = result_.residual;
    frame.unactuated = problem_.unactuated;
    frame.unactuatedResidual = problem_.unactuatedResidual;
    for (Eigen::Index i = 0; i < frame.residual.size(); ++i)
        if (frame.unactuated[static_cast<std::size_t>(i)]) frame.residual[i] = frame.tau[i];
    frame.torqueError = 0.5 * frame.residual.squaredNorm();
}

const TensionFrame& TensionAnalysis::calcFrame(const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                                               const Eigen::VectorXd& udot,
                                               const std::vector<SpatialVector>& appliedLinkForces) {
    calcInverseDynamics(model_, data_, q, u, udot, appliedLinkForces, frame_.tau);  // kinematics at (q, u) too
    forceElements_.subtractFrom(data_, frame_.tau);
    builder_.build(data_, frame_.tau, problem_);
    builder_.solve(*solver_, problem_, result_);
    readSolution();
    return frame_;
}

}  // namespace sinew

#include "sinew/tensions/tension_problem.hpp"

#include <string>

#include "sinew/core/error.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/tensions/static_optimization.hpp"

namespace sinew {
namespace {

// Activation bounds defaulted and checked as static optimization checks them.
void checkActivationSettings(const Model& model, TensionProblemSettings& settings) {
    StaticOptimizationSettings check;
    check.maxIsometricForce = settings.maxTension;
    check.minActivation = settings.minActivation;
    check.maxActivation = settings.maxActivation;
    validateStaticOptimizationSettings(check);
    settings.minActivation = check.minActivation;
    settings.maxActivation = check.maxActivation;
    if (!settings.useMusclePhysiology) return;
    for (const Wire& wire : model.getWires())
        if (!wire.law->getMaxIsometricForce())
            throw Error("tensions: wire '" + wire.name + "' has force law '" + wire.lawSpec.type +
                        "'; muscle physiology in static optimization needs a muscle law (one with a max isometric "
                        "force, such as thelen2003_muscle or millard2012_muscle)");
}

}  // namespace

TensionProblemBuilder::TensionProblemBuilder(const Model& model, TensionProblemSettings settings)
    : model_(model),
      settings_(std::move(settings)),
      wires_(model, settings_.maxTension, settings_.problem, settings_.columns),
      unactuatedRows_(model, settings_.unactuatedThreshold),
      Jt_(makeWireJacobianTransposePattern(model)) {
    if (settings_.variables == WireVariables::Activation) checkActivationSettings(model, settings_);
}

TensionProblem TensionProblemBuilder::makeProblem() const {
    const int nu = model_.getNumU(), numWires = model_.getNumWires();
    TensionProblem problem;
    problem.distribution = wires_.makeProblem();
    problem.unactuated.assign(static_cast<std::size_t>(nu), 0);
    problem.forceMultiplier.setOnes(numWires);
    problem.forcePerActivation = settings_.maxTension;
    if (settings_.variables == WireVariables::Activation) rewriteInActivations(problem);
    return problem;
}

// OpenSim's StaticOptimizationTarget::prepareToOptimize with use_muscle_physiology: the force per unit
// activation is Thelen2003Muscle::calcInextensibleTendonActiveFiberForce(s, 1), max isometric force times
// the law's multiplier at the path's length and speed.
void TensionProblemBuilder::calcForceMultipliers(Data& data, TensionProblem& problem) const {
    if (!settings_.useMusclePhysiology) return;
    calcWireSpeeds(model_, data);
    for (int w = 0; w < model_.getNumWires(); ++w) {
        WireState state;
        state.length = data.wireLength[w];
        state.speed = data.wireSpeed[w];
        problem.forceMultiplier[w] = model_.getWire(w).law->calcActiveForceMultiplier(state);
    }
    problem.forcePerActivation = settings_.maxTension.cwiseProduct(problem.forceMultiplier);
}

// Static optimization's variables: each wire's column per unit activation, activation bounds, the cost
// Σ weight_j / p |x_j|^p with weights p (Σ |x|^p, as OpenSim's), no LP cost; every row met exactly.
void TensionProblemBuilder::rewriteInActivations(TensionProblem& problem) const {
    DistributionProblem& distribution = problem.distribution;
    const int numWires = model_.getNumWires();
    distribution.tolerance.setZero(model_.getNumU());
    distribution.isEquality.assign(static_cast<std::size_t>(model_.getNumU()), true);
    for (int w = 0; w < numWires; ++w)
        for (Eigen::SparseMatrix<double>::InnerIterator it(distribution.A, w); it; ++it)
            it.valueRef() *= problem.forcePerActivation[w];
    distribution.lower.head(numWires) = settings_.minActivation;
    distribution.upper.head(numWires) = settings_.maxActivation;
    distribution.cost.setZero();
    distribution.weight.setConstant(settings_.activationExponent);
}

void TensionProblemBuilder::build(Data& data, const Eigen::VectorXd& tau, TensionProblem& problem) {
    calcWirePaths(model_, data);
    calcWireJacobianTranspose(model_, data, Jt_);
    wires_.update(data, Jt_, tau, problem.distribution);
    problem.unactuatedResidual = unactuatedRows_.apply(data, tau, model_.getNumWires(), wires_.getBlocksEnd(),
                                                       problem.distribution, problem.unactuated);
    if (settings_.variables != WireVariables::Activation) return;
    calcForceMultipliers(data, problem);
    rewriteInActivations(problem);
}

void TensionProblemBuilder::solve(TensionSolver& solver, TensionProblem& problem, DistributionResult& result) const {
    solver.solve(problem.distribution, result);
    if (result.status != DistributionStatus::Infeasible || settings_.variables == WireVariables::Activation) return;
    std::vector<bool>& isEquality = problem.distribution.isEquality;
    const std::vector<bool>& virtualLinkRows = wires_.getVirtualLinkRows();
    bool blockRowLacks = false;
    for (std::size_t i = 0; i < isEquality.size(); ++i)
        blockRowLacks = blockRowLacks || (isEquality[i] && !virtualLinkRows[i] && result.reserve[static_cast<Eigen::Index>(i)] != 0);
    if (!blockRowLacks) return;
    isEquality = virtualLinkRows;
    solver.solve(problem.distribution, result);
}

void TensionProblemBuilder::calcTensions(const TensionProblem& problem, const Eigen::VectorXd& x,
                                         Eigen::VectorXd& tension) const {
    const int numWires = model_.getNumWires();
    if (settings_.variables == WireVariables::Activation)
        tension = x.head(numWires).cwiseProduct(settings_.maxTension).cwiseProduct(problem.forceMultiplier);
    else
        tension = x.head(numWires);
}

}  // namespace sinew

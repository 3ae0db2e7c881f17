#include "sinew/tensions/static_optimization_solver.hpp"

#include <cmath>
#include <string>

#include "sinew/core/error.hpp"
#include "sinew/tensions/infeasible_frame.hpp"

namespace sinew {
namespace {

// Every row of the activation problem is exact, so Σ |a|² is the objective, not a tie-break to walk away from.
ActiveSetOptions withoutProximalSteps(ActiveSetOptions options) {
    options.proximalSteps = 0;
    return options;
}

}  // namespace

StaticOptimizationSolver::StaticOptimizationSolver(double exponent, ActiveSetOptions options)
    : exponent_(exponent), infeasibilityTolerance_(options.infeasibilityTolerance), activeSet_(withoutProximalSteps(options)) {
    if (!(exponent >= 1) || !std::isfinite(exponent))
        throw Error("static optimization: activation exponent " + std::to_string(exponent) +
                    ", expected a finite value >= 1 (below 1 the sum of activations^exponent is not convex)");
    if (exponent != 2) ipopt_ = std::make_unique<IpoptSolver>();
}

void StaticOptimizationSolver::solve(const DistributionProblem& problem, DistributionResult& result) {
    if (!ipopt_) {
        activeSet_.solve(problem, result);
        return;
    }
    ipopt_->solve(problem, exponent_, result);
    const DistributionSolve solveLeastSquares = [&](const DistributionProblem& relaxed, DistributionResult& answer) {
        ipopt_->solve(relaxed, exponent_, answer);
    };
    if (result.status != DistributionStatus::Optimal)
        reportInfeasibleFrame(problem, exponent_, infeasibilityTolerance_, solveLeastSquares, result);
}

}  // namespace sinew

#pragma once
// What a frame the QP or static-optimization solver could not solve reports (docs/tensions.md, "Infeasible
// frames"): the phase-1 LP (lp_solver.hpp) on its equality rows decides whether any x within the bounds
// meets them; if none does, the frame is Infeasible, its reserve is the smallest (L1) generalized force per
// row that would make it feasible (which DOF lacks muscle), and its x is the best least-squares answer.
#include <functional>

#include "sinew/tensions/distribution_problem.hpp"

namespace sinew {

// Solves a problem into a result (the solver that failed, on the relaxation below).
using DistributionSolve = std::function<void(const DistributionProblem&, DistributionResult&)>;

// When the phase-1 reserve of `problem`'s equality rows exceeds `tolerance` × max(1, |tau|): status
// Infeasible, result.reserve that reserve (zero on tolerance rows), and x, multipliers and kkt from
// `solveLeastSquares` on the least-squares relaxation: every row a tolerance row, the weights scaled down
// (if larger) so that their mean is 1e-6 × the columns' mean |a_j|², the QP's regulariser: the residual
// first, then the smallest cost.
// residual, Z and objective (Σ weight_j / exponent |x_j|^exponent + ½ |residual|² over the original
// tolerance rows) are then of `problem`; iterations are added. Returns false, leaving `result` as it was,
// when the frame is feasible or there are no equality rows (or Clp fails).
bool reportInfeasibleFrame(const DistributionProblem& problem, double exponent, double tolerance,
                           const DistributionSolve& solveLeastSquares, DistributionResult& result);

}  // namespace sinew

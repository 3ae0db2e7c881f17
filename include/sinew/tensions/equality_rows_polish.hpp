#pragma once
// The last digits of a distribution's equality rows (virtual-link equilibrium, the root's force with a foot
// down). A dual method meets them only up to its regulariser (sigma y, docs/tensions.md), an interior
// point up to its constraint tolerance: micronewtons on a node that a frame pulls hard against. As a QP
// solver's solution polishing does, x is then projected onto the rows: the move d of the variables that
// are off their bounds that meets them at the least ½ dᵀ H d, H the objective's curvature, cut short where
// a variable would cross a bound and repeated without the variables that reached one. Such a move,
// d = H⁻¹ Mᵀ μ (M the rows' columns), changes the objective's gradient by Mᵀ μ: the rows' multipliers
// take it up (y += μ), so the optimality conditions hold as before.
#include <Eigen/Core>

#include "sinew/tensions/distribution_problem.hpp"

namespace sinew {

// Moves x (numVariables, within the bounds) onto the equality rows where they are off by more than
// roundoff, keeping it within the bounds, and the rows' multipliers y (rows) with it. curvature
// (numBounded, > 0): the objective's second derivative per bounded variable; a free variable (which costs
// nothing) moves as the cheapest bounded one. Leaves x and y as they were where no such move lowers the
// rows' largest residual. Returns that residual after (N or N m).
double polishEqualityRows(const DistributionProblem& problem, const Eigen::VectorXd& curvature, Eigen::VectorXd& x,
                          Eigen::VectorXd& multipliers);

}  // namespace sinew

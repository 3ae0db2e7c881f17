#include "sinew/tensions/infeasible_frame.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sinew/tensions/lp_solver.hpp"

namespace sinew {

bool reportInfeasibleFrame(const DistributionProblem& problem, double exponent, double tolerance,
                           const DistributionSolve& solveLeastSquares, DistributionResult& result) {
    const int rows = problem.getNumRows(), numBounded = problem.getNumBounded();
    // Phase 1 on the equality rows alone: the QP's tolerance rows are soft, any residual is allowed there.
    std::vector<int> equalityRows;
    for (int i = 0; i < rows; ++i)
        if (problem.isEquality[static_cast<std::size_t>(i)]) equalityRows.push_back(i);
    if (equalityRows.empty()) return false;
    const int numEquality = static_cast<int>(equalityRows.size());
    Eigen::SparseMatrix<double> select(numEquality, rows);
    for (int k = 0; k < numEquality; ++k) select.insert(k, equalityRows[static_cast<std::size_t>(k)]) = 1;
    DistributionProblem phaseOne = problem;
    phaseOne.A = select * problem.A;
    phaseOne.A.makeCompressed();
    phaseOne.target = select * problem.target;
    phaseOne.tolerance.setZero(numEquality);
    phaseOne.isEquality.assign(static_cast<std::size_t>(numEquality), true);
    Eigen::VectorXd x, equalityReserve;
    int iterations = result.iterations;
    if (!solvePhaseOneLp(phaseOne, x, equalityReserve, iterations)) return false;
    const double scale = std::max(1.0, problem.target.cwiseAbs().maxCoeff());
    if (!(equalityReserve.cwiseAbs().maxCoeff() > tolerance * scale)) return false;

    DistributionProblem relaxed = problem;
    relaxed.isEquality.assign(static_cast<std::size_t>(rows), false);
    double columnTerm = 0;
    for (int j = 0; j < numBounded; ++j) columnTerm += problem.A.col(j).squaredNorm();
    const double meanWeight = numBounded ? problem.weight.mean() : 1.0;
    // The QP's own regulariser (wire_problem.hpp) when it is not already that small.
    if (columnTerm > 0) relaxed.weight *= std::min(1.0, 1e-6 * columnTerm / numBounded / meanWeight);
    solveLeastSquares(relaxed, result);

    result.status = DistributionStatus::Infeasible;
    result.iterations += iterations;
    result.reserve = select.transpose() * equalityReserve;
    calcResultSummary(problem, result);
    result.objective = 0;
    for (int j = 0; j < numBounded; ++j)
        result.objective += problem.weight[j] / exponent * std::pow(std::abs(result.x[j]), exponent);
    for (int i = 0; i < rows; ++i)
        if (!problem.isEquality[static_cast<std::size_t>(i)]) result.objective += 0.5 * result.residual[i] * result.residual[i];
    return true;
}

}  // namespace sinew

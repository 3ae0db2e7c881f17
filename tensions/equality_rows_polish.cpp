#include "sinew/tensions/equality_rows_polish.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

namespace sinew {
namespace {

// Rounds of projection: each removes the variables that the last one brought onto a bound.
constexpr int kPolishRounds = 3;
// Rows within this of their size are met: the sum A x itself rounds at about 1e-16 of its terms.
constexpr double kRoundoff = 1e-13;

double calcLargestResidual(const Eigen::VectorXd& residual, const std::vector<int>& rows) {
    double largest = 0;
    for (const int i : rows) largest = std::max(largest, std::abs(residual[i]));
    return largest;
}

}  // namespace

double polishEqualityRows(const DistributionProblem& problem, const Eigen::VectorXd& curvature, Eigen::VectorXd& x,
                          Eigen::VectorXd& multipliers) {
    std::vector<int> rows;
    for (int i = 0; i < problem.getNumRows(); ++i)
        if (problem.isEquality[static_cast<std::size_t>(i)]) rows.push_back(i);
    if (rows.empty()) return 0;
    Eigen::VectorXd residual = problem.target - problem.A * x;
    const double before = calcLargestResidual(residual, rows);
    const double size = std::max({1.0, problem.target.cwiseAbs().maxCoeff(), (problem.A * x).cwiseAbs().maxCoeff()});
    if (before <= kRoundoff * size) return before;
    std::vector<int> rowIndex(static_cast<std::size_t>(problem.getNumRows()), -1);
    for (std::size_t k = 0; k < rows.size(); ++k) rowIndex[static_cast<std::size_t>(rows[k])] = static_cast<int>(k);
    const int numBounded = problem.getNumBounded();
    const double freeCurvature = numBounded > 0 ? curvature.minCoeff() : 1.0;
    Eigen::VectorXd polished = x, polishedMultipliers = multipliers;
    for (int round = 0; round < kPolishRounds; ++round) {
        // The variables the rows see and that may move both ways: free ones, bounded ones strictly inside.
        std::vector<int> columns;
        for (int j = 0; j < problem.getNumVariables(); ++j) {
            if (j < numBounded && !(polished[j] > problem.lower[j] && polished[j] < problem.upper[j])) continue;
            for (Eigen::SparseMatrix<double>::InnerIterator it(problem.A, j); it; ++it)
                if (rowIndex[static_cast<std::size_t>(it.row())] >= 0 && it.value() != 0) {
                    columns.push_back(j);
                    break;
                }
        }
        if (columns.empty()) break;
        Eigen::MatrixXd M = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(columns.size()));
        for (std::size_t c = 0; c < columns.size(); ++c)
            for (Eigen::SparseMatrix<double>::InnerIterator it(problem.A, columns[c]); it; ++it) {
                const int k = rowIndex[static_cast<std::size_t>(it.row())];
                if (k >= 0) M(k, static_cast<Eigen::Index>(c)) = it.value();
            }
        Eigen::VectorXd offRows(static_cast<Eigen::Index>(rows.size()));
        for (std::size_t k = 0; k < rows.size(); ++k) offRows[static_cast<Eigen::Index>(k)] = residual[rows[k]];
        // The least ½ dᵀ H d with M d = residual: d = H⁻¹ Mᵀ μ, (M H⁻¹ Mᵀ) μ = residual, as small as the rows.
        Eigen::VectorXd inverseCurvature(static_cast<Eigen::Index>(columns.size()));
        for (std::size_t c = 0; c < columns.size(); ++c)
            inverseCurvature[static_cast<Eigen::Index>(c)] = 1 / (columns[c] < numBounded ? curvature[columns[c]] : freeCurvature);
        const Eigen::MatrixXd MHinv = M * inverseCurvature.asDiagonal();
        const Eigen::VectorXd mu = (MHinv * M.transpose()).completeOrthogonalDecomposition().solve(offRows);
        const Eigen::VectorXd move = MHinv.transpose() * mu;
        double step = 1;
        for (std::size_t c = 0; c < columns.size(); ++c) {
            const int j = columns[c];
            const double d = move[static_cast<Eigen::Index>(c)];
            if (j >= numBounded || d == 0) continue;
            const double room = d > 0 ? problem.upper[j] - polished[j] : polished[j] - problem.lower[j];
            step = std::min(step, room / std::abs(d));
        }
        for (std::size_t c = 0; c < columns.size(); ++c) {
            const int j = columns[c];
            polished[j] += step * move[static_cast<Eigen::Index>(c)];
            if (j < numBounded) polished[j] = std::clamp(polished[j], problem.lower[j], problem.upper[j]);
        }
        for (std::size_t k = 0; k < rows.size(); ++k) polishedMultipliers[rows[k]] += step * mu[static_cast<Eigen::Index>(k)];
        residual = problem.target - problem.A * polished;
        if (calcLargestResidual(residual, rows) <= kRoundoff * size) break;
    }
    const double after = calcLargestResidual(residual, rows);
    if (!(after < before) || !polished.allFinite()) return before;
    x = polished;
    multipliers = polishedMultipliers;
    return after;
}

}  // namespace sinew

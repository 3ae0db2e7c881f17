// The equality rows' polish (tensions/equality_rows_polish.cpp) against a dense reference: the move that
// meets the rows at the least ½ dᵀ H d is the solution of the KKT system [H -Mᵀ; M 0] [d; μ] = [0; r]
// (full-pivot LU). Bounds kept, a variable on its bound left there, a move that would cross one cut short
// there and finished without it, rows already met left alone.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "sinew/tensions/equality_rows_polish.hpp"
#include "support/random_distribution_problems.hpp"

namespace sinew {
namespace {

struct Frame {
    DistributionProblem problem;
    Eigen::VectorXd x, y, curvature;
    std::vector<int> equalityRows;
};

// A random problem with 3 equality rows and 2 free columns, x inside the bounds (every seventh tension on
// its lower bound), and the equality rows' targets 1e-4 off A x.
Frame makeFrame(unsigned seed) {
    test::RandomProblemOptions options;
    options.numFree = 2;
    options.numEquality = 3;
    options.seed = seed;
    Frame f{test::makeRandomProblem(options), {}, {}, {}, {}};
    const DistributionProblem& p = f.problem;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    f.x.resize(p.getNumVariables());
    for (int j = 0; j < p.getNumBounded(); ++j)
        f.x[j] = j % 7 == 0 ? p.lower[j] : p.lower[j] + (0.2 + 0.6 * unit(rng)) * (p.upper[j] - p.lower[j]);
    for (int j = p.getNumBounded(); j < p.getNumVariables(); ++j) f.x[j] = unit(rng) - 0.5;
    f.y = Eigen::VectorXd::Random(p.getNumRows());
    f.curvature = Eigen::VectorXd::Constant(p.getNumBounded(), 0.5) + 1.5 * (Eigen::VectorXd::Random(p.getNumBounded()).array().abs()).matrix();
    const Eigen::VectorXd Ax = p.A * f.x;
    for (int i = 0; i < p.getNumRows(); ++i) {
        if (!p.isEquality[static_cast<std::size_t>(i)]) continue;
        f.equalityRows.push_back(i);
        f.problem.target[i] = Ax[i] + 1e-4 * (unit(rng) - 0.5);
    }
    return f;
}

double largestEqualityResidual(const Frame& f, const Eigen::VectorXd& x) {
    const Eigen::VectorXd residual = f.problem.target - f.problem.A * x;
    double largest = 0;
    for (const int i : f.equalityRows) largest = std::max(largest, std::abs(residual[i]));
    return largest;
}

// The reference move over the variables strictly inside their bounds (and the free ones), the free ones
// weighted as the cheapest bounded one: (d, μ).
std::pair<Eigen::VectorXd, Eigen::VectorXd> solveReference(const Frame& f) {
    const DistributionProblem& p = f.problem;
    const int n = p.getNumVariables(), numBounded = p.getNumBounded();
    const Eigen::MatrixXd A = Eigen::MatrixXd(p.A);
    const Eigen::Index e = static_cast<Eigen::Index>(f.equalityRows.size());
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + e, n + e);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + e);
    for (int j = 0; j < n; ++j) {
        const bool inside = j >= numBounded || (f.x[j] > p.lower[j] && f.x[j] < p.upper[j]);
        if (!inside) {
            kkt(j, j) = 1;  // d_j = 0
            continue;
        }
        kkt(j, j) = j < numBounded ? f.curvature[j] : f.curvature.minCoeff();
        for (Eigen::Index k = 0; k < e; ++k) kkt(j, n + k) = -A(f.equalityRows[static_cast<std::size_t>(k)], j);
    }
    const Eigen::VectorXd residual = p.target - p.A * f.x;
    for (Eigen::Index k = 0; k < e; ++k) {
        for (int j = 0; j < n; ++j)
            if (kkt(j, n + k) != 0) kkt(n + k, j) = A(f.equalityRows[static_cast<std::size_t>(k)], j);
        rhs[n + k] = residual[f.equalityRows[static_cast<std::size_t>(k)]];
    }
    const Eigen::VectorXd solution = kkt.fullPivLu().solve(rhs);
    return {solution.head(n), solution.tail(e)};
}

TEST(EqualityRowsPolish, MovesTheLeastWeightedDistanceOntoTheRows) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
        Frame f = makeFrame(seed);
        const auto [d, mu] = solveReference(f);
        Eigen::VectorXd x = f.x, y = f.y;
        const double after = polishEqualityRows(f.problem, f.curvature, x, y);
        EXPECT_GT(largestEqualityResidual(f, f.x), 1e-6) << "seed " << seed;
        EXPECT_LE(after, 1e-13) << "seed " << seed;
        EXPECT_EQ(after, largestEqualityResidual(f, x)) << "seed " << seed;
        EXPECT_LE((x - f.x - d).lpNorm<Eigen::Infinity>(), 1e-12 * std::max(1.0, d.lpNorm<Eigen::Infinity>())) << "seed " << seed;
        for (int j = 0; j < f.problem.getNumBounded(); j += 7) EXPECT_EQ(x[j], f.x[j]) << "seed " << seed << ": on its bound";
        for (std::size_t k = 0; k < f.equalityRows.size(); ++k) {
            const int i = f.equalityRows[k];
            EXPECT_NEAR(y[i] - f.y[i], mu[static_cast<Eigen::Index>(k)], 1e-9 * std::max(1.0, mu.lpNorm<Eigen::Infinity>()))
                << "seed " << seed << " row " << i;
        }
        for (int i = 0; i < f.problem.getNumRows(); ++i) {
            if (!f.problem.isEquality[static_cast<std::size_t>(i)]) {
                EXPECT_EQ(y[i], f.y[i]) << "tolerance row " << i;
            }
        }
    }
}

TEST(EqualityRowsPolish, StopsAtABoundThenFinishesWithoutTheVariable) {
    Frame f = makeFrame(3);
    const Eigen::VectorXd d = solveReference(f).first;
    Eigen::Index k = 0;
    d.head(f.problem.getNumBounded()).cwiseAbs().maxCoeff(&k);
    // Half the reference move's room left before the bound it heads for, the rows' targets moved with it
    // (the same residual, so the same reference move).
    const double moved = (d[k] > 0 ? f.problem.upper[k] - 0.5 * d[k] : f.problem.lower[k] - 0.5 * d[k]) - f.x[k];
    f.x[k] += moved;
    for (Eigen::SparseMatrix<double>::InnerIterator it(f.problem.A, k); it; ++it) f.problem.target[it.row()] += it.value() * moved;
    Eigen::VectorXd x = f.x, y = f.y;
    const double after = polishEqualityRows(f.problem, f.curvature, x, y);
    EXPECT_EQ(x[k], d[k] > 0 ? f.problem.upper[k] : f.problem.lower[k]);
    EXPECT_LE(after, 1e-13);
    for (int j = 0; j < f.problem.getNumBounded(); ++j) {
        EXPECT_GE(x[j], f.problem.lower[j]) << j;
        EXPECT_LE(x[j], f.problem.upper[j]) << j;
    }
}

TEST(EqualityRowsPolish, LeavesRowsMetToRoundoffAlone) {
    Frame f = makeFrame(2);
    const Eigen::VectorXd Ax = f.problem.A * f.x;
    for (const int i : f.equalityRows) f.problem.target[i] = Ax[i];
    Eigen::VectorXd x = f.x, y = f.y;
    EXPECT_LE(polishEqualityRows(f.problem, f.curvature, x, y), 1e-13);
    EXPECT_EQ(x, f.x);
    EXPECT_EQ(y, f.y);
}

}  // namespace
}  // namespace sinew

// The block-arrow Cholesky (tools/block_arrow_cholesky.cpp) against Eigen's dense LLT of the same matrices:
// the factor, the three solves, the verdict on matrices that are not positive definite, and the dense
// fallback where an entry couples two blocks.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "sinew/tools/block_arrow_cholesky.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

// A random symmetric positive-definite matrix in block-arrow form: each block coupled to the trunk's rows
// from its `couplingStart` on (the trunk deepest first), to no other block.
Eigen::MatrixXd makeArrow(const std::vector<Eigen::Index>& sizes, const std::vector<Eigen::Index>& couplingStart,
                          Eigen::Index trunk, std::mt19937& rng) {
    std::normal_distribution<double> normal;
    Eigen::Index blocks = 0;
    for (Eigen::Index s : sizes) blocks += s;
    const Eigen::Index n = blocks + trunk;
    // H = B B^T with B's rows sharing columns only where H may couple them.
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, 2 * n);
    Eigen::Index first = 0;
    for (std::size_t i = 0; i < sizes.size(); ++i) {
        for (Eigen::Index r = first; r < first + sizes[i]; ++r)
            for (Eigen::Index c = first; c < first + sizes[i]; ++c) B(r, c) = normal(rng);
        // The block's own columns reach the trunk rows it couples to.
        for (Eigen::Index r = blocks + couplingStart[i]; r < n; ++r)
            for (Eigen::Index c = first; c < first + sizes[i]; ++c) B(r, c) = normal(rng);
        first += sizes[i];
    }
    for (Eigen::Index r = blocks; r < n; ++r)
        for (Eigen::Index c = n; c < 2 * n; ++c) B(r, c) = normal(rng);
    Eigen::MatrixXd H = B * B.transpose();
    H.diagonal().array() += 0.1;
    return H;
}

double relativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

void expectSolvesAsDense(const Eigen::MatrixXd& H, const std::vector<Eigen::Index>& sizes, std::mt19937& rng) {
    BlockArrowCholesky factor;
    ASSERT_TRUE(factor.compute(H, sizes));
    const Eigen::LLT<Eigen::MatrixXd> dense(H);
    ASSERT_EQ(dense.info(), Eigen::Success);
    std::normal_distribution<double> normal;
    const Eigen::MatrixXd X = Eigen::MatrixXd::NullaryExpr(H.rows(), 3, [&] { return normal(rng); });
    Eigen::MatrixXd solved = X, lower = X, lowerTransposed = X;
    factor.solveInPlace(solved);
    factor.solveLowerInPlace(lower);
    factor.solveLowerTransposeInPlace(lowerTransposed);
    EXPECT_LT(relativeError(solved, dense.solve(X)), 1e-10);
    // L is unique (positive diagonal), so the triangular solves are the dense factor's.
    EXPECT_LT(relativeError(lower, dense.matrixL().solve(X)), 1e-10);
    EXPECT_LT(relativeError(lowerTransposed, dense.matrixU().solve(X)), 1e-10);
    EXPECT_LT(relativeError(H * solved, X), 1e-10);
}

TEST(BlockArrowCholesky, SolvesAsADenseCholeskyDoes) {
    std::mt19937 rng(7);
    // The whole body's shape: head, arms, legs (on the trunk's last six rows, the pelvis), trunk.
    expectSolvesAsDense(makeArrow({3, 18, 18, 9, 9}, {3, 0, 0, 57, 57}, 63, rng), {3, 18, 18, 9, 9}, rng);
    // A block coupled to no trunk row, an empty block, and no trunk at all.
    expectSolvesAsDense(makeArrow({4, 0, 5}, {6, 0, 2}, 6, rng), {4, 0, 5}, rng);
    expectSolvesAsDense(makeArrow({4, 5}, {0, 0}, 0, rng), {4, 5}, rng);
    // No blocks: a dense factor.
    expectSolvesAsDense(makeArrow({}, {}, 12, rng), {}, rng);
}

TEST(BlockArrowCholesky, AnEntryCouplingTwoBlocksFactorsTheWholeMatrixDensely) {
    std::mt19937 rng(11);
    Eigen::MatrixXd H = makeArrow({5, 6}, {0, 2}, 7, rng);
    H(7, 1) = H(1, 7) = 0.3;  // the second block's first row with the first block's second
    expectSolvesAsDense(H, {5, 6}, rng);
}

TEST(BlockArrowCholesky, AMatrixThatIsNotPositiveDefiniteIsRefused) {
    std::mt19937 rng(3);
    const std::vector<Eigen::Index> sizes{4, 5};
    Eigen::MatrixXd H = makeArrow(sizes, {0, 0}, 6, rng);
    BlockArrowCholesky factor;
    // Negative curvature in a block, in the trunk, and a NaN.
    for (Eigen::Index at : {Eigen::Index{2}, Eigen::Index{12}}) {
        Eigen::MatrixXd indefinite = H;
        indefinite(at, at) -= 1.01 * Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H).eigenvalues().maxCoeff();
        EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(indefinite).info(), Eigen::NumericalIssue);
        EXPECT_FALSE(factor.compute(indefinite, sizes)) << "diagonal entry " << at;
    }
    Eigen::MatrixXd withNan = H;
    withNan(10, 10) = std::nan("");
    EXPECT_FALSE(factor.compute(withNan, sizes));
}

TEST(BlockArrowCholesky, BlocksLargerThanTheMatrixAreAnError) {
    BlockArrowCholesky factor;
    EXPECT_TRUE(test::throwsErrorAt([&] { factor.compute(Eigen::MatrixXd::Identity(4, 4), {3, 2}); },
                                    "block-arrow Cholesky: blocks of 5 unknowns in a 4 x 4 matrix", {}, "blocks {3, 2}"));
}

}  // namespace
}  // namespace sinew

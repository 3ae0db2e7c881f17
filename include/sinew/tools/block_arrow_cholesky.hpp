#pragma once
// The Cholesky factor L L^T = H of a symmetric positive-definite matrix in block-arrow form: independent
// blocks first, which no entry couples to one another, then a trunk that each of them may couple to,
//
//     H = [D_1       C_1^T]
//         [    D_2   C_2^T]
//         [C_1 C_2   S    ],
//
// so that L keeps that form (no fill outside it) and the blocks cost their own size, not the whole matrix's.
// A kinematic tree's Gauss-Newton matrix is one: two unknowns are coupled only where one's joint moves the
// other's link, so the subtrees hanging off a common trunk (limbs off a spine) are the blocks
// (docs/inverse-kinematics.md, "The solver"). On the whole body's 120 observed unknowns it takes a third of
// a dense Cholesky's arithmetic.
#include <Eigen/Core>
#include <vector>

namespace sinew {

class BlockArrowCholesky {
public:
    // Factors H (n x n, its lower triangle read), whose first blockSizes[0] + ... unknowns are the
    // independent blocks in that order and the rest the trunk. False where H is not numerically positive
    // definite (a pivot that is not positive). Where some entry does couple two blocks, H is factored as
    // one dense trunk: right, only slower. A block's coupling to the trunk is taken from its first trunk
    // row with a non-zero entry on, so a block that hangs from the trunk's last rows (order the trunk
    // deepest first, its root last) costs only those.
    bool compute(const Eigen::MatrixXd& H, const std::vector<Eigen::Index>& blockSizes);
    // X = H^-1 X, L^-1 X and L^-T X with the last factor computed.
    void solveInPlace(Eigen::Ref<Eigen::MatrixXd> X) const;
    void solveLowerInPlace(Eigen::Ref<Eigen::MatrixXd> X) const;
    void solveLowerTransposeInPlace(Eigen::Ref<Eigen::MatrixXd> X) const;

private:
    bool couplesTwoBlocks() const;

    Eigen::MatrixXd L_;                     // the factor in its lower triangle
    std::vector<Eigen::Index> blockStart_;  // the blocks' first unknowns, then the trunk's
    std::vector<Eigen::Index> couplingStart_;  // per block: its first coupled trunk row, counted in the trunk
};

}  // namespace sinew

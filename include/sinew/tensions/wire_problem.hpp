#pragma once
// The tension-distribution problem of a sinew model, frame by frame: rows are the model's nu DOFs,
// bounded variables its wires' tensions (N, in [0, maxTension]) and any extra column blocks
// (problem_columns.hpp: reserves, contact forces), free variables the loops' constraint forces (3 per ball
// loop, N, on link B at its loop point; link A gets the opposite). Column j of A is the generalized force
// of a unit tension, -J^T e_j (docs/wire-jacobian.md), so A x = tau is the paper's Eq. 8, tau = J^T f with
// its sign convention, plus the loops' and blocks' shares. The rows of virtual links' joints are
// equalities (a massless link is in equilibrium), and so are the rows a block marks at a frame (the root's
// force rows when a foot is down: contact_columns.hpp); every other row is a tolerance row. The whole frame
// (inverse dynamics' tau, the unactuated rows, static optimization's activations) is tension_problem.hpp.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/tensions/distribution_problem.hpp"
#include "sinew/tensions/problem_columns.hpp"

namespace sinew {

struct WireProblemOptions {
    double torqueTolerance = 1e-3;  // LP band delta on each tolerance row (N m, or N for translations)
    double wireCost = 1;            // LP cost per newton of tension, every wire
    // QP regulariser: every wire's weight is this times the frame's mean |a_j|^2 (squared moment-arm
    // norm), i.e. ½ eps mean|a|^2 |f|^2 is added to Z; it makes the least-squares tensions unique.
    double regularization = 1e-6;
};

class WireProblemBuilder {
public:
    // maxTension (numWires, N, > 0 and finite). Throws sinew::Error naming the wire otherwise. `columns`:
    // extra bounded blocks, placed after the wires in this order (kept alive by the builder).
    WireProblemBuilder(const Model& model, Eigen::VectorXd maxTension, WireProblemOptions options = {},
                       std::vector<std::shared_ptr<ProblemColumns>> columns = {});

    // A problem with this model's sparsity pattern (the DOFs each wire's, block's and loop's support can
    // reach), bounds, costs and row kinds; A's values and the target are zero until update().
    DistributionProblem makeProblem() const;

    // One frame: A = [-J^T, blocks, loop columns] in the fixed pattern (Eq. 8), target = tau (nu), the
    // QP weights, the blocks' bounds and the frame's equality rows. J is numWires x nu (calcWireJacobian); `data` must hold
    // calcPositionKinematics at the frame's q (and what the blocks read; its scratchF_G is used as
    // workspace for the loop columns).
    void update(Data& data, const Eigen::MatrixXd& J, const Eigen::VectorXd& tau, DistributionProblem& problem) const;
    // The same from J^T in sparse form (calcWireJacobianTranspose, in makeWireJacobianTransposePattern's
    // pattern), copied without a lookup: what a frame of tensions from motion uses.
    void update(Data& data, const Eigen::SparseMatrix<double>& Jt, const Eigen::VectorXd& tau,
                DistributionProblem& problem) const;

    const Model& getModel() const { return model_; }
    int getNumBlocks() const { return static_cast<int>(columns_.size()); }
    // The first column of block b (numWires for the first), and one past the blocks' last (the loops').
    int getBlockStart(int b) const { return blockStart_[static_cast<std::size_t>(b)]; }
    int getBlocksEnd() const { return blockStart_.back(); }

    // (nu) the virtual links' rows: the equality rows of every frame, before the blocks mark theirs.
    const std::vector<bool>& getVirtualLinkRows() const { return virtualLinkRows_; }

private:
    void checkFrame(const Eigen::VectorXd& tau, const DistributionProblem& problem) const;
    // Everything of update() but the wires' column values: their roundoff, the QP weights, blocks, loops, target.
    void updateAfterWires(Data& data, const Eigen::VectorXd& tau, DistributionProblem& problem) const;

    const Model& model_;
    Eigen::VectorXd maxTension_;
    WireProblemOptions options_;
    std::vector<std::shared_ptr<ProblemColumns>> columns_;
    std::vector<int> blockStart_;           // (blocks + 1)
    std::vector<bool> virtualLinkRows_;     // (nu)
    Eigen::SparseMatrix<double> pattern_;  // (nu x (numWires + block columns + 3 numLoops)) ones where A may be non-zero
};

}  // namespace sinew

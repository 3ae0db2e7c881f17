#pragma once
// The tension-distribution problem of a sinew model, frame by frame: rows are the model's nu DOFs,
// bounded variables its wires' tensions (N, in [0, maxTension]), free variables the loops' constraint
// forces (3 per ball loop, N, on link B at its loop point; link A gets the opposite). Column j of A is the
// generalized force of a unit tension, -J^T e_j (docs/wire-jacobian.md), so A x = tau means the wires and
// loops produce the generalized forces tau. The rows of virtual links' joints are equalities (a massless
// link is in equilibrium); every other row is a tolerance row.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/tensions/distribution_problem.hpp"

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
    // maxTension (numWires, N, > 0 and finite). Throws sinew::Error naming the wire otherwise.
    WireProblemBuilder(const Model& model, Eigen::VectorXd maxTension, WireProblemOptions options = {});

    // A problem with this model's sparsity pattern (the DOFs each wire's and loop's support can reach), bounds,
    // costs and row kinds; A's values and the target are zero until update().
    DistributionProblem makeProblem() const;

    // One frame: A = [-J^T, loop columns] in the fixed pattern, target = tau (nu), the QP weights. J is
    // numWires x nu (calcWireJacobian); `data` must hold calcPositionKinematics at the frame's q (its F_G is
    // used as workspace for the loop columns).
    void update(Data& data, const Eigen::MatrixXd& J, const Eigen::VectorXd& tau, DistributionProblem& problem) const;

    const Model& getModel() const { return model_; }

private:
    const Model& model_;
    Eigen::VectorXd maxTension_;
    WireProblemOptions options_;
    Eigen::SparseMatrix<double> pattern_;  // (nu x (numWires + 3 numLoops)) ones where A may be non-zero
};

}  // namespace sinew

#pragma once
// The loads every joint and loop closure carries (docs/joint-loads.md), from inverse dynamics: what a joint
// transmits is its subtree's net force, inertial less applied, which calcInverseDynamics accumulates tip to
// base before projecting it onto the joint's motion subspace.
#include <Eigen/Core>
#include <Eigen/QR>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"

namespace sinew {

// Results and workspace of calcJointReactions for one Model, sized once at construction.
struct JointReactionsData {
    explicit JointReactionsData(const Model& model);

    // Per link (numLinks): the spatial force [moment; force] (N m; N) the parent (or ground) applies to the
    // link through its joint, as though applied at the joint centre (the origin of M, Data::p_GM), its
    // generalized forces included: Simbody's calcMobilizerReactionForces convention. F_GM in ground axes;
    // F_BM the same force in the link's frame B axes.
    std::vector<SpatialVector> F_GM, F_BM;
    // Per loop (numLoops): the force (N) the ball closure applies to link B at its point p_B, in ground and
    // in link B's axes. Link A receives its negative at p_A.
    std::vector<Eigen::Vector3d> loopForce_G, loopForce_B;
    // Generalized forces (nu; N or N m) the joints and loop forces leave unexplained: inverse dynamics with
    // the loop forces, less the applied generalized forces. Zero to roundoff when udot is the forward
    // dynamics of the forces given; otherwise the joints' motion subspaces carry the difference too.
    Eigen::VectorXd residual;

    // Workspace (numLinks, nu x 3 numLoops, 3 numLoops): the applied and loop link forces, the generalized
    // forces of unit loop forces (the transposed loop-constraint Jacobian), the loop forces stacked.
    std::vector<SpatialVector> linkForces_G;
    Eigen::MatrixXd loopColumns;
    Eigen::VectorXd loopForces;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> loopSolver;
};

// The reactions at coordinates q (nq), speeds u (nu) and accelerations udot (nu) under the applied
// generalized forces (nu; N or N m, on the right of M udot + C = tau + ...) and link forces (numLinks, in
// the Data::F_G convention: moment about the link's origin, force, ground axes; wire tensions enter as
// calcWireLinkForces gives them). Gravity is the model's. The loop forces are the least-squares,
// minimum-norm solution of (loop columns) f = inverse dynamics - tau, unique unless loops are redundant.
// Fills Data's kinematics for (q, u) and alpha_GB, a_GB; uses Data::scratchF_G.
void calcJointReactions(const Model& model, Data& data, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                        const Eigen::VectorXd& udot, const Eigen::VectorXd& appliedGeneralizedForces,
                        const std::vector<SpatialVector>& appliedLinkForces, JointReactionsData& reactions);

}  // namespace sinew

#pragma once
// The wire Jacobian J = d(length)/d(u) (numWires x nu), the paper's Eq. (3)-(7), and the generalized forces
// of wire tensions. docs/wire-jacobian.md derives both and fixes the sign convention.
#include <Eigen/Core>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

// J(w, :) = sum over segments (1/l)(p_{j+1} - p_j)^T (J_p{j+1} - J_p{j}); so wireSpeed = J u.
// J must be numWires x nu. Needs calcPositionKinematics and calcWirePaths. Each row costs O(points + the
// links between the wire's points and the root).
void calcWireJacobian(const Model& model, Data& data, Eigen::Ref<Eigen::MatrixXd> J);

// The spatial forces (moment about the ground origin; force) that tensions f >= 0 (numWires, N) exert on
// each link, into Data::F_G. Needs calcWirePaths.
void calcWireLinkForces(const Model& model, Data& data, const Eigen::VectorXd& tensions);

// The generalized forces (nu) that tensions f >= 0 (numWires, N) exert: tau = -J^T f, since a tension
// shortens its wire. Computed in one tip-to-base pass without forming J. Needs calcWirePaths.
void calcWireGeneralizedForces(const Model& model, Data& data, const Eigen::VectorXd& tensions,
                               Eigen::Ref<Eigen::VectorXd> tau);

}  // namespace sinew

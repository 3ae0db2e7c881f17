#pragma once
// The wire Jacobian J = d(length)/d(u) (numWires x nu), the paper's Eq. (3)-(7), and the generalized forces
// of wire tensions. docs/wire-jacobian.md derives both and fixes the sign convention.
#include <Eigen/Core>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

// J(w, :) = sum over segments (1/l)(p_{j+1} - p_j)^T (J_p{j+1} - J_p{j}); so wireSpeed = J u. Wrap
// tangent points count as fixed on their objects' links, and a moving point adds its motion in its link to
// its coordinate's column (docs/wire-paths.md); a wire over an ellipsoid takes its row from
// Data::wireLengthGradient. J must be numWires x nu. Needs calcPositionKinematics and calcWirePaths. Each
// row costs O(points + the links between the wire's points and the root). Uses Data::scratchF_G.
void calcWireJacobian(const Model& model, Data& data, Eigen::Ref<Eigen::MatrixXd> J);

// The spatial forces (moment about each link's origin; force) that tensions f >= 0 (numWires, N) exert on
// each link, into Data::F_G. Needs calcWirePaths. The rest of their generalized forces acts on coordinates
// directly: addWireCoordinateForces gives it.
void calcWireLinkForces(const Model& model, Data& data, const Eigen::VectorXd& tensions);

// Adds to tau (nu) the generalized forces of tensions f that are no link forces: through moving points'
// motion in their links (OpenSim's MovingPathPoint), -f dL/dp . R_GB dp_B/dq on the coordinate's u; and all
// of a wire over an ellipsoid's, -f dL/du from Data::wireLengthGradient. Zero for models with neither.
// Needs calcWirePaths.
void addWireCoordinateForces(const Model& model, const Data& data, const Eigen::VectorXd& tensions,
                             Eigen::Ref<Eigen::VectorXd> tau);

// The generalized forces (nu) that tensions f >= 0 (numWires, N) exert: tau = -J^T f, since a tension
// shortens its wire. Computed in one tip-to-base pass without forming J. Needs calcWirePaths. Leaves the
// wires' link forces in Data::F_G (calcWireLinkForces); uses Data::scratchF_G.
void calcWireGeneralizedForces(const Model& model, Data& data, const Eigen::VectorXd& tensions,
                               Eigen::Ref<Eigen::VectorXd> tau);

}  // namespace sinew

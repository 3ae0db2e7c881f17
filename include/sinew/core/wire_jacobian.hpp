#pragma once
// The wire Jacobian J = d(length)/d(u) (numWires x nu), the paper's Eq. (3)-(7), and the generalized forces
// of wire tensions. docs/wire-jacobian.md derives both and fixes the sign convention.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

// J(w, :) = sum over segments (1/l)(p_{j+1} - p_j)^T (J_p{j+1} - J_p{j}); so wireSpeed = J u. Wrap
// tangent points count as fixed on their objects' links, and a moving point adds its motion in its link to
// its coordinate's column (docs/wire-paths.md); a wire over an ellipsoid takes its row from
// Data::wireLengthGradient. J must be numWires x nu. Needs calcPositionKinematics and calcWirePaths. Each
// row costs O(points + its span links); zeroing J costs O(numWires x nu). Uses Data::scratchF_G.
void calcWireJacobian(const Model& model, Data& data, Eigen::Ref<Eigen::MatrixXd> J);

// J's transpose in sparse form (nu x numWires, column-major, compressed), the form the tension problems take:
// column w holds row w of J on the speeds of wire w's span links' joints (Wire::numSpanLinks) and of its
// moving points' coordinates; J is zero elsewhere. The pattern depends on the model only; the values are zero.
Eigen::SparseMatrix<double> makeWireJacobianTransposePattern(const Model& model);

// Fills the values of Jt, a matrix made by makeWireJacobianTransposePattern(model), with J^T. Costs O(the
// wires' points and span links), not O(numWires x nu); allocates nothing. Needs what calcWireJacobian needs.
void calcWireJacobianTranspose(const Model& model, Data& data, Eigen::SparseMatrix<double>& Jt);

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

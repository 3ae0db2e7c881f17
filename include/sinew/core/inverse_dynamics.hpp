#pragma once
// Inverse dynamics of the link tree by the recursive Newton-Euler algorithm (docs/opensim-joints.md,
// "Inverse dynamics"; Featherstone, Rigid Body Dynamics Algorithms (2008), sec. 5.3). O(N), allocation-free.
#include <Eigen/Core>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"

namespace sinew {

// The generalized forces tau (nu) with M(q) udot + C(q, u) = tau + gravity + applied, on every joint type:
// what Simbody's SimbodyMatterSubsystem::calcResidualForceIgnoringConstraints returns (and OpenSim's
// inverse dynamics reports), loops ignored. appliedLinkForces has one spatial force per link in the
// Data::F_G convention (moment about the link's origin; force; ground axes). Fills Data's position and
// velocity kinematics for (q, u), alpha_GB and a_GB; uses Data::scratchF_G, and leaves Data::F_G alone.
void calcInverseDynamics(const Model& model, Data& data, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                         const Eigen::VectorXd& udot, const std::vector<SpatialVector>& appliedLinkForces,
                         Eigen::Ref<Eigen::VectorXd> tau);

// The same, with Data's position kinematics already at q (calcPositionKinematics), as they are where the
// applied forces were evaluated at q: the poses are not computed twice.
void calcInverseDynamicsAtPositions(const Model& model, Data& data, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                                    const Eigen::VectorXd& udot, const std::vector<SpatialVector>& appliedLinkForces,
                                    Eigen::Ref<Eigen::VectorXd> tau);

}  // namespace sinew

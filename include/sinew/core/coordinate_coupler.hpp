#pragma once
// Coupled coordinates (OpenSim's CoordinateCouplerConstraint, Model::getCouplers): putting a pose on the
// constraint manifold. Both engines enforce couplers in forward dynamics (calcForwardDynamics; Simbody's
// Constraint::CoordinateCoupler, sinew/plugin/coordinate_constraints.hpp).
#include <Eigen/Core>

#include "sinew/core/model.hpp"

namespace sinew {

// Sets every coupler's dependent coordinate from its independent one, q_dep = scaleFactor * f(q_indep), as
// OpenSim's assembly does before an analysis (Model::assemble, which gives dependent coordinates no goal of
// their own): for motions whose table lacks the dependent column, or whose values drift from it. OpenSim's
// InverseDynamicsTool does not do this (a missing column is held at its default value, a present one used
// as it is), so inverse dynamics should be given the motion as it stands. Allocates nothing.
void applyCoordinateCouplers(const Model& model, Eigen::Ref<Eigen::VectorXd> q);

}  // namespace sinew

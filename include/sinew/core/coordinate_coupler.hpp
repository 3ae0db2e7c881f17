#pragma once
// Coupled coordinates (OpenSim's CoordinateCouplerConstraint, Model::getCouplers): putting a pose on the
// constraint manifold, and refusing the engines that would let the dependent coordinate drift.
#include <Eigen/Core>
#include <string>

#include "sinew/core/model.hpp"

namespace sinew {

// Sets every coupler's dependent coordinate from its independent one, q_dep = scaleFactor * f(q_indep), as
// OpenSim's assembly does before an analysis (Model::assemble, which gives dependent coordinates no goal of
// their own): for motions whose table lacks the dependent column, or whose values drift from it. OpenSim's
// InverseDynamicsTool does not do this (a missing column is held at its default value, a present one used
// as it is), so inverse dynamics should be given the motion as it stands. Allocates nothing.
void applyCoordinateCouplers(const Model& model, Eigen::Ref<Eigen::VectorXd> q);

// Throws sinew::Error naming the model's first coupler, for `engine` (e.g. "sinew's forward dynamics"),
// which integrates every coordinate as free and would break the coupling.
void requireNoCouplers(const Model& model, const std::string& engine);

}  // namespace sinew

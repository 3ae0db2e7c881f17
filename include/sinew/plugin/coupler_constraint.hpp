#pragma once
// OpenSim's CoordinateCouplerConstraint as Simbody's Constraint::CoordinateCoupler, the way OpenSim builds it
// (CoordinateCouplerConstraint::extendAddToSystem): one function of the dependent and independent
// coordinates held at zero, q_dep - s f(q_ind) = 0.
#include "sinew/plugin/ndebug_guard.hpp"

#include <Simbody.h>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

// Adds `coupler` of `model` to `matter`; mobilizedBodies[link] is each link's mobilized body.
SimTK::ConstraintIndex addCouplerConstraint(SimTK::SimbodyMatterSubsystem& matter, const Model& model,
                                            const CoordinateCoupler& coupler,
                                            const std::vector<SimTK::MobilizedBodyIndex>& mobilizedBodies);

}  // namespace sinew

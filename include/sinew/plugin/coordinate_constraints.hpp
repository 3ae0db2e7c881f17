#pragma once
// OpenSim's constraints on single coordinates in Simbody, built the way OpenSim builds them: a
// CoordinateCouplerConstraint as Constraint::CoordinateCoupler (CoordinateCouplerConstraint::
// extendAddToSystem: one function of the dependent and independent coordinates held at zero, q_dep -
// s f(q_ind) = 0), and a locked coordinate as Constraint::PrescribedMotion of a constant, its default value
// (Coordinate::extendAddToSystem, setLocked).
#include "sinew/plugin/ndebug_guard.hpp"

#include <Simbody.h>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

// Adds `coupler` of `model` to `matter`; mobilizedBodies[link] is each link's mobilized body.
SimTK::ConstraintIndex addCouplerConstraint(SimTK::SimbodyMatterSubsystem& matter, const Model& model,
                                            const CoordinateCoupler& coupler,
                                            const std::vector<SimTK::MobilizedBodyIndex>& mobilizedBodies);

// Holds coordinate q (a custom joint's) of `model` at its default value.
SimTK::ConstraintIndex addLockConstraint(SimTK::SimbodyMatterSubsystem& matter, const Model& model, int q,
                                         const std::vector<SimTK::MobilizedBodyIndex>& mobilizedBodies);

}  // namespace sinew

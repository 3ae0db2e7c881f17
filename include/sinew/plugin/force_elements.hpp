#pragma once
// The model's force elements (core/force_elements.hpp) in Simbody, built as OpenSim builds them: a
// PointToPointSpring as Force::TwoPointLinearSpring, a BushingForce as Force::LinearBushing, a
// HuntCrossleyForce as Simbody's HuntCrossleyForce on a GeneralContactSubsystem contact set (one per force,
// each surface's parameters set on it), and a CoordinateLimitForce (OpenSim's own element) as a
// Force::Custom mobility force from core's formula.
#include "sinew/plugin/ndebug_guard.hpp"

#include <Simbody.h>
#include <memory>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

// Adds every force element of `model` to `system`; mobilizedBodies[link] is each link's mobilized body.
// Returns the contact subsystem the Hunt-Crossley forces use (null without contact): Simbody's forces keep a
// reference to this handle, so its owner must keep it as long as the system.
std::unique_ptr<SimTK::GeneralContactSubsystem> addForceElements(SimTK::MultibodySystem& system, SimTK::SimbodyMatterSubsystem& matter,
                      SimTK::GeneralForceSubsystem& forces, const Model& model,
                      const std::vector<SimTK::MobilizedBodyIndex>& mobilizedBodies);

}  // namespace sinew

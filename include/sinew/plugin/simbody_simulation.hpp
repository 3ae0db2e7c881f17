#pragma once
// Forward simulation of a model under gravity and its wires with Simbody's integrators, reporting frames at a
// fixed interval (the paper's section 4.1 experiment with hangBy set). The options and frames are the
// engine-independent ones of sinew/core/simulation.hpp; sinew's own engine is simulateForwardSinew
// (sinew/core/forward_simulation.hpp).
#include "sinew/plugin/ndebug_guard.hpp"

#include <functional>

#include "sinew/core/model.hpp"
#include "sinew/core/simulation.hpp"

namespace sinew {

// Calls onFrame for t = 0 and every reportInterval up to duration. Integrator::Adaptive is Simbody's
// Runge-Kutta-Merson with error control at options.accuracy; RungeKutta4Fixed the same method with
// setFixedStepSize (the report interval split into equal steps no longer than fixedStep). Loops, couplers and the
// hang weld are Simbody constraints, projected to options.accuracy. Virtual links are held in quasi-static
// equilibrium by a VirtualLinkWireForce (simbody_model.hpp); frames carry their poses and quasi-static
// twists (SimulationSummary::maxVirtualLinkResidual: how well it held). Throws sinew::Error for an
// integration failure, naming the time.
SimulationSummary simulateForward(const Model& model, const ForwardSimulationOptions& options,
                                  const std::function<void(const SimulationFrame&)>& onFrame);

}  // namespace sinew

#pragma once
// Forward simulation of a model under gravity and its wires with Simbody's error-controlled integrator,
// reporting frames at a fixed interval (the paper's section 4.1 experiment with hangBy set).
#include "sinew/simbody/ndebug_guard.hpp"

#include <Eigen/Core>
#include <functional>
#include <string>

#include "sinew/core/model.hpp"

namespace sinew {

struct ForwardSimulationOptions {
    std::string hangBy;            // link welded to ground at its default pose; empty for none
    double duration = 1.0;         // s
    double reportInterval = 0.01;  // s between output frames
    double accuracy = 1e-6;        // integrator relative accuracy, also the constraint tolerance
    Eigen::VectorXd initialSpeeds;  // u at t = 0 (nu), projected onto the loop constraints; empty: at rest
};

struct SimulationFrame {
    double time = 0;           // s
    Eigen::VectorXd q;         // nq
    Eigen::VectorXd u;         // nu
    Eigen::VectorXd tensions;  // N, per wire
    double kineticEnergy = 0;    // J
    double potentialEnergy = 0;  // J, gravity plus conservative wire laws
};

struct SimulationSummary {
    int frames = 0;
    int steps = 0;                // integrator steps taken
    double wallSeconds = 0;       // integration and reporting, not system construction
    double initialEnergy = 0;     // J
    double maxEnergyDrift = 0;    // J, max |E(t) - E(0)| over the reported frames
    double peakKineticEnergy = 0;  // J, scale for the drift
};

// Calls onFrame for t = 0 and every reportInterval up to duration. Throws sinew::Error for a model Simbody
// cannot simulate (virtual links, whose massless forward dynamics comes with the closed-chain solver) or
// an integration failure, naming the time.
SimulationSummary simulateForward(const Model& model, const ForwardSimulationOptions& options,
                                  const std::function<void(const SimulationFrame&)>& onFrame);

}  // namespace sinew

#pragma once
// Records every output frame of a simulation run, for comparing engines on whole trajectories.
#include <vector>

#include "sinew/core/simulation.hpp"

namespace sinew {

struct Trajectory {
    std::vector<SimulationFrame> frames;
    SimulationSummary summary;
};

template <class Engine>
Trajectory record(Engine engine, const Model& model, const ForwardSimulationOptions& options) {
    Trajectory trajectory;
    trajectory.summary = engine(model, options, [&](const SimulationFrame& frame) { trajectory.frames.push_back(frame); });
    return trajectory;
}

}  // namespace sinew

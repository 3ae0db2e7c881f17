#pragma once
// OpenSim's inverse dynamics tool on a sinew model: a coordinates table (e.g. inverse kinematics output)
// processed as OpenSim processes it (padding, low-pass, quintic splines; docs/signal-processing.md), measured
// external loads, then sinew's recursive Newton-Euler inverse dynamics per frame. The per-frame call is
// calcInverseDynamics (include/sinew/core/inverse_dynamics.hpp); this file runs whole motions and setups.
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "sinew/core/model.hpp"
#include "sinew/io/external_loads.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/io/tool_setup.hpp"

namespace sinew {

struct InverseDynamicsOptions {
    double lowpassCutoffHz = -1;  // negative: no filtering (OpenSim's default)
    double startTime = -std::numeric_limits<double>::infinity();  // s, OpenSim's time_range
    double finalTime = std::numeric_limits<double>::infinity();
    // The model's force elements (springs, bushings, limits, contact) act on the motion, as OpenSim applies
    // every force forces_to_exclude does not name; the generalized forces are then what the rest must give.
    bool forceElements = true;
    // Progress, optional: frame rises from 1 and the last call has frame == frames. The frames run in two
    // halves on two threads, so it is called from one thread, not always the caller's, and may skip counts.
    std::function<void(int frame, int frames)> onFrame;
};

// Generalized forces per frame, one column per speed named as OpenSim names them ("<coordinate>_moment"
// for rotational coordinates, "<coordinate>_force" otherwise; a ball or free joint j: j_wx_moment..
// j_wz_moment about F's axes, a free joint's j_vx_force.. along them). The table's columns must be exactly
// the model's coordinates (the error lists what is missing or extra; quaternions as coordinate_table.hpp
// reads them); rotational columns of an inDegrees table are converted.
StorageTable runInverseDynamics(const Model& model, const StorageTable& coordinates, const ExternalLoads* loads,
                                const InverseDynamicsOptions& options);

// An OpenSim InverseDynamicsTool setup as it stands: reads its model (.osim or sinew YAML), coordinates and
// external loads with paths relative to the setup file, runs, and writes results_directory/
// output_gen_force_file (or into outputDirectory when given). Returns the file written. The wires never
// enter sinew's inverse dynamics, as with forces_to_exclude "Muscles"; the model's force elements do unless
// it names "All"; `notes` receives what the run left out or could not honour.
std::string runInverseDynamicsTool(const InverseDynamicsSetup& setup, const std::string& outputDirectory,
                                   const std::function<void(const std::string&)>& notes,
                                   const std::function<void(int frame, int frames)>& onFrame = {});

}  // namespace sinew

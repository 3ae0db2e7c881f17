#pragma once
// OpenSim's AnalyzeTool with a StaticOptimization analysis on a sinew model (docs/tensions-from-motion.md,
// "OpenSim static optimization"): the coordinates processed as the AnalyzeTool processes them (padding and
// low-pass, quintic splines for the speeds, quintic splines through the speeds for the accelerations), then
// per frame min Σ a² over the muscles' activations and the reserve actuators' controls with the inverse
// dynamics generalized forces met exactly, each muscle's force per unit activation from its force-length,
// force-velocity and pennation (use_muscle_physiology).
//
// runStaticOptimizationTool (static_optimization_tool.cpp) reads the setup and its files;
// runOsimStaticOptimization (osim_static_optimization.cpp) solves.
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/io/external_loads.hpp"
#include "sinew/io/osim_actuator.hpp"
#include "sinew/io/storage_file.hpp"

namespace sinew {

struct AnalyzeSetup;

struct OsimStaticOptimizationOptions {
    // false: the motion is coordinates (filtered at lowpassCutoffHz, splined); true: OpenSim states, q and u
    // taken as they are (osim_states.hpp; the cut-off does not apply, as in OpenSim).
    bool motionIsStates = false;
    double lowpassCutoffHz = -1;  // Hz; negative: no filtering
    double startTime = -std::numeric_limits<double>::infinity();  // s
    double finalTime = std::numeric_limits<double>::infinity();
    // Reserve actuators: the model's and the force-set files' CoordinateActuators that apply force, then
    // their PointActuators and TorqueActuators (residuals on a floating root), in that order of columns.
    std::vector<OsimCoordinateActuator> reserves;
    std::vector<OsimPointActuator> pointActuators;
    std::vector<OsimTorqueActuator> torqueActuators;
    // (numWires) each muscle's min_control / max_control (OpenSim bounds activations by them); empty: [0, 1].
    Eigen::VectorXd minActivation, maxActivation;
    bool useMusclePhysiology = true;
    double activationExponent = 2;  // OpenSim's activation_exponent (>= 1)
    int stepInterval = 1;  // OpenSim's step_interval (TensionMotionOptions::stepInterval)
    std::function<void(int frame, int frames)> onFrame;
};

struct OsimStaticOptimizationResult {
    // OpenSim's <name>_StaticOptimization_force.sto: each muscle's force (N), then each reserve's (N m or N).
    StorageTable force;
    // <name>_StaticOptimization_activation.sto: each muscle's activation, then each reserve's control.
    StorageTable activation;
    // Per frame: status, Z, ... as TensionMotionResult::report (tension_motion.hpp).
    StorageTable report;
    int flaggedFrames = 0;  // frames the solver did not solve to optimality
};

// The wires must all have a muscle law (thelen2003_muscle, millard2012_muscle) when useMusclePhysiology; a
// reserve's coordinate or bodies must be the model's (else sinew::Error at the actuator's file:line).
OsimStaticOptimizationResult runOsimStaticOptimization(const Model& model, const StorageTable& motionTable,
                                                       const ExternalLoads* loads,
                                                       const OsimStaticOptimizationOptions& options);

// An AnalyzeTool setup with a StaticOptimization analysis, as it stands: model (.osim), force-set files,
// states or coordinates, external loads, cut-off, time range. Writes <name>_StaticOptimization_force.sto,
// _activation.sto and sinew's per-frame _report.sto into results_directory (or outputDirectory when
// given) and returns the files written. `notes` receives what the run left out or could not honour.
std::vector<std::string> runStaticOptimizationTool(const AnalyzeSetup& setup, const std::string& outputDirectory,
                                                   const std::function<void(const std::string&)>& notes,
                                                   const std::function<void(int frame, int frames)>& onFrame = {});

}  // namespace sinew

#pragma once
// Wire tensions over a whole motion (docs/tensions-from-motion.md): a coordinates table processed as
// OpenSim's tools process it (coordinate_preprocessing.hpp), measured external loads, then
// TensionAnalysis::calcFrame per frame. Every frame is kept: an infeasible or failed one is flagged in the
// report with its residuals, never dropped.
#include <functional>
#include <limits>

#include "sinew/core/model.hpp"
#include "sinew/io/external_loads.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tools/tension_analysis.hpp"

namespace sinew {

struct TensionMotionOptions {
    TensionAnalysisOptions analysis;
    double lowpassCutoffHz = -1;  // negative: no filtering
    double startTime = -std::numeric_limits<double>::infinity();  // s
    double finalTime = std::numeric_limits<double>::infinity();
    // false: udot is the second derivative of the coordinates' quintic splines (the inverse dynamics tool);
    // true: the first derivative of quintic splines through the speeds at every processed row (OpenSim's
    // AnalyzeTool states, which StaticOptimization differentiates again).
    bool accelerationsFromSpeedSplines = false;
    std::function<void(int frame, int frames)> onFrame;  // progress, optional
};

struct TensionMotionResult {
    StorageTable tensions;     // N, one column per wire (its name)
    StorageTable activations;  // static optimization: one column per wire; empty otherwise
    StorageTable reserves;     // static optimization with reserves: N m or N, one column per reserve
    // Per frame: status (0 optimal, 1 infeasible, 2 failed), Z (N² m²), active_wires, iterations,
    // unactuated_residual (|tau| on DOFs no wire reaches), then <coordinate>_residual and
    // <coordinate>_reserve per DOF (see TensionFrame).
    StorageTable report;
    int flaggedFrames = 0;  // frames whose status is not optimal
};

// The model's coordinates must all be scalar and the table's columns exactly the model's coordinates
// (readCoordinateSamples says what is missing or extra).
TensionMotionResult runTensionAnalysis(const Model& model, const StorageTable& motion, const ExternalLoads* loads,
                                       const TensionMotionOptions& options);

}  // namespace sinew

#pragma once
// An OpenSim states table (.sto: an AnalyzeTool <states_file>, a forward simulation's or CMC's states) on a
// sinew model, as OpenSim's AnalyzeTool and StaticOptimization take it (docs/tensions-from-motion.md,
// "States files"): q and u are the file's values at its rows, unfiltered; u̇ is the derivative of
// interpolating quintic splines through each speed column over every row of the file
// (StaticOptimization's GCVSplineSet(5, states)).
//
// Columns are found as OpenSim's TableUtilities::findStateLabelIndex finds them: the state path
// /jointset/<joint>/<coordinate>/value (or /speed) or any tail of it (<coordinate>/value), else the
// OpenSim 3 names <coordinate> and <coordinate>_u. Other columns (muscle activations, fibre lengths) are
// ignored.
#include <limits>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/model.hpp"
#include "sinew/io/storage_file.hpp"

namespace sinew {

// Frames: the rows from the last one at or before startTime (or the first) to the last one at or before
// finalTime (OpenSim's Storage::findIndex). The model's coordinates must be scalar. Throws sinew::Error at
// the table's file:line naming a coordinate whose value or speed column is missing, a table in degrees
// (OpenSim refuses those too), or a time range that selects no row.
CoordinateTrajectory readOsimStates(const Model& model, const StorageTable& states,
                                    double startTime = -std::numeric_limits<double>::infinity(),
                                    double finalTime = std::numeric_limits<double>::infinity());

}  // namespace sinew

#pragma once
// The generalized coordinates, speeds and accelerations OpenSim 4.4's InverseDynamicsTool derives from a
// coordinates table: with a cutoff >= 0, pad by half the row count (Storage::pad), resample to a uniform
// step if the times are not uniform (Storage::resample), low-pass (Storage::lowpassIIR); convert degrees;
// fit interpolating quintic GCVSPL splines (GCVSplineSet(5, ...)) and differentiate them at the table's
// rows inside the time range. Step by step, with sources, in docs/signal-processing.md.
#include <Eigen/Core>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sinew/signal/smoothing_spline.hpp"

namespace sinew {

// The splines' set-ups a table's processing made, for another table with the same times to reuse (the
// set-ups depend on the times alone).
struct CoordinateSplineSetUps {
    std::optional<SplineInterpolation> resampling;  // on the padded rows, where uneven rows were resampled
    std::optional<SplineInterpolation> final;       // on the processed rows
};

struct CoordinatePreprocessingOptions {
    // Hz; negative: no padding, resampling or filtering (OpenSim's default -1). Zero is refused.
    double lowpassCutoffHz = -1;
    // s; the tool's time_range: frames from the last row at or before startTime (or the first row) to the
    // last row at or before finalTime. The default takes every row, padding included.
    double startTime = -std::numeric_limits<double>::infinity();
    double finalTime = std::numeric_limits<double>::infinity();
    int splineDegree = 5;  // OpenSim's InverseDynamicsTool: 5
    // Per column, applied after filtering and before the splines as OpenSim converts degrees: pi/180 for
    // the rotational coordinates of an inDegrees=yes table, 1 for translations. Empty: all 1.
    Eigen::VectorXd columnScales;
    // Only for error messages (which otherwise say "column 3"); empty or one per column.
    std::vector<std::string> columnNames;
    // An earlier table's (CoordinateTrajectory::setUps): each set-up is used where its sites and degree are
    // this table's, else made anew. The result is the same either way.
    std::shared_ptr<const CoordinateSplineSetUps> setUps;
};

struct CoordinateTrajectory {
    Eigen::VectorXd times;  // (nFrames) s: rows of the processed table, so resampled times when resampled
    Eigen::MatrixXd q;      // (nFrames x nColumns) the splines' values, in the scaled units
    Eigen::MatrixXd qdot;   // (nFrames x nColumns) first derivatives, per s
    Eigen::MatrixXd qddot;  // (nFrames x nColumns) second derivatives, per s^2
    // The processed table the splines interpolate (padded, resampled, filtered, scaled; nRows x nColumns)
    // and the splines themselves, to evaluate at other times.
    Eigen::VectorXd processedTimes;
    Eigen::MatrixXd processedValues;
    Eigen::Index firstRow = 0;   // times(0)'s row in processedTimes (OpenSim's states-storage index)
    std::vector<SmoothingSpline> splines;
    double samplePeriod = 0;     // s; the filter's step (0 without filtering)
    double usedCutoffHz = -1;    // the cutoff applied (0.49 of the sampling rate if the request exceeded Nyquist)
    bool resampled = false;      // whether uneven times were resampled to samplePeriod
    std::shared_ptr<const CoordinateSplineSetUps> setUps;  // the splines' set-ups this processing used
};

// `times` (nRows) strictly increasing; `values` (nRows x nColumns), one column per coordinate as in the
// file. Throws sinew::Error naming the row, column or option at fault (non-finite numbers, times not
// increasing, too few rows for the spline, a time range that selects no row).
CoordinateTrajectory preprocessCoordinates(const Eigen::VectorXd& times, const Eigen::MatrixXd& values,
                                           const CoordinatePreprocessingOptions& options = {});

// The checks preprocessCoordinates starts with, and their errors: sizes, names and scales, rows enough for
// the splines, times finite and increasing, values finite, row by row. For a caller that processes the
// columns in parts, so that the whole table's first bad row is the one reported.
void checkCoordinateTable(const Eigen::VectorXd& times, const Eigen::MatrixXd& values,
                          const CoordinatePreprocessingOptions& options);

}  // namespace sinew

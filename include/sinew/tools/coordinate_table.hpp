#pragma once
// A motion table (.mot/.sto: IK results, simulation states) read onto a model's coordinates: columns
// matched by name, rotational coordinates of an inDegrees table converted to radians. Ball and free joints
// read as their quaternion columns (j_qw j_qx j_qy j_qz, never converted: no angles) and a free joint's
// position (j_x j_y j_z, m).
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/model.hpp"
#include "sinew/io/storage_file.hpp"

namespace sinew {

struct CoordinateSamples {
    Eigen::VectorXd times;  // (rows) s
    Eigen::MatrixXd q;      // (rows x nq) rad or m, in the model's q order
    // (nq) the factor each column was converted by from the table's units: pi/180 for the rotational
    // coordinates of an inDegrees table, else 1. Empty where unknown.
    Eigen::VectorXd scales;
    std::string where;      // "file:line" of the table's labels, for messages; empty for none
};

// The table's columns must be exactly the model's coordinates, else a sinew::Error at the table's file:line
// lists what is missing or extra. Each quaternion must be unit to within 0.01 (an error names the row) and
// takes, row by row, the sign of q or -q nearer the previous row's, so that its components vary
// continuously.
CoordinateSamples readCoordinateSamples(const Model& model, const StorageTable& table);

// A motion as OpenSim's tools take it: a model coordinate missing from the table is held at its default
// value (InverseDynamicsTool: "coordinate file does not contain coordinate ... Assuming default value";
// AnalyzeTool's SimbodyEngine::formCompleteStorages alike), and a column that is no coordinate is not
// read. Returns the table with exactly the model's coordinates (a default in degrees for a rotational one
// of an inDegrees table), telling `notes` each coordinate held and each column left out.
StorageTable completeCoordinateTable(const Model& model, const StorageTable& table,
                                     const std::function<void(const std::string&)>& notes);

// A motion table's columns processed before the model is known, as preprocessCoordinateSamples would process
// them (the ID tool does this while it reads the model): every column, each converted first by `scale`, the
// factor of a rotational coordinate (pi/180 in an inDegrees table, else 1). Each column's arithmetic is its
// own, so preprocessCoordinateSamples can take from it, bit for bit, the columns of the coordinates that
// have that factor, and process only the others (translations, coordinates missing from the table).
struct ProcessedMotionTable {
    std::vector<std::string> columns;  // the table's
    Eigen::VectorXd times;             // the table's rows
    double lowpassCutoffHz = -1, startTime = 0, finalTime = 0;  // as asked
    double scale = 1;
    Eigen::MatrixXd values;            // the table's values times `scale`
    CoordinateTrajectory trajectory;   // one column per table column
};
ProcessedMotionTable preprocessMotionTable(const StorageTable& table, double lowpassCutoffHz, double startTime,
                                           double finalTime);

// q, q̇, q̈ from the samples as OpenSim's tools derive them (coordinate_preprocessing.hpp): cutoff in Hz
// (negative: no filtering), the time range in s; errors name the table's file, the row and the model's
// coordinates. The frames never reach beyond the samples' own times: the padding filtering adds is not a
// result (OpenSim 4.4 reports the motion's or the setup's range). With ball or free joints, each
// quaternion's four components are splined like any coordinate, then the result's q holds the unit
// quaternions and its qdot and qddot the speeds u and u̇ (nu columns, calcSpeedsFromCoordinateRates);
// without, q̇ = u.
// `processed`, when given, is the samples' table processed beforehand (preprocessMotionTable): it is used
// where it holds what the samples need (the same times, cutoff and time range; a column of the same numbers),
// and the result is the same.
CoordinateTrajectory preprocessCoordinateSamples(const Model& model, const CoordinateSamples& samples,
                                                 double lowpassCutoffHz, double startTime, double finalTime,
                                                 const ProcessedMotionTable* processed = nullptr);

}  // namespace sinew

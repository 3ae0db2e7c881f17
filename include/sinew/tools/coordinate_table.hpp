#pragma once
// A motion table (.mot/.sto: IK results, simulation states) read onto a model's coordinates: columns
// matched by name, rotational coordinates of an inDegrees table converted to radians.
#include <Eigen/Core>
#include <string>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/model.hpp"
#include "sinew/io/storage_file.hpp"

namespace sinew {

struct CoordinateSamples {
    Eigen::VectorXd times;  // (rows) s
    Eigen::MatrixXd q;      // (rows x nq) rad or m, in the model's q order
    std::string where;      // "file:line" of the table's labels, for messages; empty for none
};

// The model's coordinates must all be scalar (custom, pin and weld joints: q = u); the table's columns must
// be exactly the model's coordinates, else a sinew::Error at the table's file:line lists what is missing
// or extra.
CoordinateSamples readCoordinateSamples(const Model& model, const StorageTable& table);

// q, q̇, q̈ from the samples as OpenSim's tools derive them (coordinate_preprocessing.hpp): cutoff in Hz
// (negative: no filtering), the time range in s; errors name the table's file, the row and the model's
// coordinates. The frames never reach beyond the samples' own times: the padding filtering adds is not a
// result (OpenSim 4.4 reports the motion's or the setup's range).
CoordinateTrajectory preprocessCoordinateSamples(const Model& model, const CoordinateSamples& samples,
                                                 double lowpassCutoffHz, double startTime, double finalTime);

}  // namespace sinew

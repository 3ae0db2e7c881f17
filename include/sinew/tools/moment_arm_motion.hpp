#pragma once
// OpenSim's MuscleAnalysis lengths and moment arms over a motion (or at the default pose): per row, the
// coordinates made to follow their couplers (as OpenSim's AnalyzeTool assembles each frame), the wire paths
// and r = -dL/dq (core/moment_arms.hpp), written as OpenSim names its files.
#include <functional>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tools/coordinate_table.hpp"

namespace sinew {

struct MomentArmMotion {
    StorageTable lengths;                 // m, one column per wire
    std::vector<StorageTable> momentArms;  // per speed (getSpeedNames), m or m/m, one column per wire
    std::vector<bool> crossed;            // per speed: some wire's moment arm about it is non-zero
};

// Every row of `samples`; `where` names the input in errors ("FILE: row 3 (t = ...)", or the model's file
// at the default pose when samples are the default pose: rowLabels false). Throws sinew::Error naming the
// row and the wire whose length or moment arm is not finite.
MomentArmMotion calcMomentArmMotion(const Model& model, const CoordinateSamples& samples, const std::string& where,
                                    bool rowLabels, const std::function<void(int frame, int frames)>& onFrame = {});

// <model>_Length.sto and <model>_MomentArm_<coordinate>.sto for each coordinate some wire crosses, in one
// set (an earlier run's file for a coordinate no longer crossed is removed); returns the files written.
int writeMomentArmFiles(const Model& model, MomentArmMotion& motion, const std::string& outputDirectory);

}  // namespace sinew

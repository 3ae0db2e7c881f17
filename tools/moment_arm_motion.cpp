#include "sinew/tools/moment_arm_motion.hpp"

#include <cmath>
#include <filesystem>

#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/moment_arms.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/tools/motion_frames.hpp"

namespace sinew {
namespace {

// Named here, at the input row, rather than later as a cell of the output file.
void checkFinite(const Model& model, const Data& data, const Eigen::MatrixXd& R, const std::string& at) {
    if (data.wireLength.allFinite() && R.allFinite()) return;
    for (int w = 0; w < model.getNumWires(); ++w)
        if (!std::isfinite(data.wireLength[w]) || !R.row(w).allFinite())
            throw Error(at + ": wire '" + model.getWire(w).name +
                        "' has a non-finite length or moment arm (check its points and wrap objects)");
}

}  // namespace

MomentArmMotion calcMomentArmMotion(const Model& model, const CoordinateSamples& samples, const std::string& where,
                                    bool rowLabels, const std::function<void(int frame, int frames)>& onFrame) {
    std::vector<std::string> wireNames;
    for (const Wire& wire : model.getWires()) wireNames.push_back(wire.name);
    const std::size_t numSpeeds = static_cast<std::size_t>(model.getNumU());
    MomentArmMotion motion;
    motion.lengths = StorageTable{model.getName() + " wire lengths (m)", false, wireNames, {}, {}};
    motion.momentArms.assign(numSpeeds, StorageTable{"", false, wireNames, {}, {}});
    motion.crossed.assign(numSpeeds, false);
    CoordinateTrajectory trajectory;
    trajectory.times = samples.times;
    trajectory.q = samples.q;
    Data data(model);
    Eigen::MatrixXd R(model.getNumWires(), model.getNumU());
    Eigen::VectorXd q(model.getNumQ());
    forEachMotionFrame(
        model, trajectory, nullptr,
        [&](const MotionFrame& frame) {
            // As OpenSim's AnalyzeTool, which assembles each frame: dependent coordinates follow their couplers.
            q = frame.q;
            applyCoordinateCouplers(model, q);
            calcPositionKinematics(model, data, q);
            calcWirePaths(model, data);
            calcMomentArms(model, data, R);
            checkFinite(model, data, R,
                        rowLabels ? where + ": row " + std::to_string(frame.index + 1) + " (t = " +
                                        std::to_string(frame.time) + " s)"
                                  : where + ": at the default pose");
            motion.lengths.times.push_back(frame.time);
            motion.lengths.rows.emplace_back(data.wireLength.data(), data.wireLength.data() + data.wireLength.size());
            for (std::size_t c = 0; c < numSpeeds; ++c) {
                const auto column = R.col(static_cast<Eigen::Index>(c));
                motion.crossed[c] = motion.crossed[c] || column.cwiseAbs().maxCoeff() > 0;
                motion.momentArms[c].times.push_back(frame.time);
                motion.momentArms[c].rows.emplace_back(column.data(), column.data() + column.size());
            }
        },
        onFrame);
    return motion;
}

int writeMomentArmFiles(const Model& model, MomentArmMotion& motion, const std::string& outputDirectory) {
    std::filesystem::create_directories(outputDirectory);
    const std::filesystem::path dir(outputDirectory);
    const std::vector<std::string> speedNames = getSpeedNames(model);
    OutputFileSet outputs;
    writeStorageFile(motion.lengths, outputs, (dir / (model.getName() + "_Length.sto")).string());
    int files = 1;
    for (std::size_t c = 0; c < speedNames.size(); ++c) {
        const std::string path = (dir / (model.getName() + "_MomentArm_" + speedNames[c] + ".sto")).string();
        if (!motion.crossed[c]) {
            outputs.retire(path);  // an earlier run's file for a coordinate this motion's wires no longer cross
            continue;
        }
        motion.momentArms[c].name = model.getName() + " moment arms about " + speedNames[c] + " (m or m/m)";
        writeStorageFile(motion.momentArms[c], outputs, path);
        ++files;
    }
    outputs.commit();
    return files;
}

}  // namespace sinew

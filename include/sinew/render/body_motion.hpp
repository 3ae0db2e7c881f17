#pragma once
// The instants a picture or viewer shows: a motion's rows (coordinates by name) with the wires' tensions,
// either read from a tensions table or from the wires' force laws at each row, made into BodyFrames.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/render/body_scene.hpp"

namespace sinew {

// A motion on the model's q: rows x nq, q order.
struct PoseTable {
    std::string file;       // where it was read, for messages
    Eigen::VectorXd times;  // s (rows)
    Eigen::MatrixXd q;      // rad or m, quaternions for ball and free joints (rows x nq)
};

// Columns matched by name: a model of scalar coordinates reads a .mot/.sto as the tools do
// (readCoordinateSamples: exactly the model's coordinates, degrees converted); a model with ball or free
// joints reads its own coordinates file (`sinew simulate`'s, columns getCoordinateNames), which must not be
// in degrees. Errors name the file and the columns.
PoseTable readPoseTable(const Model& model, const std::string& path);

// Wire tensions per row (rows x numWires, N), columns exactly the model's wire names.
struct TensionTable {
    std::string file;
    Eigen::VectorXd times;     // s (rows)
    Eigen::MatrixXd tensions;  // N (rows x numWires), finite and >= 0
};
TensionTable readTensionTable(const Model& model, const std::string& path);

// Which rows to show, of a table of `times` read from `file`: row `frame` (from 0), the row nearest `time`,
// or `count` rows evenly from the first to the last. Errors name the file, the frame or time asked for and
// the range there is.
int findFrame(const Eigen::VectorXd& times, int frame, const std::string& file);
int findFrameAtTime(const Eigen::VectorXd& times, double time, const std::string& file);
std::vector<int> selectStripFrames(const Eigen::VectorXd& times, int count, const std::string& file);

// The frames at the given rows. With a motion, `rows` index it; the tensions (when given) are then those of
// the tensions table's row at the same time (an error naming both files where there is none). With tensions
// only, `rows` index the tensions table and the body stays at the default pose. Without tensions, each
// wire's force law gives them at the row's lengths, with lengthening speeds by central differences of the
// lengths over the neighbouring rows (0 with a single row). Without a motion the pose is the model's
// default, its virtual links put in equilibrium. `motion` and `tensions` may be null.
std::vector<BodyFrame> calcBodyFrames(const Model& model, const PoseTable* motion, const TensionTable* tensions,
                                      const std::vector<int>& rows);

}  // namespace sinew

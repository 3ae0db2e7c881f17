#pragma once
// OpenSim's InverseKinematicsTool on sinew's solver (inverse_kinematics.hpp): a marker capture (.trc) fitted
// frame by frame, with the setup's marker and coordinate tasks, written as OpenSim writes its results (the
// coordinates .mot in degrees, and the marker errors). docs/inverse-kinematics.md.
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "sinew/core/marker.hpp"
#include "sinew/core/model.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/io/trc_file.hpp"
#include "sinew/tools/inverse_kinematics.hpp"

namespace sinew {

struct InverseKinematicsResult {
    std::vector<double> times;  // s, the capture's frames inside the time range
    InverseKinematicsMotion motion;
    std::vector<std::string> markers;  // the marker tasks' markers, in task order
    std::vector<double> markerWeights;
};

// What to fit: the setup's applied tasks with a weight > 0, or with no marker task at all, every model
// marker the capture has, at weight 1. Tasks naming a marker the model or the capture lacks are left out
// with a note (OpenSim warns the same way); coordinate tasks take their targets from the model's default,
// the task's value (rad or m) or the setup's coordinate file, interpolated at each frame's time.
struct InverseKinematicsRequest {
    std::vector<InverseKinematicsTaskSetup> markerTasks, coordinateTasks;
    std::string coordinateFile;  // for coordinate tasks from_file
    double startTime = -std::numeric_limits<double>::infinity();  // s
    double endTime = std::numeric_limits<double>::infinity();
    double accuracy = 1e-5;
    // Segment frames to follow as well (a BVH capture's, bvh_targets.hpp), with their targets per capture
    // frame (R_GF, ground axes, in task order); none for a TRC capture.
    std::vector<OrientationTask> orientationTasks = {};
    std::vector<std::vector<Eigen::Matrix3d>> orientations = {};
};

// The setup's tasks, coordinate file, time range and accuracy.
InverseKinematicsRequest makeInverseKinematicsRequest(const InverseKinematicsSetup& setup);

// Throws sinew::Error naming the capture when no frame lies in the time range or no marker can be fitted.
InverseKinematicsResult runInverseKinematics(const Model& model, const std::vector<Marker>& markers,
                                             const MarkerTable& capture, const InverseKinematicsRequest& request,
                                             const std::function<void(const std::string&)>& notes,
                                             const std::function<void(int frame, int frames)>& onFrame = {});

// q with the model's free root turned and moved so that the markers best match the first frame's targets
// in a least-squares rigid fit (Kabsch): a start from which inverse kinematics does not have to find the
// capture's heading. q unchanged when the root is not a free joint on ground or fewer than 3 markers are seen.
Eigen::VectorXd alignFreeRoot(const Model& model, const std::vector<Marker>& markers, const Eigen::Matrix3Xd& targets,
                              const Eigen::VectorXd& q);

// The coordinates as OpenSim's IK writes them: every coordinate in q order, rotational ones in degrees.
StorageTable makeInverseKinematicsTable(const Model& model, const InverseKinematicsResult& result);
// Per frame: total_squared_error (weighted, m^2), marker_error_RMS and marker_error_max (m), as OpenSim's
// _ik_marker_errors.sto, plus the markers seen, the iterations and whether the solve converged.
StorageTable makeMarkerErrorTable(const InverseKinematicsResult& result);

// What a fitted motion's frames add up to, as `sinew ik` prints it.
struct InverseKinematicsSummary {
    int frames = 0;
    double medianRmsError = 0, largestRmsError = 0;  // m, of the per-frame RMS marker (or joint-centre) errors
    double largestError = 0;                          // m, of any one marker in any frame
    double medianIterations = 0, largestIterations = 0;
    int unconverged = 0;                              // frames that ended on a budget, not converged
};
// Throws sinew::Error for a result without frames.
InverseKinematicsSummary summarizeInverseKinematics(const InverseKinematicsResult& result);

// Both files of one run, renamed into place together (io/atomic_file.hpp); without writeErrors an errors
// file of an earlier run at errorsPath is removed, so that it is not taken for this run's. decimals >= 0
// writes the coordinates with that many digits after the point (StorageTable::decimals).
void writeInverseKinematicsFiles(const Model& model, const InverseKinematicsResult& result, const std::string& motionPath,
                                 const std::string& errorsPath, bool writeErrors = true, int decimals = -1);

// The setup as `opensim-cmd run-tool` runs it: its model (its MarkerSet), capture, tasks and time range;
// writes the .mot (and <name>_ik_marker_errors.sto when report_errors) into outputDir, or the setup's
// results_directory when empty. Returns the .mot's path.
std::string runInverseKinematicsTool(const InverseKinematicsSetup& setup, const std::string& outputDir,
                                     const std::function<void(const std::string&)>& notes,
                                     const std::function<void(int frame, int frames)>& onFrame = {});

}  // namespace sinew

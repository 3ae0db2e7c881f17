#include "sinew/tools/inverse_kinematics_tool.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/io/model_loading.hpp"

namespace sinew {
namespace {

constexpr double kDegrees = 180 / M_PI;
constexpr double kTimeTolerance = 1e-9;  // s: a frame at the range's end, written with rounding, is in it
constexpr double kLeadingOrientationWeight = 1;  // m^2/rad^2, the first frame's coarse solve
constexpr double kCoarseAccuracy = 1e-3;         // m (rad) of target motion in its last step
constexpr int kFirstFrameIterations = 2000;

int findMarker(const std::vector<Marker>& markers, const std::string& name) {
    for (std::size_t m = 0; m < markers.size(); ++m)
        if (markers[m].name == name) return static_cast<int>(m);
    return -1;
}

// A coordinate task's target at each frame time.
struct CoordinateTarget {
    std::vector<double> times, values;  // from the coordinate file; empty: the constant `value`
    double value = 0;

    double at(double t) const {
        if (times.empty()) return value;
        if (t <= times.front()) return values.front();
        if (t >= times.back()) return values.back();
        const std::size_t k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
        const double s = (t - times[k - 1]) / (times[k] - times[k - 1]);
        return values[k - 1] + s * (values[k] - values[k - 1]);
    }
};

CoordinateTarget makeCoordinateTarget(const Model& model, const InverseKinematicsTaskSetup& task,
                                      const std::string& coordinateFile, const StorageTable* file) {
    const int q = model.findCoordinateIndex(task.name);
    const Coordinate& c = model.getCoordinates()[static_cast<std::size_t>(q)];
    CoordinateTarget target;
    if (task.valueType == "default_value") {
        target.value = c.defaultValue;
    } else if (task.valueType == "manual_value") {
        target.value = task.value;
    } else {
        if (!file) throw Error(task.where + ": coordinate task '" + task.name + "' takes its value from_file, but the "
                                            "setup names no coordinate_file");
        const int column = matchStorageColumns(*file, {task.name}, ExtraColumns::Allow)[0];
        const double scale = file->inDegrees && c.motionType == MotionType::Rotational ? 1 / kDegrees : 1;
        target.times = file->times;
        for (const std::vector<double>& row : file->rows) target.values.push_back(scale * row[static_cast<std::size_t>(column)]);
        if (target.times.empty()) throw Error(coordinateFile + ": no rows for coordinate task '" + task.name + "'");
    }
    return target;
}

// Coarse to fine for the first frame, which starts far from the capture: the segment frames first, at the
// weight of a joint centre per radian (each mapped link's rotation then follows its own target, nearly
// independently of the others), from which the requested weights converge to the fit rather than to one of
// the local minima that centres alone leave between a default pose and a capture's.
Eigen::VectorXd startFromOrientations(const Model& model, const std::vector<Marker>& markers,
                                      const std::vector<MarkerTask>& markerTasks, const InverseKinematicsRequest& request,
                                      const InverseKinematicsTargets& first, Eigen::VectorXd q) {
    std::vector<OrientationTask> leading = request.orientationTasks;
    for (OrientationTask& task : leading) task.weight = kLeadingOrientationWeight;
    InverseKinematicsOptions options;
    options.accuracy = kCoarseAccuracy;
    InverseKinematicsSolver(model, markers, markerTasks, {}, options, leading).solve({first.markers, Eigen::VectorXd(), first.orientations}, q);
    return q;
}

}  // namespace

InverseKinematicsResult runInverseKinematics(const Model& model, const std::vector<Marker>& markers,
                                             const MarkerTable& capture, const InverseKinematicsRequest& request,
                                             const std::function<void(const std::string&)>& notes,
                                             const std::function<void(int frame, int frames)>& onFrame) {
    auto note = [&](const std::string& line) {
        if (notes) notes(line);
    };
    std::vector<InverseKinematicsTaskSetup> wanted = request.markerTasks;
    if (wanted.empty())
        for (const Marker& m : markers) wanted.push_back({m.name, true, 1, "default_value", 0, ""});
    InverseKinematicsResult result;
    std::vector<MarkerTask> markerTasks;
    std::vector<Marker> taskMarkers;
    std::vector<int> captureColumn;
    for (const InverseKinematicsTaskSetup& task : wanted) {
        if (!task.apply || task.weight == 0) continue;
        const auto column = std::find(capture.markers.begin(), capture.markers.end(), task.name);
        if (findMarker(markers, task.name) < 0) {
            note("marker task '" + task.name + "'" + (task.where.empty() ? "" : " (" + task.where + ")") +
                 ": the model has no such marker; left out");
        } else if (column == capture.markers.end()) {
            if (!request.markerTasks.empty())
                note("marker task '" + task.name + "': " + capture.source + " has no such marker; left out");
        } else {
            markerTasks.push_back({task.name, task.weight});
            taskMarkers.push_back(markers[static_cast<std::size_t>(findMarker(markers, task.name))]);
            captureColumn.push_back(static_cast<int>(column - capture.markers.begin()));
            result.markers.push_back(task.name);
            result.markerWeights.push_back(task.weight);
        }
    }
    if (markerTasks.empty())
        throw Error(capture.source + ": none of its markers is a marker task on model '" + model.getName() + "'");
    std::optional<StorageTable> coordinateFile;
    if (!request.coordinateFile.empty()) coordinateFile = readStorageFile(request.coordinateFile);
    std::vector<CoordinateTask> coordinateTasks;
    std::vector<CoordinateTarget> coordinateTargets;
    for (const InverseKinematicsTaskSetup& task : request.coordinateTasks) {
        if (!task.apply || task.weight == 0) continue;
        if (model.findCoordinateIndex(task.name) == Model::kNotFound) {
            note("coordinate task '" + task.name + "' (" + task.where + "): the model has no such coordinate; left out");
            continue;
        }
        coordinateTasks.push_back({task.name, task.weight});
        coordinateTargets.push_back(makeCoordinateTarget(model, task, request.coordinateFile,
                                                          coordinateFile ? &*coordinateFile : nullptr));
    }
    std::vector<InverseKinematicsTargets> targets;
    for (std::size_t k = 0; k < capture.times.size(); ++k) {
        const double t = capture.times[k];
        if (t < request.startTime - kTimeTolerance || t > request.endTime + kTimeTolerance) continue;
        InverseKinematicsTargets frame;
        frame.markers.resize(3, static_cast<Eigen::Index>(markerTasks.size()));
        for (std::size_t m = 0; m < markerTasks.size(); ++m)
            frame.markers.col(static_cast<Eigen::Index>(m)) = capture.positions[k].col(captureColumn[m]);
        frame.coordinates.resize(static_cast<Eigen::Index>(coordinateTasks.size()));
        for (std::size_t c = 0; c < coordinateTasks.size(); ++c)
            frame.coordinates[static_cast<Eigen::Index>(c)] = coordinateTargets[c].at(t);
        if (!request.orientationTasks.empty()) frame.orientations = request.orientations.at(k);
        targets.push_back(std::move(frame));
        result.times.push_back(t);
    }
    if (targets.empty())
        throw Error(capture.source + ": no frame between " + std::to_string(request.startTime) + " and " +
                    std::to_string(request.endTime) + " s");
    InverseKinematicsOptions options;
    options.accuracy = request.accuracy;
    InverseKinematicsSolver solver(model, markers, markerTasks, coordinateTasks, options, request.orientationTasks);
    Eigen::VectorXd start = alignFreeRoot(model, taskMarkers, targets.front().markers, model.getDefaultQ());
    if (!request.orientationTasks.empty()) start = startFromOrientations(model, markers, markerTasks, request, targets.front(), start);
    // The first frame, from far, converges with more iterations than a warm frame needs.
    InverseKinematicsOptions first = options;
    first.maxIterations = kFirstFrameIterations;
    InverseKinematicsSolver(model, markers, markerTasks, coordinateTasks, first, request.orientationTasks).solve(targets.front(), start);
    result.motion = solveInverseKinematics(solver, start, targets, onFrame);
    return result;
}

Eigen::VectorXd alignFreeRoot(const Model& model, const std::vector<Marker>& markers, const Eigen::Matrix3Xd& targets,
                              const Eigen::VectorXd& q) {
    if (model.getNumLinks() == 0 || model.getJoint(0).type != JointType::Free || model.getJoint(0).parent != kGround) return q;
    Data data(model);
    calcPositionKinematics(model, data, q);
    std::vector<Eigen::Vector3d> from, to;
    for (std::size_t m = 0; m < markers.size(); ++m)
        if (targets.col(static_cast<Eigen::Index>(m)).allFinite()) {
            from.push_back(calcMarkerLocation_G(data, markers[m]));
            to.push_back(targets.col(static_cast<Eigen::Index>(m)));
        }
    if (from.size() < 3) return q;
    Eigen::Matrix3Xd a(3, static_cast<Eigen::Index>(from.size())), b(3, static_cast<Eigen::Index>(to.size()));
    for (std::size_t k = 0; k < from.size(); ++k) {
        a.col(static_cast<Eigen::Index>(k)) = from[k];
        b.col(static_cast<Eigen::Index>(k)) = to[k];
    }
    // Eigen's umeyama: the rigid transform (no scaling) taking a onto b in the least-squares sense.
    const Eigen::Matrix4d T = Eigen::umeyama(a, b, false);
    const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
    const Joint& root = model.getJoint(0);
    const Eigen::Matrix3d R_GB = R * data.R_GB[0];
    const Eigen::Vector3d p_GB = R * data.p_GB[0] + T.topRightCorner<3, 1>();
    // p_GB = p_PF + R_PF p_FM - R_GB p_BM and R_GB = R_PF R_FM R_BM^T, with the parent ground.
    const Eigen::Matrix3d R_FM = root.R_PF.transpose() * R_GB * root.R_BM;
    const Eigen::Vector3d p_FM = root.R_PF.transpose() * (p_GB + R_GB * root.p_BM - root.p_PF);
    Eigen::VectorXd aligned = q;
    const Eigen::Quaterniond quaternion(R_FM);
    aligned.segment<4>(root.qStart) << quaternion.w(), quaternion.x(), quaternion.y(), quaternion.z();
    aligned.segment<3>(root.qStart + 4) = p_FM;
    return aligned;
}

StorageTable makeInverseKinematicsTable(const Model& model, const InverseKinematicsResult& result) {
    StorageTable table;
    table.name = "Coordinates";
    table.inDegrees = true;
    table.columns = getCoordinateNames(model);
    table.times = result.times;
    for (const Eigen::VectorXd& q : result.motion.q) {
        std::vector<double> row(static_cast<std::size_t>(q.size()));
        for (Eigen::Index i = 0; i < q.size(); ++i) {
            const Coordinate& c = model.getCoordinates()[static_cast<std::size_t>(i)];
            const Joint& joint = model.getJoint(c.joint);
            // Quaternion entries are no angles; OpenSim's own models have none.
            const bool angle = c.motionType == MotionType::Rotational && joint.nq == joint.nu;
            row[static_cast<std::size_t>(i)] = angle ? kDegrees * q[i] : q[i];
        }
        table.rows.push_back(std::move(row));
    }
    return table;
}

InverseKinematicsSummary summarizeInverseKinematics(const InverseKinematicsResult& result) {
    const std::vector<InverseKinematicsReport>& reports = result.motion.reports;
    if (reports.empty()) throw Error("inverse kinematics: no frames to summarize");
    std::vector<double> rms, iterations;
    InverseKinematicsSummary summary;
    for (const InverseKinematicsReport& report : reports) {
        rms.push_back(report.rmsMarkerError);
        iterations.push_back(report.iterations);
        summary.largestError = std::max(summary.largestError, report.maxMarkerError);
        summary.unconverged += report.converged ? 0 : 1;
    }
    const auto median = [](std::vector<double>& values) {
        std::sort(values.begin(), values.end());
        return values[values.size() / 2];
    };
    summary.frames = static_cast<int>(reports.size());
    summary.medianRmsError = median(rms);
    summary.largestRmsError = rms.back();
    summary.medianIterations = median(iterations);
    summary.largestIterations = iterations.back();
    return summary;
}

StorageTable makeMarkerErrorTable(const InverseKinematicsResult& result) {
    StorageTable table;
    table.name = "Model Marker Errors from IK";
    table.columns = {"total_squared_error", "marker_error_RMS", "marker_error_max", "markers_seen", "iterations",
                     "converged"};
    // A BVH fit's segment frames: their errors (rad) after OpenSim's columns.
    const bool withOrientations = std::any_of(result.motion.reports.begin(), result.motion.reports.end(),
                                              [](const InverseKinematicsReport& r) { return r.orientationsSeen > 0; });
    if (withOrientations) {
        table.columns.push_back("orientation_error_RMS");
        table.columns.push_back("orientation_error_max");
    }
    table.times = result.times;
    for (const InverseKinematicsReport& report : result.motion.reports) {
        double total = 0;
        for (Eigen::Index m = 0; m < report.markerErrors.size(); ++m)
            if (!std::isnan(report.markerErrors[m]))
                total += result.markerWeights[static_cast<std::size_t>(m)] * report.markerErrors[m] * report.markerErrors[m];
        table.rows.push_back({total, report.rmsMarkerError, report.maxMarkerError, static_cast<double>(report.markersSeen),
                              static_cast<double>(report.iterations), report.converged ? 1.0 : 0.0});
        if (withOrientations) {
            table.rows.back().push_back(report.rmsOrientationError);
            table.rows.back().push_back(report.maxOrientationError);
        }
    }
    return table;
}

InverseKinematicsRequest makeInverseKinematicsRequest(const InverseKinematicsSetup& setup) {
    InverseKinematicsRequest request;
    request.markerTasks = setup.markerTasks;
    request.coordinateTasks = setup.coordinateTasks;
    request.coordinateFile = setup.coordinateFile;
    request.startTime = setup.startTime;
    request.endTime = setup.endTime;
    request.accuracy = setup.accuracy;
    return request;
}

std::string runInverseKinematicsTool(const InverseKinematicsSetup& setup, const std::string& outputDir,
                                     const std::function<void(const std::string&)>& notes,
                                     const std::function<void(int frame, int frames)>& onFrame) {
    const Model model = loadModel(setup.modelFile, notes);
    const std::vector<Marker> markers = loadMarkers(setup.modelFile, model);
    if (notes && std::isfinite(setup.constraintWeight))
        notes("constraint_weight " + std::to_string(setup.constraintWeight) +
              " is not used: sinew's IK holds loops and couplers exactly (OpenSim's Inf)");
    const InverseKinematicsRequest request = makeInverseKinematicsRequest(setup);
    if (request.markerTasks.empty()) throw Error(setup.file + ": the IKTaskSet has no IKMarkerTask");
    const InverseKinematicsResult result =
        runInverseKinematics(model, markers, readTrcFile(setup.markerFile), request, notes, onFrame);
    const std::filesystem::path directory = outputDir.empty() ? setup.resultsDirectory : outputDir;
    std::filesystem::create_directories(directory);
    const std::string path = (directory / setup.outputMotionFile).string();
    // OpenSim names the errors file after the tool; an unnamed setup's after its motion file.
    const std::string stem = setup.name.empty() ? std::filesystem::path(setup.outputMotionFile).stem().string() : setup.name;
    writeInverseKinematicsFiles(model, result, path, (directory / (stem + "_ik_marker_errors.sto")).string(),
                                setup.reportErrors);
    return path;
}

void writeInverseKinematicsFiles(const Model& model, const InverseKinematicsResult& result, const std::string& motionPath,
                                 const std::string& errorsPath, bool writeErrors, int decimals) {
    OutputFileSet files;
    StorageTable coordinates = makeInverseKinematicsTable(model, result);
    coordinates.decimals = decimals;
    writeStorageFile(coordinates, files, motionPath);
    if (writeErrors) writeStorageFile(makeMarkerErrorTable(result), files, errorsPath);
    else files.retire(errorsPath);
    files.commit();
}

}  // namespace sinew

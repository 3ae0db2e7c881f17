#include "sinew/tools/tension_motion.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/coordinate_rates.hpp"
#include "sinew/core/error.hpp"
#include "sinew/signal/smoothing_spline.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/joint_load_table.hpp"
#include "sinew/tools/measured_loads.hpp"
#include "sinew/tools/motion_contacts.hpp"
#include "sinew/tools/motion_frames.hpp"

namespace sinew {
namespace {

// OpenSim's AnalyzeTool stores q and the q splines' derivative u at every processed row; its
// StaticOptimization fits GCVSplineSet(5, states) through those and takes the u splines' derivative as
// the target accelerations (StaticOptimizationTarget::computeConstraintVector).
std::vector<SmoothingSpline> fitSpeedSplines(const CoordinateTrajectory& trajectory) {
    const Eigen::VectorXd& times = trajectory.processedTimes;
    Eigen::MatrixXd speeds(times.size(), static_cast<Eigen::Index>(trajectory.splines.size()));
    for (Eigen::Index c = 0; c < speeds.cols(); ++c)
        for (Eigen::Index r = 0; r < times.size(); ++r)
            speeds(r, c) = trajectory.splines[static_cast<std::size_t>(c)].calcDerivative(times[r], 1);
    return SmoothingSpline::interpolateColumns(5, times, speeds);
}

// The rows whose coordinates are all finite; `missing` gets the indices of the others within
// [startTime, finalTime].
CoordinateSamples keepFiniteRows(const CoordinateSamples& samples, const TensionMotionOptions& options,
                                 std::vector<int>& missing) {
    std::vector<Eigen::Index> kept;
    for (Eigen::Index r = 0; r < samples.times.size(); ++r) {
        if (samples.q.row(r).allFinite())
            kept.push_back(r);
        else if (samples.times[r] >= options.startTime && samples.times[r] <= options.finalTime)
            missing.push_back(static_cast<int>(r));
    }
    if (kept.size() == static_cast<std::size_t>(samples.times.size())) return samples;
    CoordinateSamples finite;
    finite.times = samples.times(kept);
    finite.q = samples.q(kept, Eigen::all);
    finite.where = samples.where;
    return finite;
}

StorageTable makeTable(const std::string& name, const std::vector<std::string>& columns) {
    StorageTable table;
    table.name = name;
    table.columns = columns;
    return table;
}

void append(StorageTable& table, double t, const Eigen::VectorXd& values) {
    table.times.push_back(t);
    table.rows.emplace_back(values.data(), values.data() + values.size());
}

// The result's tables, a row per frame.
class TensionTables {
public:
    TensionTables(const Model& model, const TensionMotionOptions& options, bool staticOptimization,
                  TensionMotionResult& result)
        : model_(model), options_(options), staticOptimization_(staticOptimization), result_(result) {
        std::vector<std::string> wireNames;
        reportColumns_ = {"status", "Z", "active_wires", "iterations", "ipopt", "unactuated_residual"};
        for (const Wire& wire : model.getWires()) wireNames.push_back(wire.name);
        // Per DOF (speed): a ball joint j's j_wx_residual.., a scalar coordinate's own name.
        const std::vector<std::string> dofNames = getSpeedNames(model);
        for (const std::string& dof : dofNames) reportColumns_.push_back(dof + "_residual");
        for (const std::string& dof : dofNames) reportColumns_.push_back(dof + "_reserve");
        result.tensions = makeTable("Wire tensions (" + options.analysis.method + ")", wireNames);
        result.report = makeTable("Tension report", reportColumns_);
        std::vector<std::string> ligamentNames;
        for (int w = 0; w < model.getNumWires(); ++w) {
            const Wire& wire = model.getWire(w);
            if (wire.kind != WireKind::Ligament || !wire.crossSection) continue;
            ligaments_.push_back(w);
            ligamentNames.push_back(wire.name);
        }
        if (!ligaments_.empty()) result.ligamentStress = makeTable("Ligament stress (Pa)", ligamentNames);
        if (!staticOptimization) return;
        result.activations = makeTable("Static Optimization", wireNames);
        std::vector<std::string> reserveNames;
        for (const ReserveActuator& reserve : options.analysis.reserves) reserveNames.push_back(reserve.name);
        result.reserves = makeTable("Reserve actuator forces", reserveNames);
    }

    // A frame without input: zeros everywhere but its status, so that no table holds NaN.
    void appendMissing(double t) {
        append(result_.tensions, t, Eigen::VectorXd::Zero(model_.getNumWires()));
        if (staticOptimization_) {
            append(result_.activations, t, Eigen::VectorXd::Zero(model_.getNumWires()));
            append(result_.reserves, t, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(options_.analysis.reserves.size())));
        }
        Eigen::VectorXd row = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(reportColumns_.size()));
        row[0] = kMissingInputStatus;
        append(result_.report, t, row);
        if (!ligaments_.empty())
            append(result_.ligamentStress, t, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(ligaments_.size())));
    }

    void appendFrame(double t, const TensionFrame& frame) {
        result_.infeasibleFrames += frame.status == DistributionStatus::Infeasible;
        result_.ipoptFrames += frame.usedIpopt;
        result_.failedFrames += frame.status == DistributionStatus::Failed;
        append(result_.tensions, t, frame.tension);
        if (staticOptimization_) {
            append(result_.activations, t, frame.activation);
            append(result_.reserves, t, frame.reserveForce);
        }
        std::vector<double> row = {static_cast<double>(frame.status), frame.torqueError,
                                   static_cast<double>(frame.activeWires), static_cast<double>(frame.iterations),
                                   frame.usedIpopt ? 1.0 : 0.0, frame.unactuatedResidual};
        row.insert(row.end(), frame.residual.data(), frame.residual.data() + frame.residual.size());
        row.insert(row.end(), frame.reserve.data(), frame.reserve.data() + frame.reserve.size());
        result_.report.times.push_back(t);
        result_.report.rows.push_back(std::move(row));
        if (ligaments_.empty()) return;
        std::vector<double> stress;
        for (const int w : ligaments_) stress.push_back(frame.tension[w] / *model_.getWire(w).crossSection);
        result_.ligamentStress.times.push_back(t);
        result_.ligamentStress.rows.push_back(std::move(stress));
    }

private:
    const Model& model_;
    const TensionMotionOptions& options_;
    bool staticOptimization_;
    TensionMotionResult& result_;
    std::vector<std::string> reportColumns_;
    std::vector<int> ligaments_;  // the wires of ligamentStress's columns
};

// One frame's tensions; errors name the frame.
const TensionFrame& solveFrame(TensionAnalysis& analysis, const MotionFrame& motion) {
    const std::string at =
        "tensions at t = " + std::to_string(motion.time) + " s (frame " + std::to_string(motion.index + 1) + ")";
    const TensionFrame* solved = nullptr;
    try {
        solved = &analysis.calcFrame(motion.q, motion.u, motion.udot, motion.appliedLinkForces);
    } catch (const Error& e) {
        throw Error(at + ": " + e.what());
    }
    if (!solved->tau.allFinite()) {
        Eigen::Index k = 0;
        while (std::isfinite(solved->tau[k])) ++k;
        throw Error(at + ": the generalized force of '" + getSpeedNames(analysis.getModel())[static_cast<std::size_t>(k)] +
                    "' from inverse dynamics is not finite (check the motion and external loads there)");
    }
    return *solved;
}

bool isRecorded(const CoordinateTrajectory& trajectory, int frame, int stepInterval) {
    const Eigen::Index last = trajectory.times.size() - 1;
    return frame == 0 || frame == last || (trajectory.firstRow + frame) % stepInterval == 0;
}

// Every frame of `trajectory` (q, qdot as u, qddot as udot), with the rows of `sampleTimes` listed in
// `missingRows` flagged in between.
TensionMotionResult analyseTrajectory(const Model& model, const CoordinateTrajectory& trajectory,
                                      const Eigen::VectorXd& sampleTimes, std::vector<int> missingRows,
                                      const ExternalLoads* loads, const TensionMotionOptions& options) {
    if (options.stepInterval < 1)
        throw Error("tensions: step interval " + std::to_string(options.stepInterval) + ", expected 1 or more");
    TensionMotionResult result;
    result.missingRows = std::move(missingRows);
    std::optional<MeasuredLoads> measured;
    if (loads) measured.emplace(model, *loads);
    std::optional<MotionContacts> contacts;
    TensionAnalysisOptions analysisOptions = options.analysis;
    if (!loads && options.contact && !model.getContacts().empty()) {
        contacts.emplace(model, trajectory, options.contactDetection, result.contact);
        analysisOptions.columns.push_back(contacts->getColumns());
    }
    TensionAnalysis analysis(model, analysisOptions);
    TensionTables tables(model, options, analysis.solvesActivations(), result);
    JointLoadTable jointLoads(model, contacts ? contacts->getColumns() : nullptr, result.jointLoads);
    const auto appendMissing = [&](double t) {
        tables.appendMissing(t);
        if (contacts) contacts->appendMissing(t);
        jointLoads.appendMissing(t);
    };
    const std::vector<int>& missing = result.missingRows;
    std::size_t nextMissing = 0;
    forEachMotionFrame(
        model, trajectory, measured ? &*measured : nullptr,
        [&](const MotionFrame& motion) {
            for (; nextMissing < missing.size() && sampleTimes[missing[nextMissing]] <= motion.time; ++nextMissing)
                appendMissing(sampleTimes[missing[nextMissing]]);
            // After resampling (--lowpass over a gap) a frame may fall on a missing row's time: it stays flagged.
            if (nextMissing > 0 && sampleTimes[missing[nextMissing - 1]] == motion.time) return;
            if (!isRecorded(trajectory, motion.index, options.stepInterval)) return;
            if (contacts) contacts->prepareFrame(motion.index);
            const auto start = std::chrono::steady_clock::now();
            const TensionFrame& frame = solveFrame(analysis, motion);
            const auto solved = std::chrono::steady_clock::now();
            result.frameSeconds.push_back(std::chrono::duration<double>(solved - start).count());
            jointLoads.appendFrame(motion, analysis, frame);
            result.jointLoadSeconds.push_back(
                std::chrono::duration<double>(std::chrono::steady_clock::now() - solved).count());
            tables.appendFrame(motion.time, frame);
            if (contacts) contacts->appendFrame(motion, analysis, frame);
        },
        options.onFrame);
    for (; nextMissing < missing.size(); ++nextMissing) appendMissing(sampleTimes[missing[nextMissing]]);
    result.flaggedFrames = result.infeasibleFrames + result.failedFrames + static_cast<int>(missing.size());
    return result;
}

}  // namespace

TensionMotionResult runTensionAnalysis(const Model& model, const StorageTable& motion, const ExternalLoads* loads,
                                       const TensionMotionOptions& options) {
    std::vector<int> missingRows;
    const CoordinateSamples allSamples = readCoordinateSamples(model, motion);
    const CoordinateSamples samples = keepFiniteRows(allSamples, options, missingRows);
    CoordinateTrajectory trajectory = preprocessCoordinateSamples(model, samples, options.lowpassCutoffHz,
                                                                  options.startTime, options.finalTime);
    if (options.accelerationsFromSpeedSplines) {
        if (hasQuaternionJoints(model))
            throw Error("tensions: accelerations from speed splines (OpenSim's StaticOptimization) need scalar "
                        "coordinates, and model '" + model.getName() + "' has ball or free joints");
        const std::vector<SmoothingSpline> speedSplines = fitSpeedSplines(trajectory);
        for (Eigen::Index i = 0; i < trajectory.times.size(); ++i)
            for (Eigen::Index j = 0; j < trajectory.qddot.cols(); ++j)
                trajectory.qddot(i, j) = speedSplines[static_cast<std::size_t>(j)].calcDerivative(trajectory.times[i], 1);
    }
    return analyseTrajectory(model, trajectory, allSamples.times, std::move(missingRows), loads, options);
}

TensionMotionResult runTensionAnalysis(const Model& model, const CoordinateTrajectory& states,
                                       const ExternalLoads* loads, const TensionMotionOptions& options) {
    const Eigen::Index frames = states.times.size();
    if (states.q.rows() != frames || states.qdot.rows() != frames || states.qddot.rows() != frames ||
        states.q.cols() != model.getNumQ() || states.qdot.cols() != model.getNumU() ||
        states.qddot.cols() != model.getNumU())
        throw Error("tensions: states of " + std::to_string(frames) + " frames with q " +
                    std::to_string(states.q.rows()) + " x " + std::to_string(states.q.cols()) + ", u " +
                    std::to_string(states.qdot.rows()) + " x " + std::to_string(states.qdot.cols()) + " and udot " +
                    std::to_string(states.qddot.rows()) + " x " + std::to_string(states.qddot.cols()) +
                    " for model '" + model.getName() + "' (nq " + std::to_string(model.getNumQ()) + ", nu " +
                    std::to_string(model.getNumU()) + ")");
    return analyseTrajectory(model, states, states.times, {}, loads, options);
}

namespace {

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

double mean(const std::vector<double>& values) {
    double sum = 0;
    for (double value : values) sum += value;
    return values.empty() ? 0 : sum / static_cast<double>(values.size());
}

std::size_t findColumn(const StorageTable& table, const std::string& name) {
    return static_cast<std::size_t>(matchStorageColumns(table, {name}, ExtraColumns::Allow)[0]);
}

}  // namespace

TensionMotionSummary summarizeTensionMotion(const Model& model, const TensionMotionResult& result) {
    TensionMotionSummary summary;
    summary.frames = static_cast<int>(result.report.times.size());
    const std::size_t status = findColumn(result.report, "status"), z = findColumn(result.report, "Z");
    std::vector<double> zs;
    for (const std::vector<double>& row : result.report.rows)
        if (row[status] != kMissingInputStatus) zs.push_back(row[z]);
    summary.solvedFrames = static_cast<int>(zs.size());
    summary.medianSeconds = median(result.frameSeconds);
    summary.meanSeconds = mean(result.frameSeconds);
    summary.medianJointLoadSeconds = median(result.jointLoadSeconds);
    summary.medianZ = median(zs);
    summary.meanZ = mean(zs);
    summary.maxZ = zs.empty() ? 0 : *std::max_element(zs.begin(), zs.end());
    double mass = 0;
    for (const Link& link : model.getLinks()) mass += link.mass;
    summary.bodyWeight = mass * model.getGravity().norm();
    if (result.contact.columns.empty()) return summary;
    std::vector<std::size_t> flags;
    for (const Contact& contact : model.getContacts()) flags.push_back(findColumn(result.contact, contact.name + "_in_contact"));
    const std::size_t residual = findColumn(result.contact, "root_force_residual");
    std::vector<double> residuals;
    for (const std::vector<double>& row : result.contact.rows)
        if (std::any_of(flags.begin(), flags.end(), [&](std::size_t c) { return row[c] > 0; }))
            residuals.push_back(row[residual]);
    summary.contactFrames = static_cast<int>(residuals.size());
    summary.medianRootResidual = median(residuals);
    summary.maxRootResidual = residuals.empty() ? 0 : *std::max_element(residuals.begin(), residuals.end());
    return summary;
}

int countFramesWithZAtMost(const TensionMotionResult& run, const TensionMotionResult& reference) {
    if (run.report.times != reference.report.times)
        throw Error("tension runs: the two reports are of different frames (" + std::to_string(run.report.times.size()) +
                    " and " + std::to_string(reference.report.times.size()) + " rows)");
    const std::size_t status = findColumn(run.report, "status"), z = findColumn(run.report, "Z");
    const std::size_t referenceStatus = findColumn(reference.report, "status"), referenceZ = findColumn(reference.report, "Z");
    int count = 0;
    for (std::size_t r = 0; r < run.report.rows.size(); ++r) {
        const std::vector<double>& row = run.report.rows[r];
        const std::vector<double>& other = reference.report.rows[r];
        if (row[status] == kMissingInputStatus || other[referenceStatus] == kMissingInputStatus) continue;
        count += row[z] <= other[referenceZ];
    }
    return count;
}

}  // namespace sinew

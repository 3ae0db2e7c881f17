#include "sinew/tools/tension_motion.hpp"

#include <cmath>
#include <optional>
#include <string>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/error.hpp"
#include "sinew/signal/smoothing_spline.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/measured_loads.hpp"

namespace sinew {
namespace {

// OpenSim's AnalyzeTool stores q and the q splines' derivative u at every processed row; its
// StaticOptimization fits GCVSplineSet(5, states) through those and takes the u splines' derivative as
// the target accelerations (StaticOptimizationTarget::computeConstraintVector).
std::vector<SmoothingSpline> fitSpeedSplines(const CoordinateTrajectory& trajectory) {
    std::vector<SmoothingSpline> splines;
    const Eigen::VectorXd& times = trajectory.processedTimes;
    Eigen::VectorXd speeds(times.size());
    for (const SmoothingSpline& coordinate : trajectory.splines) {
        for (Eigen::Index r = 0; r < times.size(); ++r) speeds[r] = coordinate.calcDerivative(times[r], 1);
        splines.push_back(SmoothingSpline::fitFromErrorVariance(5, times, speeds, 0.0));
    }
    return splines;
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

// Every frame of `trajectory` (q, qdot as u, qddot as udot), with the rows of `sampleTimes` listed in
// `missingRows` flagged in between.
TensionMotionResult analyseTrajectory(const Model& model, const CoordinateTrajectory& trajectory,
                                      const Eigen::VectorXd& sampleTimes, std::vector<int> missingRows,
                                      const ExternalLoads* loads, const TensionMotionOptions& options) {
    const std::vector<Coordinate>& coordinates = model.getCoordinates();
    TensionMotionResult result;
    result.missingRows = std::move(missingRows);

    std::optional<MeasuredLoads> measured;
    if (loads) measured.emplace(model, *loads);
    TensionAnalysis analysis(model, options.analysis);
    const bool staticOptimization = options.analysis.method == TensionMethod::StaticOptimization;

    std::vector<std::string> wireNames, reportColumns = {"status", "Z", "active_wires", "iterations", "ipopt",
                                                         "unactuated_residual"};
    for (const Wire& wire : model.getWires()) wireNames.push_back(wire.name);
    for (const Coordinate& c : coordinates) reportColumns.push_back(c.name + "_residual");
    for (const Coordinate& c : coordinates) reportColumns.push_back(c.name + "_reserve");
    result.tensions = makeTable("Wire tensions (" + std::string(toString(options.analysis.method)) + ")", wireNames);
    result.report = makeTable("Tension report", reportColumns);
    if (staticOptimization) {
        result.activations = makeTable("Static Optimization", wireNames);
        std::vector<std::string> reserveNames;
        for (const ReserveActuator& reserve : options.analysis.reserves) reserveNames.push_back(reserve.name);
        result.reserves = makeTable("Reserve actuator forces", reserveNames);
    }

    Data data(model);
    std::vector<SpatialVector> linkForces(static_cast<std::size_t>(model.getNumLinks()));
    const Eigen::Index n = trajectory.q.cols();
    Eigen::VectorXd q(n), u(n), udot(n);
    const auto append = [](StorageTable& table, double t, const Eigen::VectorXd& values) {
        table.times.push_back(t);
        table.rows.emplace_back(values.data(), values.data() + values.size());
    };
    // A frame without input: zeros everywhere but its status, so that no table holds NaN.
    const auto appendMissing = [&](double t) {
        append(result.tensions, t, Eigen::VectorXd::Zero(model.getNumWires()));
        if (staticOptimization) {
            append(result.activations, t, Eigen::VectorXd::Zero(model.getNumWires()));
            append(result.reserves, t, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(options.analysis.reserves.size())));
        }
        Eigen::VectorXd row = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(reportColumns.size()));
        row[0] = kMissingInputStatus;
        append(result.report, t, row);
    };
    const std::vector<int>& missing = result.missingRows;
    std::size_t nextMissing = 0;
    const int frames = static_cast<int>(trajectory.times.size());
    for (int i = 0; i < frames; ++i) {
        const double t = trajectory.times[i];
        for (; nextMissing < missing.size() && sampleTimes[missing[nextMissing]] <= t; ++nextMissing)
            appendMissing(sampleTimes[missing[nextMissing]]);
        // After resampling (--lowpass over a gap) a frame may fall on a missing row's time: it stays flagged.
        if (nextMissing > 0 && sampleTimes[missing[nextMissing - 1]] == t) continue;
        q = trajectory.q.row(i).transpose();
        u = trajectory.qdot.row(i).transpose();
        udot = trajectory.qddot.row(i).transpose();
        calcAppliedLinkForces(model, measured ? &*measured : nullptr, data, t, q, linkForces);
        const std::string at = "tensions at t = " + std::to_string(t) + " s (frame " + std::to_string(i + 1) + ")";
        const TensionFrame* solved = nullptr;
        try {
            solved = &analysis.calcFrame(q, u, udot, linkForces);
        } catch (const Error& e) {
            throw Error(at + ": " + e.what());
        }
        const TensionFrame& frame = *solved;
        if (!frame.tau.allFinite()) {
            Eigen::Index k = 0;
            while (std::isfinite(frame.tau[k])) ++k;
            throw Error(at + ": the generalized force of '" + getSpeedNames(model)[static_cast<std::size_t>(k)] +
                        "' from inverse dynamics is not finite (check the motion and external loads there)");
        }
        result.infeasibleFrames += frame.status == DistributionStatus::Infeasible;
        result.ipoptFrames += frame.usedIpopt;
        result.failedFrames += frame.status == DistributionStatus::Failed;
        append(result.tensions, t, frame.tension);
        if (staticOptimization) {
            append(result.activations, t, frame.activation);
            append(result.reserves, t, frame.reserveForce);
        }
        std::vector<double> row = {static_cast<double>(frame.status), frame.torqueError,
                                   static_cast<double>(frame.activeWires), static_cast<double>(frame.iterations),
                                   frame.usedIpopt ? 1.0 : 0.0,
                                   frame.unactuatedResidual};
        row.insert(row.end(), frame.residual.data(), frame.residual.data() + frame.residual.size());
        row.insert(row.end(), frame.reserve.data(), frame.reserve.data() + frame.reserve.size());
        result.report.times.push_back(t);
        result.report.rows.push_back(std::move(row));
        if (options.onFrame) options.onFrame(i + 1, frames);
    }
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

}  // namespace sinew

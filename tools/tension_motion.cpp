#include "sinew/tools/tension_motion.hpp"

#include <algorithm>
#include <optional>

#include "sinew/core/coordinate_preprocessing.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/smoothing_spline.hpp"
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
    return finite;
}

StorageTable makeTable(const std::string& name, const std::vector<std::string>& columns) {
    StorageTable table;
    table.name = name;
    table.columns = columns;
    return table;
}

}  // namespace

TensionMotionResult runTensionAnalysis(const Model& model, const StorageTable& motion, const ExternalLoads* loads,
                                       const TensionMotionOptions& options) {
    const std::vector<Coordinate>& coordinates = model.getCoordinates();
    TensionMotionResult result;
    const CoordinateSamples allSamples = readCoordinateSamples(model, motion);
    const CoordinateSamples samples = keepFiniteRows(allSamples, options, result.missingRows);
    const CoordinateTrajectory trajectory = preprocessCoordinateSamples(model, samples, options.lowpassCutoffHz,
                                                                        options.startTime, options.finalTime);
    std::vector<SmoothingSpline> speedSplines;
    if (options.accelerationsFromSpeedSplines) speedSplines = fitSpeedSplines(trajectory);

    std::optional<MeasuredLoads> measured;
    if (loads) measured.emplace(model, *loads);
    TensionAnalysis analysis(model, options.analysis);
    const bool staticOptimization = options.analysis.method == TensionMethod::StaticOptimization;

    std::vector<std::string> wireNames, reportColumns = {"status", "Z", "active_wires", "iterations",
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
    const Eigen::Index n = samples.q.cols();
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
        for (; nextMissing < missing.size() && allSamples.times[missing[nextMissing]] <= t; ++nextMissing)
            appendMissing(allSamples.times[missing[nextMissing]]);
        // After resampling (--lowpass over a gap) a frame may fall on a missing row's time: it stays flagged.
        if (nextMissing > 0 && allSamples.times[missing[nextMissing - 1]] == t) continue;
        q = trajectory.q.row(i).transpose();
        u = trajectory.qdot.row(i).transpose();
        if (options.accelerationsFromSpeedSplines)
            for (Eigen::Index j = 0; j < n; ++j) udot[j] = speedSplines[static_cast<std::size_t>(j)].calcDerivative(t, 1);
        else
            udot = trajectory.qddot.row(i).transpose();
        std::fill(linkForces.begin(), linkForces.end(), SpatialVector::Zero());
        if (measured) {
            calcPositionKinematics(model, data, q);
            measured->addLinkForces(data, t, linkForces);
        }
        const TensionFrame& frame = analysis.calcFrame(q, u, udot, linkForces);
        if (!frame.tau.allFinite())
            throw Error("tensions at t = " + std::to_string(t) + " s (frame " + std::to_string(i + 1) +
                        "): a generalized force from inverse dynamics is not finite");
        result.infeasibleFrames += frame.status == DistributionStatus::Infeasible;
        result.failedFrames += frame.status == DistributionStatus::Failed;
        append(result.tensions, t, frame.tension);
        if (staticOptimization) {
            append(result.activations, t, frame.activation);
            append(result.reserves, t, frame.reserveForce);
        }
        std::vector<double> row = {static_cast<double>(frame.status), frame.torqueError,
                                   static_cast<double>(frame.activeWires), static_cast<double>(frame.iterations),
                                   frame.unactuatedResidual};
        row.insert(row.end(), frame.residual.data(), frame.residual.data() + frame.residual.size());
        row.insert(row.end(), frame.reserve.data(), frame.reserve.data() + frame.reserve.size());
        result.report.times.push_back(t);
        result.report.rows.push_back(std::move(row));
        if (options.onFrame) options.onFrame(i + 1, frames);
    }
    for (; nextMissing < missing.size(); ++nextMissing) appendMissing(allSamples.times[missing[nextMissing]]);
    result.flaggedFrames = result.infeasibleFrames + result.failedFrames + static_cast<int>(missing.size());
    return result;
}

}  // namespace sinew

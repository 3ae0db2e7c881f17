#include "sinew/signal/coordinate_preprocessing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "sinew/core/error.hpp"
#include "sinew/signal/signal_filter.hpp"

namespace sinew {
namespace {

// Storage::resample never makes more rows than this (OpenSim's Storage::MAX_RESAMPLE_SIZE).
constexpr double kMaxResampledRows = 100000;

// The degree of the splines Storage::lowpassIIR resamples uneven rows with.
constexpr int kResampleDegree = 5;

// Bounds on the rows' times: beyond them the splines' B-spline systems lose double precision.
constexpr double kMaxTime = 1e9;       // s
constexpr double kMinTimeStep = 1e-9;  // s

std::string formatTime(double t) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", t);
    return text;
}

std::string columnLabel(const CoordinatePreprocessingOptions& options, Eigen::Index j) {
    return options.columnNames.empty() ? "column " + std::to_string(j) : "column '" + options.columnNames[j] + "'";
}

// Storage::findIndex: the last row at or before t, or row 0 when t precedes every row.
Eigen::Index lastRowAtOrBefore(const Eigen::VectorXd& times, double t) {
    const Eigen::Index after = std::upper_bound(times.data(), times.data() + times.size(), t) - times.data();
    return std::max<Eigen::Index>(after - 1, 0);
}

// The interpolation on sites x of `degree`: `reused` where it is that, else made.
SplineInterpolation makeInterpolation(int degree, const Eigen::VectorXd& x, const std::optional<SplineInterpolation>* reused) {
    if (reused && *reused && (*reused)->getDegree() == degree && (*reused)->getX().size() == x.size() && (*reused)->getX() == x)
        return **reused;
    return SplineInterpolation(degree, x);
}

// Pads, resamples when the step is uneven, and low-passes `values` over `times` in place, as
// Storage::pad(size / 2) then Storage::lowpassIIR(cutoff).
void padAndFilter(Eigen::VectorXd& times, Eigen::MatrixXd& values, double cutoffHz, const CoordinateSplineSetUps* reuse,
                  CoordinateSplineSetUps& setUps, CoordinateTrajectory& out) {
    const int pad = static_cast<int>(times.size() / 2);
    Eigen::MatrixXd padded(times.size() + 2 * pad, values.cols());
    for (Eigen::Index j = 0; j < values.cols(); ++j) padded.col(j) = padSignal(values.col(j), pad);
    times = padSignal(times, pad);
    values = std::move(padded);

    const Eigen::Index rows = times.size();
    const double span = times(rows - 1) - times(0);
    const double smallestStep = (times.tail(rows - 1) - times.head(rows - 1)).minCoeff();
    out.samplePeriod = smallestStep;
    // Uneven steps (even the rounding of a printed table) trigger resampling at the smallest step.
    if (span / static_cast<double>(rows - 1) - smallestStep > std::numeric_limits<double>::epsilon()) {
        if (span / smallestStep > kMaxResampledRows) out.samplePeriod = span / kMaxResampledRows;
        setUps.resampling = makeInterpolation(kResampleDegree, times, reuse ? &reuse->resampling : nullptr);
        const std::vector<SmoothingSpline> splines = setUps.resampling->interpolate(values);
        // The grid accumulates the step (x += dt) exactly as GCVSplineSet::constructStorage does, so its
        // times carry the same rounding as OpenSim's output.
        std::vector<double> grid;
        for (double t = times(0); t <= times(rows - 1); t += out.samplePeriod) grid.push_back(t);
        Eigen::MatrixXd resampled(static_cast<Eigen::Index>(grid.size()), values.cols()), row(1, values.cols());
        for (Eigen::Index i = 0; i < resampled.rows(); ++i) {
            SmoothingSpline::calcDerivatives(splines.data(), splines.size(), grid[static_cast<std::size_t>(i)], 0, row.data());
            resampled.row(i) = row;
        }
        times = Eigen::Map<const Eigen::VectorXd>(grid.data(), resampled.rows());
        values = std::move(resampled);
        out.resampled = true;
    }
    for (Eigen::Index j = 0; j < values.cols(); ++j) values.col(j) = lowpassIIR(values.col(j), out.samplePeriod, cutoffHz);
    out.usedCutoffHz = calcLowpassIIRCoefficients(out.samplePeriod, cutoffHz).cutoffHz;
}

}  // namespace

void checkCoordinateTable(const Eigen::VectorXd& times, const Eigen::MatrixXd& values, const CoordinatePreprocessingOptions& o) {
    const std::string where = "coordinate preprocessing: ";
    if (values.rows() != times.size())
        throw Error(where + std::to_string(values.rows()) + " rows of values for " + std::to_string(times.size()) + " times");
    if (values.cols() == 0) throw Error(where + "no coordinate columns");
    if (!o.columnNames.empty() && static_cast<Eigen::Index>(o.columnNames.size()) != values.cols())
        throw Error(where + std::to_string(o.columnNames.size()) + " column names for " +
                    std::to_string(values.cols()) + " columns");
    if (o.columnScales.size() != 0 && o.columnScales.size() != values.cols())
        throw Error(where + std::to_string(o.columnScales.size()) + " column scales for " +
                    std::to_string(values.cols()) + " columns");
    for (Eigen::Index j = 0; j < o.columnScales.size(); ++j)
        if (!std::isfinite(o.columnScales(j)))
            throw Error(where + "the scale of " + columnLabel(o, j) + " is not finite");
    if (std::isnan(o.lowpassCutoffHz) || o.lowpassCutoffHz == 0 || std::isinf(o.lowpassCutoffHz))
        throw Error(where + "low-pass cutoff " + std::to_string(o.lowpassCutoffHz) +
                    " Hz; expected a finite frequency > 0, or a negative value for no filtering");
    if (std::isnan(o.startTime) || std::isnan(o.finalTime) || o.startTime > o.finalTime)
        throw Error(where + "time range [" + std::to_string(o.startTime) + ", " + std::to_string(o.finalTime) +
                    "] s; expected start <= final");
    const int degree = o.splineDegree;
    if (degree < 1 || degree > 2 * SmoothingSpline::kMaxHalfOrder - 1 || degree % 2 == 0)
        throw Error(where + "spline degree " + std::to_string(degree) + "; expected 1, 3, 5 or 7");
    // The splines need degree + 1 rows, the resampling splines 6 of the padded rows; padding only adds.
    if (times.size() < degree + 1 || (o.lowpassCutoffHz > 0 && times.size() + 2 * (times.size() / 2) < kResampleDegree + 1))
        throw Error(where + std::to_string(times.size()) + " rows; too few for the degree-" + std::to_string(degree) +
                    " splines" + (o.lowpassCutoffHz > 0 ? " after padding" : ""));
    for (Eigen::Index i = 0; i < times.size(); ++i) {
        if (!(std::abs(times(i)) <= kMaxTime))
            throw Error(where + "the time of row " + std::to_string(i) + " (" + formatTime(times(i)) +
                        " s) is not finite or beyond +-1e9 s");
        if (i > 0 && times(i) - times(i - 1) < kMinTimeStep && times(i) > times(i - 1))
            throw Error(where + "row " + std::to_string(i) + " (t = " + formatTime(times(i)) + " s) follows row " +
                        std::to_string(i - 1) + " (t = " + formatTime(times(i - 1)) + " s) by less than 1e-9 s, closer "
                        "than the splines resolve");
        if (i > 0 && !(times(i) > times(i - 1)))
            throw Error(where + "row " + std::to_string(i) + " (t = " + std::to_string(times(i)) +
                        " s) does not follow row " + std::to_string(i - 1) + " (t = " + std::to_string(times(i - 1)) +
                        " s); times must be strictly increasing");
        for (Eigen::Index j = 0; j < values.cols(); ++j)
            if (!std::isfinite(values(i, j)))
                throw Error(where + "row " + std::to_string(i) + " (t = " + std::to_string(times(i)) + " s), " +
                            columnLabel(o, j) + ": value is not finite");
    }
}

CoordinateTrajectory preprocessCoordinates(const Eigen::VectorXd& times, const Eigen::MatrixXd& values,
                                           const CoordinatePreprocessingOptions& options) {
    checkCoordinateTable(times, values, options);
    CoordinateTrajectory out;
    out.processedTimes = times;
    out.processedValues = values;
    auto setUps = std::make_shared<CoordinateSplineSetUps>();
    const CoordinateSplineSetUps* reuse = options.setUps.get();
    if (options.lowpassCutoffHz > 0)
        padAndFilter(out.processedTimes, out.processedValues, options.lowpassCutoffHz, reuse, *setUps, out);
    if (options.columnScales.size() != 0) out.processedValues *= options.columnScales.asDiagonal();

    const Eigen::VectorXd& t = out.processedTimes;
    if (options.finalTime < t(0) || options.startTime > t(t.size() - 1))
        throw Error("coordinate preprocessing: time range [" + std::to_string(options.startTime) + ", " +
                    std::to_string(options.finalTime) + "] s lies outside the processed table's [" +
                    std::to_string(t(0)) + ", " + std::to_string(t(t.size() - 1)) + "] s");
    // GCVSplineSet(5, storage) fits each column with error variance 0: interpolating splines.
    setUps->final = makeInterpolation(options.splineDegree, t, reuse ? &reuse->final : nullptr);
    out.splines = setUps->final->interpolate(out.processedValues);
    out.setUps = std::move(setUps);

    // InverseDynamicsTool::run: the rows from findIndex(max(first, start)) to findIndex(min(last, final)).
    const Eigen::Index first = lastRowAtOrBefore(t, std::max(t(0), options.startTime));
    const Eigen::Index last = lastRowAtOrBefore(t, std::min(t(t.size() - 1), options.finalTime));
    const Eigen::Index frames = last - first + 1;
    out.firstRow = first;
    out.times = t.segment(first, frames);
    out.q.resize(frames, values.cols());
    out.qdot.resize(frames, values.cols());
    out.qddot.resize(frames, values.cols());
    Eigen::MatrixXd derivatives(3, values.cols());
    for (Eigen::Index i = 0; i < frames; ++i) {
        SmoothingSpline::calcDerivatives(out.splines.data(), out.splines.size(), out.times(i), 2, derivatives.data());
        out.q.row(i) = derivatives.row(0);
        out.qdot.row(i) = derivatives.row(1);
        out.qddot.row(i) = derivatives.row(2);
    }
    return out;
}

}  // namespace sinew

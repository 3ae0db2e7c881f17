#include "sinew/tools/coordinate_table.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "sinew/core/coordinate_rates.hpp"
#include "sinew/core/error.hpp"
#include "side_by_side.hpp"

namespace sinew {
namespace {

constexpr double kMaxCoordinateMagnitude = 1e6;
constexpr double kDegree = M_PI / 180;  // rad
// A stored quaternion is unit up to its printed digits (4 decimals: |q| within 2e-4 of 1); further off, the
// columns are not a quaternion (a wrong column order, angles in quaternion columns).
constexpr double kQuaternionNormTolerance = 0.01;

bool isQuaternionComponent(const Model& model, int q) {
    const Joint& joint = model.getJoint(model.getCoordinates()[static_cast<std::size_t>(q)].joint);
    return (joint.type == JointType::Ball || joint.type == JointType::Free) && q < joint.qStart + 4;
}

// q and -q are one rotation, and a table may switch between them (IK output, a BVH conversion); the
// splines need the branch that varies continuously, so each row takes the sign nearer the previous row's.
// Rows with a non-finite entry are left for keepFiniteRows to flag.
void makeQuaternionsContinuous(const Model& model, const std::string& where, Eigen::MatrixXd& q) {
    for (const Joint& joint : model.getJoints()) {
        if (joint.type != JointType::Ball && joint.type != JointType::Free) continue;
        Eigen::Index previous = -1;
        for (Eigen::Index r = 0; r < q.rows(); ++r) {
            auto quaternion = q.block<1, 4>(r, joint.qStart);
            if (!quaternion.allFinite()) continue;
            const double norm = quaternion.norm();
            if (std::abs(norm - 1) > kQuaternionNormTolerance)
                throw Error(where + " (the labels; rows counted from 0 below them): row " + std::to_string(r) +
                            ": the quaternion " + joint.name + "_qw.." + joint.name + "_qz has norm " +
                            std::to_string(norm) + ", expected 1 (to within " +
                            std::to_string(kQuaternionNormTolerance) + ")");
            if (previous >= 0 && quaternion.dot(q.block<1, 4>(previous, joint.qStart)) < 0) quaternion *= -1;
            previous = r;
        }
    }
}

// Unit quaternions and the speeds u, u̇ in place of the quaternions' component rates (nq -> nu columns).
void convertQuaternionRates(const Model& model, CoordinateTrajectory& trajectory) {
    Eigen::MatrixXd u(trajectory.times.size(), model.getNumU()), udot(trajectory.times.size(), model.getNumU());
    Eigen::VectorXd frameU, frameUdot;
    for (Eigen::Index i = 0; i < trajectory.times.size(); ++i) {
        calcSpeedsFromCoordinateRates(model, trajectory.q.row(i).transpose(), trajectory.qdot.row(i).transpose(),
                                      trajectory.qddot.row(i).transpose(), frameU, frameUdot);
        u.row(i) = frameU.transpose();
        udot.row(i) = frameUdot.transpose();
        for (const Joint& joint : model.getJoints())
            if (joint.type == JointType::Ball || joint.type == JointType::Free)
                trajectory.q.block<1, 4>(i, joint.qStart).normalize();
    }
    trajectory.qdot = std::move(u);
    trajectory.qddot = std::move(udot);
}

// Whether coordinate q's column of `table` holds degrees. OpenSim converts only rotational coordinates
// (Storage conversion by Coordinate::getMotionType); a quaternion's components are no angles.
bool isInDegrees(const Model& model, const StorageTable& table, int q) {
    return table.inDegrees && model.getCoordinates()[static_cast<std::size_t>(q)].motionType == MotionType::Rotational &&
           !isQuaternionComponent(model, q);
}

// One trajectory from columns of others that share their rows (one table's): column c is column
// source[c].second of parts[source[c].first].
CoordinateTrajectory joinColumns(const std::vector<const CoordinateTrajectory*>& parts,
                                 const std::vector<std::pair<std::size_t, Eigen::Index>>& source) {
    const CoordinateTrajectory& first = *parts.front();
    CoordinateTrajectory whole;
    whole.times = first.times;
    whole.processedTimes = first.processedTimes;
    whole.firstRow = first.firstRow;
    whole.samplePeriod = first.samplePeriod;
    whole.usedCutoffHz = first.usedCutoffHz;
    whole.resampled = first.resampled;
    whole.setUps = first.setUps;
    const Eigen::Index columns = static_cast<Eigen::Index>(source.size());
    whole.q.resize(first.q.rows(), columns);
    whole.qdot.resize(first.qdot.rows(), columns);
    whole.qddot.resize(first.qddot.rows(), columns);
    whole.processedValues.resize(first.processedValues.rows(), columns);
    for (Eigen::Index c = 0; c < columns; ++c) {
        const auto [part, j] = source[static_cast<std::size_t>(c)];
        const CoordinateTrajectory& from = *parts[part];
        whole.q.col(c) = from.q.col(j);
        whole.qdot.col(c) = from.qdot.col(j);
        whole.qddot.col(c) = from.qddot.col(j);
        whole.processedValues.col(c) = from.processedValues.col(j);
        whole.splines.push_back(from.splines[static_cast<std::size_t>(j)]);
    }
    return whole;
}

CoordinatePreprocessingOptions selectColumns(const CoordinatePreprocessingOptions& options, const std::vector<Eigen::Index>& columns) {
    CoordinatePreprocessingOptions part = options;
    part.columnNames.clear();
    for (const Eigen::Index c : columns) part.columnNames.push_back(options.columnNames[static_cast<std::size_t>(c)]);
    if (options.columnScales.size() != 0) part.columnScales = options.columnScales(columns);
    return part;
}

// The columns are independent (each padded, filtered and splined alone, as OpenSim does), so the table's
// two halves are processed side by side, each column's arithmetic unchanged. The whole table is checked
// first, so that a bad value is reported as processing it whole would.
CoordinateTrajectory preprocessInHalves(const Eigen::VectorXd& times, const Eigen::MatrixXd& q,
                                        const CoordinatePreprocessingOptions& options) {
    const Eigen::Index columns = q.cols(), half = columns / 2;
    if (half == 0) return preprocessCoordinates(times, q, options);
    checkCoordinateTable(times, q, options);
    std::vector<Eigen::Index> left, right;
    std::vector<std::pair<std::size_t, Eigen::Index>> source;
    for (Eigen::Index c = 0; c < columns; ++c) {
        source.emplace_back(c < half ? 0 : 1, c < half ? c : c - half);
        (c < half ? left : right).push_back(c);
    }
    std::optional<CoordinateTrajectory> leftPart, rightPart;
    runSideBySide([&] { leftPart = preprocessCoordinates(times, q.leftCols(half), selectColumns(options, left)); },
                  [&] { rightPart = preprocessCoordinates(times, q.rightCols(columns - half), selectColumns(options, right)); });
    return joinColumns({&*leftPart, &*rightPart}, source);
}

// The columns `processed` holds as the samples have them (the same numbers: the table's times and values,
// converted by the same factor) are taken from it; the others are processed here.
CoordinateTrajectory preprocessWithProcessedTable(const CoordinateSamples& samples, double lowpassCutoffHz, double startTime,
                                                  double finalTime, const CoordinatePreprocessingOptions& options,
                                                  const ProcessedMotionTable& processed) {
    const Eigen::Index columns = samples.q.cols();
    const bool sameProcessing = processed.lowpassCutoffHz == lowpassCutoffHz && processed.startTime == startTime &&
                                processed.finalTime == finalTime;
    if (!sameProcessing || samples.scales.size() != columns || processed.times.size() != samples.times.size() ||
        processed.times != samples.times)
        return preprocessInHalves(samples.times, samples.q, options);
    std::vector<std::pair<std::size_t, Eigen::Index>> source;
    std::vector<Eigen::Index> others;
    for (Eigen::Index c = 0; c < columns; ++c) {
        const auto found = std::find(processed.columns.begin(), processed.columns.end(), options.columnNames[static_cast<std::size_t>(c)]);
        const Eigen::Index j = found - processed.columns.begin();
        if (found != processed.columns.end() && samples.scales(c) == processed.scale &&
            processed.values.col(j) == samples.q.col(c)) {
            source.emplace_back(0, j);
        } else {
            source.emplace_back(1, static_cast<Eigen::Index>(others.size()));
            others.push_back(c);
        }
    }
    if (others.empty()) return joinColumns({&processed.trajectory}, source);
    Eigen::MatrixXd q(samples.q.rows(), static_cast<Eigen::Index>(others.size()));
    for (std::size_t k = 0; k < others.size(); ++k) q.col(static_cast<Eigen::Index>(k)) = samples.q.col(others[k]);
    CoordinatePreprocessingOptions rest = selectColumns(options, others);
    rest.setUps = processed.trajectory.setUps;  // the same times: the splines' set-ups are the same
    const CoordinateTrajectory processedRest = preprocessInHalves(samples.times, q, rest);
    return joinColumns({&processed.trajectory, &processedRest}, source);
}

// The options OpenSim's tools process a table with: the time range clamped to its rows'. Errors name `where`.
CoordinatePreprocessingOptions makeOptions(const Eigen::VectorXd& times, double lowpassCutoffHz, double startTime,
                                           double finalTime, const std::string& where, std::vector<std::string> names) {
    CoordinatePreprocessingOptions options;
    options.lowpassCutoffHz = lowpassCutoffHz;
    const Eigen::Index rows = times.size();
    options.startTime = rows ? std::max(startTime, times[0]) : startTime;
    options.finalTime = rows ? std::min(finalTime, times[rows - 1]) : finalTime;
    if (rows && options.startTime > options.finalTime)
        throw Error((where.empty() ? "" : where + ": ") + "the time range [" + std::to_string(startTime) + ", " +
                    std::to_string(finalTime) + "] s lies outside the motion's [" + std::to_string(times[0]) + ", " +
                    std::to_string(times[rows - 1]) + "] s");
    options.columnNames = std::move(names);
    return options;
}

// Errors of a table's processing, at its labels. Called in the handler: without a place, the error itself
// goes on.
[[noreturn]] void rethrowAt(const std::string& where, const Error& e) {
    if (where.empty()) throw;
    throw Error(where + " (the labels; rows counted from 0 below them): " + e.what());
}

}  // namespace

CoordinateSamples readCoordinateSamples(const Model& model, const StorageTable& table) {
    const std::vector<Coordinate>& coordinates = model.getCoordinates();
    std::vector<std::string> names;
    for (const Coordinate& c : coordinates) names.push_back(c.name);
    const std::vector<int> columnOf = matchStorageColumns(table, names, ExtraColumns::Refuse);

    // Coordinates in rad, degrees or m: no body's comes near; the splines' derivatives of larger ones overflow.
    checkStorageMagnitudes(table, columnOf, kMaxCoordinateMagnitude, "a coordinate (rad, degrees or m)");
    CoordinateSamples samples;
    const Eigen::Index rows = static_cast<Eigen::Index>(table.times.size()), n = static_cast<Eigen::Index>(names.size());
    samples.times = Eigen::Map<const Eigen::VectorXd>(table.times.data(), rows);
    samples.q.resize(rows, n);
    samples.where = table.where;
    samples.scales.resize(n);
    for (Eigen::Index c = 0; c < n; ++c) {
        const std::size_t column = static_cast<std::size_t>(columnOf[static_cast<std::size_t>(c)]);
        samples.scales(c) = isInDegrees(model, table, static_cast<int>(c)) ? kDegree : 1.0;
        for (Eigen::Index r = 0; r < rows; ++r) samples.q(r, c) = table.rows[static_cast<std::size_t>(r)][column] * samples.scales(c);
    }
    makeQuaternionsContinuous(model, table.where, samples.q);
    return samples;
}

StorageTable completeCoordinateTable(const Model& model, const StorageTable& table,
                                     const std::function<void(const std::string&)>& notes) {
    const std::vector<Coordinate>& coordinates = model.getCoordinates();
    StorageTable complete = table;
    complete.columns.clear();
    for (std::vector<double>& row : complete.rows) {
        row.clear();
        row.reserve(coordinates.size());  // filled a value at a time below
    }
    const std::string source = table.where.empty() ? "the motion" : table.where;
    for (std::size_t c = 0; c < coordinates.size(); ++c) {
        const Coordinate& coordinate = coordinates[c];
        const auto found = std::find(table.columns.begin(), table.columns.end(), coordinate.name);
        double held = coordinate.defaultValue;
        if (found == table.columns.end()) {
            if (isInDegrees(model, table, static_cast<int>(c))) held *= 180 / M_PI;
            if (notes)
                notes("coordinate '" + coordinate.name + "' is not in " + source + ": held at its default value " +
                      std::to_string(coordinate.defaultValue) + " (as OpenSim's tools do)");
        }
        complete.columns.push_back(coordinate.name);
        const std::size_t column = static_cast<std::size_t>(found - table.columns.begin());
        for (std::size_t r = 0; r < table.rows.size(); ++r)
            complete.rows[r].push_back(found == table.columns.end() ? held : table.rows[r][column]);
    }
    for (const std::string& column : table.columns)
        if (notes && std::find(complete.columns.begin(), complete.columns.end(), column) == complete.columns.end())
            notes("column '" + column + "' of " + source + " is no coordinate of model '" + model.getName() +
                  "': not read (as OpenSim's tools do)");
    return complete;
}

ProcessedMotionTable preprocessMotionTable(const StorageTable& table, double lowpassCutoffHz, double startTime,
                                           double finalTime) {
    ProcessedMotionTable processed;
    processed.columns = table.columns;
    processed.times = Eigen::Map<const Eigen::VectorXd>(table.times.data(), static_cast<Eigen::Index>(table.times.size()));
    processed.lowpassCutoffHz = lowpassCutoffHz;
    processed.startTime = startTime;
    processed.finalTime = finalTime;
    processed.scale = table.inDegrees ? kDegree : 1.0;
    Eigen::MatrixXd& values = processed.values;
    values.resize(processed.times.size(), static_cast<Eigen::Index>(table.columns.size()));
    for (Eigen::Index r = 0; r < values.rows(); ++r)
        for (Eigen::Index c = 0; c < values.cols(); ++c)
            values(r, c) = table.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] * processed.scale;
    const CoordinatePreprocessingOptions options =
        makeOptions(processed.times, lowpassCutoffHz, startTime, finalTime, table.where, table.columns);
    try {
        processed.trajectory = preprocessCoordinates(processed.times, processed.values, options);
    } catch (const Error& e) {
        rethrowAt(table.where, e);
    }
    return processed;
}

CoordinateTrajectory preprocessCoordinateSamples(const Model& model, const CoordinateSamples& samples,
                                                 double lowpassCutoffHz, double startTime, double finalTime,
                                                 const ProcessedMotionTable* processed) {
    std::vector<std::string> names;
    for (const Coordinate& c : model.getCoordinates()) names.push_back(c.name);
    const CoordinatePreprocessingOptions options =
        makeOptions(samples.times, lowpassCutoffHz, startTime, finalTime, samples.where, std::move(names));
    try {
        CoordinateTrajectory trajectory = processed && !hasQuaternionJoints(model)
                                              ? preprocessWithProcessedTable(samples, lowpassCutoffHz, startTime, finalTime,
                                                                             options, *processed)
                                              : preprocessInHalves(samples.times, samples.q, options);
        if (hasQuaternionJoints(model)) convertQuaternionRates(model, trajectory);
        return trajectory;
    } catch (const Error& e) {
        rethrowAt(samples.where, e);
    }
}

}  // namespace sinew

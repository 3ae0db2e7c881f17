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

// The columns are independent (each padded, filtered and splined alone, as OpenSim does), so the table's
// two halves are processed side by side, each column's arithmetic unchanged. The whole table is checked
// first, so that a bad value is reported as processing it whole would.
CoordinateTrajectory preprocessInHalves(const Eigen::VectorXd& times, const Eigen::MatrixXd& q,
                                        const CoordinatePreprocessingOptions& options) {
    const Eigen::Index columns = q.cols(), half = columns / 2;
    if (half == 0) return preprocessCoordinates(times, q, options);
    checkCoordinateTable(times, q, options);
    auto optionsFor = [&](Eigen::Index first, Eigen::Index count) {
        CoordinatePreprocessingOptions part = options;
        part.columnNames.assign(options.columnNames.begin() + first, options.columnNames.begin() + first + count);
        if (options.columnScales.size() != 0) part.columnScales = options.columnScales.segment(first, count);
        return part;
    };
    std::optional<CoordinateTrajectory> left, right;
    runSideBySide([&] { left = preprocessCoordinates(times, q.leftCols(half), optionsFor(0, half)); },
                  [&] { right = preprocessCoordinates(times, q.rightCols(columns - half), optionsFor(half, columns - half)); });
    CoordinateTrajectory whole = std::move(*left);
    auto append = [](Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
        Eigen::MatrixXd joined(a.rows(), a.cols() + b.cols());
        joined << a, b;
        a = std::move(joined);
    };
    append(whole.q, right->q);
    append(whole.qdot, right->qdot);
    append(whole.qddot, right->qddot);
    append(whole.processedValues, right->processedValues);
    whole.splines.insert(whole.splines.end(), right->splines.begin(), right->splines.end());
    return whole;
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
    for (Eigen::Index c = 0; c < n; ++c) {
        const std::size_t column = static_cast<std::size_t>(columnOf[static_cast<std::size_t>(c)]);
        const bool degrees = isInDegrees(model, table, static_cast<int>(c));
        for (Eigen::Index r = 0; r < rows; ++r)
            samples.q(r, c) = table.rows[static_cast<std::size_t>(r)][column] * (degrees ? M_PI / 180 : 1.0);
    }
    makeQuaternionsContinuous(model, table.where, samples.q);
    return samples;
}

StorageTable completeCoordinateTable(const Model& model, const StorageTable& table,
                                     const std::function<void(const std::string&)>& notes) {
    const std::vector<Coordinate>& coordinates = model.getCoordinates();
    StorageTable complete = table;
    complete.columns.clear();
    for (std::vector<double>& row : complete.rows) row.clear();
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

CoordinateTrajectory preprocessCoordinateSamples(const Model& model, const CoordinateSamples& samples,
                                                 double lowpassCutoffHz, double startTime, double finalTime) {
    CoordinatePreprocessingOptions options;
    options.lowpassCutoffHz = lowpassCutoffHz;
    const Eigen::Index rows = samples.times.size();
    options.startTime = rows ? std::max(startTime, samples.times[0]) : startTime;
    options.finalTime = rows ? std::min(finalTime, samples.times[rows - 1]) : finalTime;
    if (rows && options.startTime > options.finalTime)
        throw Error((samples.where.empty() ? "" : samples.where + ": ") + "the time range [" +
                    std::to_string(startTime) + ", " + std::to_string(finalTime) + "] s lies outside the motion's [" +
                    std::to_string(samples.times[0]) + ", " + std::to_string(samples.times[rows - 1]) + "] s");
    for (const Coordinate& c : model.getCoordinates()) options.columnNames.push_back(c.name);
    try {
        CoordinateTrajectory trajectory = preprocessInHalves(samples.times, samples.q, options);
        if (hasQuaternionJoints(model)) convertQuaternionRates(model, trajectory);
        return trajectory;
    } catch (const Error& e) {
        if (samples.where.empty()) throw;
        throw Error(samples.where + " (the labels; rows counted from 0 below them): " + e.what());
    }
}

}  // namespace sinew

#include "sinew/tools/coordinate_table.hpp"

#include <algorithm>
#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

constexpr double kMaxCoordinateMagnitude = 1e6;

}  // namespace

CoordinateSamples readCoordinateSamples(const Model& model, const StorageTable& table) {
    for (const Joint& joint : model.getJoints())
        if (joint.type == JointType::Ball || joint.type == JointType::Free)
            throw Error("model '" + model.getName() + "': joint '" + joint.name + "' is a " + toString(joint.type) +
                        " joint, whose quaternion cannot be read from a coordinates table (motion files need "
                        "custom, pin or weld joints)");
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
        // OpenSim converts only rotational coordinates (Storage conversion by Coordinate::getMotionType).
        const bool degrees = table.inDegrees && coordinates[static_cast<std::size_t>(c)].motionType == MotionType::Rotational;
        for (Eigen::Index r = 0; r < rows; ++r)
            samples.q(r, c) = table.rows[static_cast<std::size_t>(r)][column] * (degrees ? M_PI / 180 : 1.0);
    }
    return samples;
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
        return preprocessCoordinates(samples.times, samples.q, options);
    } catch (const Error& e) {
        if (samples.where.empty()) throw;
        throw Error(samples.where + " (the labels; rows counted from 0 below them): " + e.what());
    }
}

}  // namespace sinew

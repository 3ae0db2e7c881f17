#include "sinew/tools/coordinate_table.hpp"

#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {

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

    CoordinateSamples samples;
    const Eigen::Index rows = static_cast<Eigen::Index>(table.times.size()), n = static_cast<Eigen::Index>(names.size());
    samples.times = Eigen::Map<const Eigen::VectorXd>(table.times.data(), rows);
    samples.q.resize(rows, n);
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
    options.startTime = startTime;
    options.finalTime = finalTime;
    for (const Coordinate& c : model.getCoordinates()) options.columnNames.push_back(c.name);
    return preprocessCoordinates(samples.times, samples.q, options);
}

}  // namespace sinew

#include "sinew/tools/osim_states.hpp"

#include <algorithm>

#include "sinew/core/error.hpp"
#include "sinew/signal/smoothing_spline.hpp"

namespace sinew {
namespace {

// The column of a coordinate's state ("value" or "speed"), as TableUtilities::findStateLabelIndex: the
// full path, its tails after each '/', then the OpenSim 3 label. -1 when absent.
int findStateColumn(const std::vector<std::string>& labels, const std::string& joint, const std::string& coordinate,
                    const std::string& state) {
    const auto find = [&](const std::string& label) {
        const auto at = std::find(labels.begin(), labels.end(), label);
        return at == labels.end() ? -1 : static_cast<int>(at - labels.begin());
    };
    const std::string path = "/jointset/" + joint + "/" + coordinate + "/" + state;
    if (const int column = find(path); column >= 0) return column;
    for (std::size_t slash = path.find('/'); slash != std::string::npos; slash = path.find('/', slash + 1))
        if (const int column = find(path.substr(slash + 1)); column >= 0) return column;
    return find(state == "value" ? coordinate : coordinate + "_u");
}

}  // namespace

CoordinateTrajectory readOsimStates(const Model& model, const StorageTable& states, double startTime,
                                    double finalTime) {
    const std::string where = states.where.empty() ? "states" : states.where;
    const std::vector<Coordinate>& coordinates = model.getCoordinates();
    const int n = model.getNumU();
    if (model.getNumQ() != n || static_cast<int>(coordinates.size()) != n)
        throw ModelError(where, "model '" + model.getName() +
                                    "' has ball or free joints, whose quaternions a states file cannot give");
    if (states.inDegrees)
        throw ModelError(where, "the states are in degrees (inDegrees=yes); OpenSim's states files are in radians "
                                "and meters, as its AnalyzeTool requires");
    const Eigen::Index rows = static_cast<Eigen::Index>(states.times.size());
    Eigen::MatrixXd q(rows, n), u(rows, n);
    for (int c = 0; c < n; ++c) {
        const Coordinate& coordinate = coordinates[static_cast<std::size_t>(c)];
        const std::string& joint = model.getJoint(coordinate.joint).name;
        const int valueColumn = findStateColumn(states.columns, joint, coordinate.name, "value");
        const int speedColumn = findStateColumn(states.columns, joint, coordinate.name, "speed");
        if (valueColumn < 0 || speedColumn < 0)
            throw ModelError(where, "no " + std::string(valueColumn < 0 ? "value" : "speed") + " column for coordinate '" +
                                        coordinate.name + "' (expected /jointset/" + joint + "/" + coordinate.name +
                                        (valueColumn < 0 ? "/value or " + coordinate.name
                                                         : "/speed or " + coordinate.name + "_u") + ")");
        checkStorageMagnitudes(states, {valueColumn}, 1e6, "a coordinate value (rad or m)");
        checkStorageMagnitudes(states, {speedColumn}, 1e6, "a coordinate speed (rad/s or m/s)");
        for (Eigen::Index r = 0; r < rows; ++r) {
            q(r, c) = states.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(valueColumn)];
            u(r, c) = states.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(speedColumn)];
        }
    }
    const Eigen::Map<const Eigen::VectorXd> times(states.times.data(), rows);
    // Storage::findIndex: the last row at or before the time (the first row when none is).
    const auto rowAtOrBefore = [&](double t) {
        return std::max<Eigen::Index>(0, std::upper_bound(states.times.begin(), states.times.end(), t) -
                                             states.times.begin() - 1);
    };
    const Eigen::Index first = rowAtOrBefore(startTime), last = rowAtOrBefore(finalTime);
    if (rows == 0 || last < first)
        throw ModelError(where, "no state row in the time range [" + std::to_string(startTime) + ", " +
                                    std::to_string(finalTime) + "] s");

    CoordinateTrajectory trajectory;
    const Eigen::Index frames = last - first + 1;
    trajectory.times = times.segment(first, frames);
    trajectory.q = q.middleRows(first, frames);
    trajectory.qdot = u.middleRows(first, frames);
    trajectory.qddot.resize(frames, n);
    const std::vector<SmoothingSpline> speeds = SmoothingSpline::interpolateColumns(5, times, u);
    for (int c = 0; c < n; ++c)
        for (Eigen::Index f = 0; f < frames; ++f)
            trajectory.qddot(f, c) = speeds[static_cast<std::size_t>(c)].calcDerivative(trajectory.times[f], 1);
    trajectory.processedTimes = times;
    trajectory.firstRow = first;
    trajectory.processedValues = q;
    return trajectory;
}

}  // namespace sinew

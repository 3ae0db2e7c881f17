#include "sinew/tools/measured_loads.hpp"

#include <algorithm>
#include <iterator>
#include <utility>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"

namespace sinew {
namespace {

int findBody(const Model& model, const std::string& body, const ExternalForce& force, const char* role) {
    const int link = model.findLinkIndex(body);
    if (link == Model::kNotFound)
        throw ModelError(force.where, "external force '" + force.name + "': " + role + " body '" + body +
                                          "' is not in model '" + model.getName() + "'");
    return link;
}

}  // namespace

Eigen::Vector3d MeasuredLoads::Channel::calcValue(double t) const {
    if (splines.empty()) return Eigen::Vector3d::Zero();
    return {splines[0].calcValue(t), splines[1].calcValue(t), splines[2].calcValue(t)};
}

MeasuredLoads::MeasuredLoads(const Model& model, const ExternalLoads& loads) {
    const StorageTable& table = loads.data;
    if (table.times.size() < 2)
        throw Error(loads.dataFile + ": external load data need at least two rows, found " +
                    std::to_string(table.times.size()));
    const Eigen::Map<const Eigen::VectorXd> times(table.times.data(), static_cast<Eigen::Index>(table.times.size()));
    // OpenSim's ExternalForce: GCVSpline(3, ...) with its default error variance 0, i.e. interpolation.
    const int degree = table.times.size() >= 4 ? 3 : 1;
    // Every channel's columns are interpolated together: the sites, and so the spline set-up, are shared.
    std::vector<int> columns;
    std::vector<std::pair<Channel*, std::size_t>> channels;  // each present channel and its first column
    auto addChannel = [&](const std::array<int, 3>& channelColumns, Channel& channel) {
        if (channelColumns[0] < 0) return;
        // Forces (N), torques (N m) and points (m) of a measured load stay far below this; beyond it the
        // generalized forces overflow or drown every other load.
        checkStorageMagnitudes(table, {channelColumns.begin(), channelColumns.end()}, 1e7, "an external load (N, N m or m)");
        channels.emplace_back(&channel, columns.size());
        columns.insert(columns.end(), channelColumns.begin(), channelColumns.end());
    };
    loads_.reserve(loads.forces.size());  // the channels are pointed to
    for (const ExternalForce& force : loads.forces) {
        if (!force.appliesForce) continue;
        Load& load = loads_.emplace_back();
        load.appliedTo = findBody(model, force.appliedToBody, force, "applied-to");
        load.forceFrame = findBody(model, force.forceExpressedInBody, force, "force-expressed-in");
        load.pointFrame = findBody(model, force.pointExpressedInBody, force, "point-expressed-in");
        addChannel(force.forceColumns, load.force);
        addChannel(force.pointColumns, load.point);
        addChannel(force.torqueColumns, load.torque);
    }
    if (columns.empty()) return;
    Eigen::MatrixXd values(times.size(), static_cast<Eigen::Index>(columns.size()));
    for (Eigen::Index c = 0; c < values.cols(); ++c)
        for (Eigen::Index r = 0; r < times.size(); ++r)
            values(r, c) = table.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(columns[static_cast<std::size_t>(c)])];
    std::vector<SmoothingSpline> splines = SmoothingSpline::interpolateColumns(degree, times, values);
    for (const auto& [channel, first] : channels)
        channel->splines.assign(std::make_move_iterator(splines.begin() + static_cast<std::ptrdiff_t>(first)),
                                std::make_move_iterator(splines.begin() + static_cast<std::ptrdiff_t>(first + 3)));
}

void MeasuredLoads::addLinkForces(const Data& data, double t, std::vector<SpatialVector>& linkForces) const {
    auto toGround = [&](int link, const Eigen::Vector3d& v) -> Eigen::Vector3d {
        return link == kGround ? v : Eigen::Vector3d(data.R_GB[static_cast<std::size_t>(link)] * v);
    };
    for (const Load& load : loads_) {
        if (load.appliedTo == kGround) continue;
        const std::size_t b = static_cast<std::size_t>(load.appliedTo);
        const Eigen::Vector3d f_G = toGround(load.forceFrame, load.force.calcValue(t));
        // Without a point, OpenSim applies the force at the body's origin.
        Eigen::Vector3d p_G = data.p_GB[b];
        if (!load.point.splines.empty()) {
            p_G = toGround(load.pointFrame, load.point.calcValue(t));
            if (load.pointFrame != kGround) p_G += data.p_GB[static_cast<std::size_t>(load.pointFrame)];
        }
        linkForces[b].head<3>() += (p_G - data.p_GB[b]).cross(f_G) + toGround(load.forceFrame, load.torque.calcValue(t));
        linkForces[b].tail<3>() += f_G;
    }
}

void calcAppliedLinkForces(const Model& model, const MeasuredLoads* loads, Data& data, double t, const Eigen::VectorXd& q,
                           std::vector<SpatialVector>& linkForces) {
    std::fill(linkForces.begin(), linkForces.end(), SpatialVector::Zero());
    if (!loads) return;
    calcPositionKinematics(model, data, q);
    loads->addLinkForces(data, t, linkForces);
}

}  // namespace sinew

#include "sinew/tools/measured_loads.hpp"

#include <algorithm>
#include <array>
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

ExternalLoadCurves::ExternalLoadCurves(const ExternalLoads& loads) {
    const StorageTable& table = loads.data;
    if (table.times.size() < 2)
        throw Error(loads.dataFile + ": external load data need at least two rows, found " +
                    std::to_string(table.times.size()));
    const Eigen::Map<const Eigen::VectorXd> times(table.times.data(), static_cast<Eigen::Index>(table.times.size()));
    // OpenSim's ExternalForce: GCVSpline(3, ...) with its default error variance 0, i.e. interpolation.
    const int degree = table.times.size() >= 4 ? 3 : 1;
    // Every force's columns are interpolated together: the sites, and so the spline set-up, are shared.
    std::vector<int> columns;
    for (const ExternalForce& force : loads.forces) {
        if (!force.appliesForce) continue;
        ForceColumns& read = forces_.emplace_back();
        read.first = columns.size();
        auto addTriple = [&](const std::array<int, 3>& triple, int& offset) {
            if (triple[0] < 0) return;
            offset = read.count;
            read.count += 3;
            columns.insert(columns.end(), triple.begin(), triple.end());
        };
        addTriple(force.forceColumns, read.force);
        addTriple(force.pointColumns, read.point);
        addTriple(force.torqueColumns, read.torque);
    }
    if (columns.empty()) return;
    Eigen::MatrixXd values(times.size(), static_cast<Eigen::Index>(columns.size()));
    for (Eigen::Index c = 0; c < values.cols(); ++c)
        for (Eigen::Index r = 0; r < times.size(); ++r)
            values(r, c) = table.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(columns[static_cast<std::size_t>(c)])];
    splines_ = SmoothingSpline::interpolateColumns(degree, times, values);
}

MeasuredLoads::MeasuredLoads(const Model& model, const ExternalLoads& loads)
    : MeasuredLoads(model, loads, ExternalLoadCurves(loads)) {}

MeasuredLoads::MeasuredLoads(const Model& model, const ExternalLoads& loads, ExternalLoadCurves curves)
    : curves_(std::move(curves)) {
    const auto applied = std::count_if(loads.forces.begin(), loads.forces.end(),
                                       [](const ExternalForce& force) { return force.appliesForce; });
    if (static_cast<std::size_t>(applied) != curves_.forces_.size())
        throw Error(loads.file + ": the load curves were fitted to other external loads (" +
                    std::to_string(curves_.forces_.size()) + " forces, not " + std::to_string(applied) + ")");
    // Force by force, its bodies and then its columns' magnitudes: the order the errors came in when the
    // curves were fitted here.
    std::size_t next = 0;
    for (const ExternalForce& force : loads.forces) {
        if (!force.appliesForce) continue;
        Load& load = loads_.emplace_back();
        load.appliedTo = findBody(model, force.appliedToBody, force, "applied-to");
        load.forceFrame = findBody(model, force.forceExpressedInBody, force, "force-expressed-in");
        load.pointFrame = findBody(model, force.pointExpressedInBody, force, "point-expressed-in");
        for (const std::array<int, 3>* triple : {&force.forceColumns, &force.pointColumns, &force.torqueColumns})
            if ((*triple)[0] >= 0)
                // Forces (N), torques (N m) and points (m) of a measured load stay far below this; beyond it the
                // generalized forces overflow or drown every other load.
                checkStorageMagnitudes(loads.data, {triple->begin(), triple->end()}, 1e7, "an external load (N, N m or m)");
        load.columns = curves_.forces_[next++];
    }
}

void MeasuredLoads::addLinkForces(const Data& data, double t, std::vector<SpatialVector>& linkForces) const {
    auto toGround = [&](int link, const Eigen::Vector3d& v) -> Eigen::Vector3d {
        return link == kGround ? v : Eigen::Vector3d(data.R_GB[static_cast<std::size_t>(link)] * v);
    };
    std::array<double, 9> values;  // a force's columns at t; each spline on the same sites, evaluated at once
    for (const Load& load : loads_) {
        if (load.appliedTo == kGround) continue;
        const ExternalLoadCurves::ForceColumns& columns = load.columns;
        SmoothingSpline::calcDerivatives(curves_.splines_.data() + columns.first, static_cast<std::size_t>(columns.count),
                                         t, 0, values.data());
        auto triple = [&](int offset) -> Eigen::Vector3d {
            return offset < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(values[offset], values[offset + 1], values[offset + 2]);
        };
        const std::size_t b = static_cast<std::size_t>(load.appliedTo);
        const Eigen::Vector3d f_G = toGround(load.forceFrame, triple(columns.force));
        // Without a point, OpenSim applies the force at the body's origin.
        Eigen::Vector3d p_G = data.p_GB[b];
        if (columns.point >= 0) {
            p_G = toGround(load.pointFrame, triple(columns.point));
            if (load.pointFrame != kGround) p_G += data.p_GB[static_cast<std::size_t>(load.pointFrame)];
        }
        linkForces[b].head<3>() += (p_G - data.p_GB[b]).cross(f_G) + toGround(load.forceFrame, triple(columns.torque));
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

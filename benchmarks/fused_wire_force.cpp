#include "fused_wire_force.hpp"

#include "sinew/core/force_law.hpp"

namespace sinew_benchmarks {

FusedWireForce::FusedWireForce(const SimTK::SimbodyMatterSubsystem& matter, const sinew::Model& model,
                               const std::vector<SimTK::MobilizedBodyIndex>& bodies)
    : matter_(matter) {
    for (const sinew::WirePoint& point : model.getWirePoints()) {
        const Eigen::Vector3d& p = point.p_B;
        points_.push_back({bodies.at(static_cast<std::size_t>(point.link)), SimTK::Vec3(p.x(), p.y(), p.z())});
    }
    for (const sinew::Wire& wire : model.getWires()) wires_.push_back({wire.firstPoint, wire.numPoints, wire.law});
    p_GP_.resize(points_.size());
    v_GP_.resize(points_.size());
    r_GP_.resize(points_.size());
}

void FusedWireForce::calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                               SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const {
    // Each point once: p = p_B0 + r, v = v_B0 + w x r, with r the station's offset in ground.
    for (std::size_t k = 0; k < points_.size(); ++k) {
        const SimTK::MobilizedBody& body = matter_.getMobilizedBody(points_[k].body);
        const SimTK::Transform& X_GB = body.getBodyTransform(state);
        const SimTK::SpatialVec& V_GB = body.getBodyVelocity(state);
        r_GP_[k] = X_GB.R() * points_[k].p_B;
        p_GP_[k] = X_GB.p() + r_GP_[k];
        v_GP_[k] = V_GB[1] + V_GB[0] % r_GP_[k];
    }
    for (const WireRange& wire : wires_) {
        double length = 0, speed = 0;
        for (int k = wire.firstPoint; k + 1 < wire.firstPoint + wire.numPoints; ++k) {
            const SimTK::Vec3 segment = p_GP_[static_cast<std::size_t>(k + 1)] - p_GP_[static_cast<std::size_t>(k)];
            const double l = segment.norm();
            length += l;
            if (l > 1e-12)
                speed += SimTK::dot(segment / l, v_GP_[static_cast<std::size_t>(k + 1)] - v_GP_[static_cast<std::size_t>(k)]);
        }
        const double tension = wire.law->calcTension(sinew::WireState{length, speed, state.getTime()});
        if (tension == 0) continue;
        // Equal and opposite forces along each segment; a segment with both ends on one body adds nothing.
        for (int k = wire.firstPoint; k + 1 < wire.firstPoint + wire.numPoints; ++k) {
            const std::size_t a = static_cast<std::size_t>(k), b = a + 1;
            if (points_[a].body == points_[b].body) continue;
            const SimTK::Vec3 segment = p_GP_[b] - p_GP_[a];
            const double l = segment.norm();
            if (l <= 1e-12) continue;
            const SimTK::Vec3 f_G = (tension / l) * segment;  // on point a, towards b
            bodyForces[points_[a].body] += SimTK::SpatialVec(r_GP_[a] % f_G, f_G);
            bodyForces[points_[b].body] -= SimTK::SpatialVec(r_GP_[b] % f_G, f_G);
        }
    }
}

SimTK::Real FusedWireForce::calcPotentialEnergy(const SimTK::State& state) const {
    SimTK::Real energy = 0;
    for (const WireRange& wire : wires_) {
        double length = 0;
        for (int k = wire.firstPoint; k + 1 < wire.firstPoint + wire.numPoints; ++k) {
            const SimTK::MobilizedBody& a = matter_.getMobilizedBody(points_[static_cast<std::size_t>(k)].body);
            const SimTK::MobilizedBody& b = matter_.getMobilizedBody(points_[static_cast<std::size_t>(k + 1)].body);
            length += (b.findStationLocationInGround(state, points_[static_cast<std::size_t>(k + 1)].p_B) -
                       a.findStationLocationInGround(state, points_[static_cast<std::size_t>(k)].p_B))
                          .norm();
        }
        energy += wire.law->calcPotentialEnergy(length);
    }
    return energy;
}

}  // namespace sinew_benchmarks

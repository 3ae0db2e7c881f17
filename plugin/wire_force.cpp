#include "sinew/simbody/wire_force.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

WireForce::WireForce(const SimTK::SimbodyMatterSubsystem& matter, std::string name, std::vector<Station> path,
                     std::shared_ptr<const ForceLaw> law)
    : matter_(matter), name_(std::move(name)), path_(std::move(path)), law_(std::move(law)) {}

SimTK::Vec3 WireForce::findStationInGround(const SimTK::State& state, std::size_t k) const {
    return matter_.getMobilizedBody(path_[k].body).findStationLocationInGround(state, path_[k].p_B);
}

// One pass over the stations, each located once: length and lengthening speed together.
void WireForce::measure(const SimTK::State& state, double& length, double& speed) const {
    length = speed = 0;
    SimTK::Vec3 p0, v0;
    matter_.getMobilizedBody(path_[0].body).findStationLocationAndVelocityInGround(state, path_[0].p_B, p0, v0);
    for (std::size_t k = 1; k < path_.size(); ++k) {
        SimTK::Vec3 p1, v1;
        matter_.getMobilizedBody(path_[k].body).findStationLocationAndVelocityInGround(state, path_[k].p_B, p1, v1);
        const SimTK::Vec3 segment = p1 - p0;
        const double l = segment.norm();
        length += l;
        if (l > 1e-12) speed += SimTK::dot(segment / l, v1 - v0);
        p0 = p1;
        v0 = v1;
    }
}

double WireForce::calcLength(const SimTK::State& state) const {
    double length = 0;
    SimTK::Vec3 p0 = findStationInGround(state, 0);
    for (std::size_t k = 1; k < path_.size(); ++k) {
        const SimTK::Vec3 p1 = findStationInGround(state, k);
        length += (p1 - p0).norm();
        p0 = p1;
    }
    return length;
}

double WireForce::calcLengtheningSpeed(const SimTK::State& state) const {
    double length = 0, speed = 0;
    measure(state, length, speed);
    return speed;
}

double WireForce::calcTension(const SimTK::State& state) const {
    double length = 0, speed = 0;
    measure(state, length, speed);
    try {
        return law_->calcTension(WireState{length, speed, state.getTime()});
    } catch (const Error& e) {
        throw Error("wire '" + name_ + "' at t = " + std::to_string(state.getTime()) + " s: " + e.what());
    }
}

void WireForce::calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                          SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const {
    const double tension = calcTension(state);
    if (tension == 0) return;
    SimTK::Vec3 p0 = findStationInGround(state, 0);
    for (std::size_t k = 0; k + 1 < path_.size(); ++k) {
        const SimTK::Vec3 p1 = findStationInGround(state, k + 1);
        const SimTK::Vec3 segment = p1 - p0;
        const double l = segment.norm();
        // A segment with both ends on one body, or collapsed to a point, pulls on nothing.
        if (path_[k].body != path_[k + 1].body && l > 1e-12) {
            const SimTK::Vec3 f_G = tension * segment / l;
            matter_.getMobilizedBody(path_[k].body).applyForceToBodyPoint(state, path_[k].p_B, f_G, bodyForces);
            matter_.getMobilizedBody(path_[k + 1].body).applyForceToBodyPoint(state, path_[k + 1].p_B, -f_G, bodyForces);
        }
        p0 = p1;
    }
}

SimTK::Real WireForce::calcPotentialEnergy(const SimTK::State& state) const {
    return law_->calcPotentialEnergy(calcLength(state));
}

VirtualLinkWireForce::VirtualLinkWireForce(const SimTK::SimbodyMatterSubsystem& matter, const Model& model,
                                           std::vector<SimTK::MobilizedBodyIndex> bodies)
    : matter_(matter), model_(model), bodies_(std::move(bodies)), data_(model), equilibrium_(model) {
    // The first warm start: the virtual links where the model file puts them, at rest.
    for (int v : equilibrium_.links) {
        const Joint& joint = model.getJoint(v);
        const Eigen::Vector4d w_xyz = model.getDefaultQ().segment<4>(joint.qStart);
        data_.R_GB[static_cast<std::size_t>(v)] =
            Eigen::Quaterniond(w_xyz[0], w_xyz[1], w_xyz[2], w_xyz[3]).normalized().toRotationMatrix();
        data_.p_GB[static_cast<std::size_t>(v)] = model.getDefaultQ().segment<3>(joint.qStart + 4);
    }
}

const VirtualLinkEquilibriumStatus& VirtualLinkWireForce::solve(const SimTK::State& state) const {
    const auto same = [](const SimTK::Vector& a, const SimTK::Vector& b) {
        if (a.size() != b.size()) return false;
        for (int i = 0; i < a.size(); ++i)
            if (a[i] != b[i]) return false;
        return true;
    };
    if (solved_ && state.getTime() == solvedTime_ && same(state.getQ(), solvedQ_) && same(state.getU(), solvedU_))
        return equilibrium_.status;
    solved_ = true;
    solvedTime_ = state.getTime();
    solvedQ_ = state.getQ();
    solvedU_ = state.getU();
    const std::vector<WirePoint>& points = model_.getWirePoints();
    for (int w : equilibrium_.wires) {
        const Wire& wire = model_.getWire(w);
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const WirePoint& point = points[static_cast<std::size_t>(k)];
            if (model_.getLink(point.link).isVirtual) continue;
            SimTK::Vec3 p_G, v_G;
            matter_.getMobilizedBody(bodies_[static_cast<std::size_t>(point.link)])
                .findStationLocationAndVelocityInGround(state, SimTK::Vec3(point.p_B[0], point.p_B[1], point.p_B[2]),
                                                        p_G, v_G);
            data_.p_GP[static_cast<std::size_t>(k)] = Eigen::Vector3d(p_G[0], p_G[1], p_G[2]);
            data_.v_GP[static_cast<std::size_t>(k)] = Eigen::Vector3d(v_G[0], v_G[1], v_G[2]);
        }
    }
    return calcVirtualLinkEquilibrium(model_, data_, state.getTime(), equilibrium_);
}

void VirtualLinkWireForce::calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                                     SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const {
    solve(state);
    const std::vector<WirePoint>& points = model_.getWirePoints();
    for (int w : equilibrium_.wires) {
        const Wire& wire = model_.getWire(w);
        const double tension = equilibrium_.tension[w];
        if (tension == 0) continue;
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const WirePoint& point = points[static_cast<std::size_t>(k)];
            if (model_.getLink(point.link).isVirtual) continue;
            const Eigen::Vector3d f_G = -tension * data_.dLdp_GP[static_cast<std::size_t>(k)];
            matter_.getMobilizedBody(bodies_[static_cast<std::size_t>(point.link)])
                .applyForceToBodyPoint(state, SimTK::Vec3(point.p_B[0], point.p_B[1], point.p_B[2]),
                                       SimTK::Vec3(f_G[0], f_G[1], f_G[2]), bodyForces);
        }
    }
}

SimTK::Real VirtualLinkWireForce::calcPotentialEnergy(const SimTK::State& state) const {
    solve(state);
    double energy = 0;
    for (int w : equilibrium_.wires) energy += model_.getWire(w).law->calcPotentialEnergy(data_.wireLength[w]);
    return energy;
}

}  // namespace sinew

#include "sinew/simbody/wire_force.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

WireForce::WireForce(const SimTK::SimbodyMatterSubsystem& matter, std::string name, std::vector<Station> path,
                     std::shared_ptr<const ForceLaw> law)
    : matter_(matter), name_(std::move(name)), path_(std::move(path)), law_(std::move(law)) {}

SimTK::Vec3 WireForce::findStationInGround(const SimTK::State& state, std::size_t k) const {
    return matter_.getMobilizedBody(path_[k].body).findStationLocationInGround(state, path_[k].p_B);
}

SimTK::Vec3 WireForce::calcSegmentDirection(const SimTK::State& state, std::size_t k, double& length) const {
    const SimTK::Vec3 segment = findStationInGround(state, k + 1) - findStationInGround(state, k);
    length = segment.norm();
    return length > 1e-12 ? segment / length : SimTK::Vec3(0);
}

double WireForce::calcLength(const SimTK::State& state) const {
    double total = 0;
    for (std::size_t k = 0; k + 1 < path_.size(); ++k) {
        double length = 0;
        calcSegmentDirection(state, k, length);
        total += length;
    }
    return total;
}

double WireForce::calcLengtheningSpeed(const SimTK::State& state) const {
    double speed = 0;
    for (std::size_t k = 0; k + 1 < path_.size(); ++k) {
        double length = 0;
        const SimTK::Vec3 e = calcSegmentDirection(state, k, length);
        const SimTK::Vec3 v0 = matter_.getMobilizedBody(path_[k].body).findStationVelocityInGround(state, path_[k].p_B);
        const SimTK::Vec3 v1 =
            matter_.getMobilizedBody(path_[k + 1].body).findStationVelocityInGround(state, path_[k + 1].p_B);
        speed += SimTK::dot(e, v1 - v0);
    }
    return speed;
}

double WireForce::calcTension(const SimTK::State& state) const {
    try {
        return law_->calcTension(WireState{calcLength(state), calcLengtheningSpeed(state), state.getTime()});
    } catch (const Error& e) {
        throw Error("wire '" + name_ + "' at t = " + std::to_string(state.getTime()) + " s: " + e.what());
    }
}

void WireForce::calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                          SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const {
    const double tension = calcTension(state);
    if (tension == 0) return;
    for (std::size_t k = 0; k + 1 < path_.size(); ++k) {
        if (path_[k].body == path_[k + 1].body) continue;
        double length = 0;
        const SimTK::Vec3 f_G = tension * calcSegmentDirection(state, k, length);
        matter_.getMobilizedBody(path_[k].body).applyForceToBodyPoint(state, path_[k].p_B, f_G, bodyForces);
        matter_.getMobilizedBody(path_[k + 1].body).applyForceToBodyPoint(state, path_[k + 1].p_B, -f_G, bodyForces);
    }
}

SimTK::Real WireForce::calcPotentialEnergy(const SimTK::State& state) const {
    return law_->calcPotentialEnergy(calcLength(state));
}

}  // namespace sinew

#include "fused_wire_force.hpp"

#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/plugin/wire_paths.hpp"

namespace sinew_benchmarks {

FusedWireForce::FusedWireForce(const SimTK::SimbodyMatterSubsystem& matter, const sinew::Model& model,
                               const std::vector<SimTK::MobilizedBodyIndex>& bodies)
    : matter_(matter),
      model_(model),
      bodies_(bodies),
      data_(model),
      tensions_(model.getNumWires()),
      tau_(model.getNumU()) {}

void FusedWireForce::calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                               SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector& mobilityForces) const {
    sinew::copyPositionKinematics(matter_, bodies_, model_, state, data_);
    sinew::copyVelocityKinematics(matter_, bodies_, model_, state, data_);
    sinew::calcWirePaths(model_, data_);
    sinew::calcWireSpeeds(model_, data_);
    sinew::calcWireTensions(model_, data_, state.getTime(), tensions_);
    sinew::calcWireLinkForces(model_, data_, tensions_);
    // Both are [moment about the body's origin; force] in ground.
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
        const sinew::SpatialVector& F = data_.F_G[b];
        bodyForces[bodies_[b]] += SimTK::SpatialVec(SimTK::Vec3(F[0], F[1], F[2]), SimTK::Vec3(F[3], F[4], F[5]));
    }
    tau_.setZero();
    sinew::addWireCoordinateForces(model_, data_, tensions_, tau_);
    for (int u = 0; u < mobilityForces.size(); ++u) mobilityForces[u] += tau_[u];
}

SimTK::Real FusedWireForce::calcPotentialEnergy(const SimTK::State& state) const {
    sinew::copyPositionKinematics(matter_, bodies_, model_, state, data_);
    sinew::calcWirePaths(model_, data_);
    return sinew::calcWirePotentialEnergy(model_, data_);
}

}  // namespace sinew_benchmarks

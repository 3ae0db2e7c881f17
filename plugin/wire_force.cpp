#include "sinew/plugin/wire_force.hpp"

namespace sinew {

WireForce::WireForce(const SimbodyWirePaths& paths, int wire) : paths_(paths), wire_(wire) {}

const std::string& WireForce::getName() const { return paths_.getModel().getWire(wire_).name; }

double WireForce::calcLength(const SimTK::State& state) const { return paths_.realizePaths(state).wireLength[wire_]; }

double WireForce::calcLengtheningSpeed(const SimTK::State& state) const {
    return paths_.realizeTensions(state).wireSpeed[wire_];
}

double WireForce::calcTension(const SimTK::State& state) const {
    paths_.realizeTensions(state);
    return paths_.getTensions()[wire_];
}

void WireForce::calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                          SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector& mobilityForces) const {
    const double tension = calcTension(state);
    if (tension != 0) paths_.applyTension(wire_, tension, bodyForces, mobilityForces);
}

SimTK::Real WireForce::calcPotentialEnergy(const SimTK::State& state) const {
    return paths_.getModel().getWire(wire_).law->calcPotentialEnergy(calcLength(state));
}

VirtualLinkWireForce::VirtualLinkWireForce(const SimbodyWirePaths& paths) : paths_(paths) {}

const VirtualLinkEquilibriumStatus& VirtualLinkWireForce::solve(const SimTK::State& state) const {
    paths_.realizeTensions(state);
    return getEquilibrium().status;
}

void VirtualLinkWireForce::calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                                     SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector& mobilityForces) const {
    solve(state);
    for (int w : getEquilibrium().wires) {
        const double tension = getEquilibrium().tension[w];
        if (tension != 0) paths_.applyTension(w, tension, bodyForces, mobilityForces);
    }
}

SimTK::Real VirtualLinkWireForce::calcPotentialEnergy(const SimTK::State& state) const {
    solve(state);
    double energy = 0;
    for (int w : getEquilibrium().wires)
        energy += paths_.getModel().getWire(w).law->calcPotentialEnergy(getData().wireLength[w]);
    return energy;
}

}  // namespace sinew

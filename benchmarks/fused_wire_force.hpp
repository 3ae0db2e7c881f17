#pragma once
// All of a model's wires as one Simbody force element running core's whole-model wire passes once per
// evaluation: the leanest way we know to give Simbody sinew's wires, for the `simbody_fused` peer of the
// forward-dynamics benchmarks.
//
// The plugin's WireForce (one Force::Custom per wire, all reading one shared evaluation of core's paths per
// state) is the element sinew's users embed in their Simbody systems, and the `simbody` peer times it; this
// one runs the same core path code (calcWirePaths, calcWireSpeeds, calcWireLinkForces on the link poses
// Simbody's state holds) without the per-element dispatch and cache look-ups, so the sinew/Simbody ratio
// can be quoted against the stronger baseline. Models without virtual links only.
#include "sinew/plugin/ndebug_guard.hpp"

#include <Eigen/Core>
#include <Simbody.h>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew_benchmarks {

class FusedWireForce : public SimTK::Force::Custom::Implementation {
public:
    // `bodies`: the mobilized body of each of the model's links. `model` must outlive the element.
    FusedWireForce(const SimTK::SimbodyMatterSubsystem& matter, const sinew::Model& model,
                   const std::vector<SimTK::MobilizedBodyIndex>& bodies);

    void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                   SimTK::Vector_<SimTK::Vec3>& particleForces, SimTK::Vector& mobilityForces) const override;
    SimTK::Real calcPotentialEnergy(const SimTK::State& state) const override;

private:
    const SimTK::SimbodyMatterSubsystem& matter_;
    const sinew::Model& model_;
    std::vector<SimTK::MobilizedBodyIndex> bodies_;  // (numLinks)
    // Buffers sized at construction; one system per thread, like sinew::Data.
    mutable sinew::Data data_;
    mutable Eigen::VectorXd tensions_;  // N (numWires)
    mutable Eigen::VectorXd tau_;       // (nu) the tensions' generalized forces that no link force carries
};

}  // namespace sinew_benchmarks

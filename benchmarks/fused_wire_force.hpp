#pragma once
// All of a model's wires as one Simbody force element that visits each wire point once: the leanest way we
// know to give Simbody sinew's wires, for the `simbody_fused` peer of the forward-dynamics benchmarks.
//
// The plugin's WireForce (one Force::Custom per wire, each point located again for the length, the speed
// and the force) is the element sinew's users embed in their Simbody systems, and the `simbody` peer times
// it; this one shows how much of that time is the per-element overhead rather than Simbody's dynamics, so
// the sinew/Simbody ratio can be quoted against the stronger baseline.
#include "sinew/simbody/ndebug_guard.hpp"

#include <Simbody.h>
#include <memory>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew_benchmarks {

class FusedWireForce : public SimTK::Force::Custom::Implementation {
public:
    // `bodies`: the mobilized body of each of the model's links.
    FusedWireForce(const SimTK::SimbodyMatterSubsystem& matter, const sinew::Model& model,
                   const std::vector<SimTK::MobilizedBodyIndex>& bodies);

    void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                   SimTK::Vector_<SimTK::Vec3>& particleForces, SimTK::Vector& mobilityForces) const override;
    SimTK::Real calcPotentialEnergy(const SimTK::State& state) const override;

private:
    struct Point {
        SimTK::MobilizedBodyIndex body;
        SimTK::Vec3 p_B;  // m, in the body frame
    };
    struct WireRange {
        int firstPoint = 0;
        int numPoints = 0;
        std::shared_ptr<const sinew::ForceLaw> law;
    };

    const SimTK::SimbodyMatterSubsystem& matter_;
    std::vector<Point> points_;     // (total wire points)
    std::vector<WireRange> wires_;  // (numWires)
    // Scratch, sized at construction: per point its position and velocity in ground (m, m/s) and the
    // offset from its body's origin, expressed in ground (m). One system per thread, like sinew::Data.
    mutable std::vector<SimTK::Vec3> p_GP_, v_GP_, r_GP_;
};

}  // namespace sinew_benchmarks

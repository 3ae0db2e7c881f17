#pragma once
// A wire as a Simbody force element: a via-point path through stations fixed on mobilized bodies, with a
// sinew force law giving the tension. Computed from Simbody's own kinematics, independently of sinew's core.
#include "sinew/simbody/ndebug_guard.hpp"

#include <Simbody.h>
#include <memory>
#include <string>
#include <vector>

#include "sinew/core/force_law.hpp"

namespace sinew {

class WireForce : public SimTK::Force::Custom::Implementation {
public:
    struct Station {
        SimTK::MobilizedBodyIndex body;
        SimTK::Vec3 p_B;  // m, in the body frame
    };

    WireForce(const SimTK::SimbodyMatterSubsystem& matter, std::string name, std::vector<Station> path,
              std::shared_ptr<const ForceLaw> law);

    const std::string& getName() const { return name_; }
    // Need the state realized to Position (length) or Velocity (speed, tension).
    double calcLength(const SimTK::State& state) const;
    double calcLengtheningSpeed(const SimTK::State& state) const;
    double calcTension(const SimTK::State& state) const;

    // Equal and opposite forces along each segment; a segment with both ends on one body adds nothing.
    void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                   SimTK::Vector_<SimTK::Vec3>& particleForces, SimTK::Vector& mobilityForces) const override;
    SimTK::Real calcPotentialEnergy(const SimTK::State& state) const override;

private:
    SimTK::Vec3 findStationInGround(const SimTK::State& state, std::size_t k) const;
    void measure(const SimTK::State& state, double& length, double& speed) const;

    const SimTK::SimbodyMatterSubsystem& matter_;
    std::string name_;
    std::vector<Station> path_;
    std::shared_ptr<const ForceLaw> law_;
};

}  // namespace sinew

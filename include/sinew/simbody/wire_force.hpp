#pragma once
// Wires as Simbody force elements. WireForce: one wire, a via-point path through stations fixed on mobilized
// bodies, with a sinew force law giving the tension, computed from Simbody's own kinematics independently of
// sinew's core. VirtualLinkWireForce: all the wires that pass through virtual links, which Simbody cannot
// hold as bodies (they are massless), in quasi-static equilibrium by sinew's core solver.
#include "sinew/simbody/ndebug_guard.hpp"

#include <Simbody.h>
#include <memory>
#include <string>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/force_law.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"

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

// The wires with a point on a virtual link (VirtualLinkEquilibriumData::wires), as one force element. At each
// evaluation Simbody locates their points on bones, calcVirtualLinkEquilibrium puts the virtual links in
// equilibrium under them (warm-started from the previous evaluation's poses), and each wire's tension pulls
// on the bones at its points there (-tension dL/dp); the pulls on a virtual link balance, so they are
// dropped. Not thread-safe: the solver's buffers and warm start are kept here, as in one State's cache.
class VirtualLinkWireForce : public SimTK::Force::Custom::Implementation {
public:
    // `model` must outlive the force element; bodies[i] is real link i's mobilized body (model order; the
    // virtual links' entries are unused).
    VirtualLinkWireForce(const SimTK::SimbodyMatterSubsystem& matter, const Model& model,
                         std::vector<SimTK::MobilizedBodyIndex> bodies);

    // Solves the equilibrium at the state (realized to Velocity). The solution stays in getData() (poses and
    // twists of the virtual links, the wires' paths) and getEquilibrium() (tensions, status) until the next
    // solve. A state with the time, q and u of the last solve reuses it: the force, the tensions and the
    // energy of one state then come from one solve, not from warm starts moved by each other's calls.
    const VirtualLinkEquilibriumStatus& solve(const SimTK::State& state) const;
    const Data& getData() const { return data_; }
    const VirtualLinkEquilibriumData& getEquilibrium() const { return equilibrium_; }

    void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                   SimTK::Vector_<SimTK::Vec3>& particleForces, SimTK::Vector& mobilityForces) const override;
    SimTK::Real calcPotentialEnergy(const SimTK::State& state) const override;

private:
    const SimTK::SimbodyMatterSubsystem& matter_;
    const Model& model_;
    std::vector<SimTK::MobilizedBodyIndex> bodies_;
    mutable Data data_;
    mutable VirtualLinkEquilibriumData equilibrium_;
    mutable bool solved_ = false;
    mutable double solvedTime_ = 0;
    mutable SimTK::Vector solvedQ_, solvedU_;
};

}  // namespace sinew

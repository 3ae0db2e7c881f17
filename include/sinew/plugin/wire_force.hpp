#pragma once
// Wires as Simbody force elements, all reading one evaluation per state of sinew's core wire paths
// (SimbodyWirePaths, wire_paths.hpp). WireForce: one wire, any path sinew's core computes (via-points,
// conditional and moving points, wraps), with its force law giving the tension. VirtualLinkWireForce: all
// the wires that pass through virtual links, which Simbody cannot hold as bodies (they are massless), in
// quasi-static equilibrium by sinew's core solver.
#include "sinew/plugin/ndebug_guard.hpp"

#include <Simbody.h>
#include <string>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"
#include "sinew/plugin/wire_paths.hpp"

namespace sinew {

class WireForce : public SimTK::Force::Custom::Implementation {
public:
    // Wire `wire` of paths.getModel(), which must not pass through a virtual link; `paths` must outlive it.
    WireForce(const SimbodyWirePaths& paths, int wire);

    const std::string& getName() const;
    // Need the state realized to Position (length) or Velocity (speed, tension).
    double calcLength(const SimTK::State& state) const;
    double calcLengtheningSpeed(const SimTK::State& state) const;
    double calcTension(const SimTK::State& state) const;

    // The tension's pull at each point of the path as evaluated, and its push on the coordinates of moving
    // points (SimbodyWirePaths::applyTension).
    void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                   SimTK::Vector_<SimTK::Vec3>& particleForces, SimTK::Vector& mobilityForces) const override;
    SimTK::Real calcPotentialEnergy(const SimTK::State& state) const override;

private:
    const SimbodyWirePaths& paths_;
    int wire_;
};

// The wires with a point on a virtual link (VirtualLinkEquilibriumData::wires), as one force element. At each
// evaluation Simbody's state places the bones, calcVirtualLinkEquilibrium puts the virtual links in
// equilibrium under the wires (warm-started from the previous evaluation's poses), and each wire's tension
// pulls on the bones at its points there (-tension dL/dp); the pulls on a virtual link balance, so they are
// dropped. Not thread-safe: the solver's buffers and warm start are kept in `paths`, as in one State's cache.
class VirtualLinkWireForce : public SimTK::Force::Custom::Implementation {
public:
    // `paths` (of a model with virtual links) must outlive it.
    explicit VirtualLinkWireForce(const SimbodyWirePaths& paths);

    // Solves the equilibrium at the state (realized to Velocity). The solution stays in getData() (poses and
    // twists of the virtual links, the wires' paths) and getEquilibrium() (tensions, status) until another
    // state is evaluated. A state is solved once until its time, q or u change: the force, the tensions and
    // the energy of one state come from one solve, not from warm starts moved by each other's calls.
    const VirtualLinkEquilibriumStatus& solve(const SimTK::State& state) const;
    const Data& getData() const { return paths_.getData(); }
    const VirtualLinkEquilibriumData& getEquilibrium() const { return paths_.getEquilibrium(); }

    void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                   SimTK::Vector_<SimTK::Vec3>& particleForces, SimTK::Vector& mobilityForces) const override;
    SimTK::Real calcPotentialEnergy(const SimTK::State& state) const override;

private:
    const SimbodyWirePaths& paths_;
};

}  // namespace sinew

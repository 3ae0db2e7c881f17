#pragma once
// Every wire's path at a Simbody state, by sinew's core: Simbody's State gives the link poses and
// velocities, and core's calcWirePaths / calcWireSpeeds make the paths from them (conditional and moving
// points, wraps over spheres, cylinders and ellipsoids, the ellipsoid wires' length gradients:
// docs/wire-paths.md), calcVirtualLinkEquilibrium holds the virtual links, calcWireTensions gives the
// tensions. One evaluation serves all of a state's wire force elements: SimbodyWirePaths is a Subsystem
// of the system (as Simbody's CableTrackerSubsystem serves its CableSprings), whose lazy cache entries in
// each State say whether the evaluation it holds is that state's. Not thread-safe: the buffers are kept
// here, one system per thread, as sinew::Data is one per thread.
#include "sinew/plugin/ndebug_guard.hpp"

#include <Eigen/Core>
#include <Simbody.h>
#include <optional>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"

namespace sinew {

// Data's q, link poses (R_GB, p_GB) and joint frames (R_GF, p_GM, H_FM of custom joints), the part of
// calcPositionKinematics that wire paths read, from a state realized to Position. bodies[i] is real link
// i's mobilized body (virtual links' entries unused, their poses left as they are). Allocates nothing.
void copyPositionKinematics(const SimTK::SimbodyMatterSubsystem& matter,
                            const std::vector<SimTK::MobilizedBodyIndex>& bodies, const Model& model,
                            const SimTK::State& state, Data& data);
// Data's u and link velocities (w_GB, v_GB) from a state realized to Velocity; the same conventions.
void copyVelocityKinematics(const SimTK::SimbodyMatterSubsystem& matter,
                            const std::vector<SimTK::MobilizedBodyIndex>& bodies, const Model& model,
                            const SimTK::State& state, Data& data);

class SimbodyWirePaths : public SimTK::Subsystem::Guts {
public:
    // Adopts a new SimbodyWirePaths into `system` and returns it (the system owns it). `model` must outlive
    // the system; bodies[i] is real link i's mobilized body. Throws sinew::Error, naming the wire, for a wire
    // through a virtual link that is not a plain polyline.
    static const SimbodyWirePaths& adopt(SimTK::MultibodySystem& system, const SimTK::SimbodyMatterSubsystem& matter,
                                         const Model& model, std::vector<SimTK::MobilizedBodyIndex> bodies);

    // Every wire's path and length at the state (realized to Position): Data::p_GP, wireLength, dLdp_GP,
    // wirePath and wireLengthGradient as calcWirePaths makes them. The reference stays valid, and the numbers
    // the state's, until another state is evaluated.
    const Data& realizePaths(const SimTK::State& state) const;
    // The same with the speeds, the virtual links' equilibrium (warm-started from the last one evaluated) and
    // the tensions (realized to Velocity). Each State is evaluated once until its time, q or u change: the
    // force elements, tensions and energy of a state share one evaluation.
    const Data& realizeTensions(const SimTK::State& state) const;
    const Eigen::VectorXd& getTensions() const { return tensions_; }  // N (numWires), of the last realizeTensions
    const Data& getData() const { return data_; }
    // The virtual links' solver and its last solve; only for a model with virtual links.
    const VirtualLinkEquilibriumData& getEquilibrium() const { return *equilibrium_; }
    const Model& getModel() const { return model_; }

    // Adds the forces of tension f (N) on wire w at the paths last evaluated: -f dL/dp at each of its path
    // points on its body (tangent points on their objects' bodies; points on virtual links are left out, as
    // their pulls balance), and on the mobilities -f dL/du through its moving points, or a wire over an
    // ellipsoid's whole -f dL/du (Data::wireLengthGradient), as addWireCoordinateForces gives them.
    void applyTension(int w, double f, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                      SimTK::Vector& mobilityForces) const;

private:
    SimbodyWirePaths(const SimTK::SimbodyMatterSubsystem& matter, const Model& model,
                     std::vector<SimTK::MobilizedBodyIndex> bodies);
    SimTK::Subsystem::Guts* cloneImpl() const override { return new SimbodyWirePaths(*this); }
    int realizeSubsystemTopologyImpl(SimTK::State& state) const override;
    // Whether the state's cache entry holds `evaluation`, the number of the evaluation in data_ (0: none).
    bool holds(const SimTK::State& state, SimTK::CacheEntryIndex entry, long long evaluation) const;
    void mark(const SimTK::State& state, SimTK::CacheEntryIndex entry, long long evaluation) const;
    void placeBonePointsOfVirtualLinkWires(const SimTK::State& state) const;

    const SimTK::SimbodyMatterSubsystem& matter_;
    const Model& model_;
    std::vector<SimTK::MobilizedBodyIndex> bodies_;
    mutable Data data_;
    mutable std::optional<VirtualLinkEquilibriumData> equilibrium_;  // empty without virtual links
    mutable Eigen::VectorXd tensions_;
    // Evaluations are numbered as they are made; pathsEvaluation_ and tensionsEvaluation_ number the ones
    // data_ holds (0: none). Each State's lazy cache entries (Position, Velocity) hold the number of the
    // evaluation made for it, and Simbody invalidates them when its time, q or u change.
    mutable long long evaluations_ = 0, pathsEvaluation_ = 0, tensionsEvaluation_ = 0;
    mutable SimTK::CacheEntryIndex pathsEntry_, tensionsEntry_;
};

}  // namespace sinew

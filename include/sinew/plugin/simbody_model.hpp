#pragma once
// Builds a SimTK::MultibodySystem from a sinew Model: one MobilizedBody per link (Free, Ball, Pin, Weld
// mobilizers, in the model's order so Simbody's q and u are sinew's), Constraint::Ball loop closures,
// Constraint::CoordinateCoupler couplers, locked coordinates as Constraint::PrescribedMotion, gravity, and one WireForce (Force::Custom) per wire, every path sinew's core computes included (wraps,
// conditional and moving points), all evaluated once per state by a SimbodyWirePaths subsystem. Virtual
// links are massless, which Simbody's bodies cannot be: they get no mobilized body, and the wires through
// them one VirtualLinkWireForce that holds them in quasi-static equilibrium. Virtual links come last in the
// model, so Simbody's q and u are then the head of sinew's (the virtual links' entries follow from the
// equilibrium: calcCoordinates).
#include "sinew/plugin/ndebug_guard.hpp"

#include <Eigen/Core>
#include <Simbody.h>
#include <memory>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/plugin/custom_mobilizer.hpp"
#include "sinew/plugin/wire_force.hpp"

namespace sinew {

struct SimbodyModelOptions {
    // Link fixed to ground at its default pose by a Constraint::Weld (the paper's "hung by the head").
    // Empty: nothing added. A link already welded to ground through weld joints needs nothing either.
    std::string hangBy;
    bool gravity = true;
    bool wires = true;
    // How custom joints enter Simbody: sinew's exact mobilizer, or OpenSim's FunctionBased construction
    // (for reproducing OpenSim's numbers; see sinew/plugin/custom_mobilizer.hpp for where it is off).
    SimbodyMobilizer customJoints = SimbodyMobilizer::Sinew;
    bool forceElements = true;  // springs, bushings, coordinate limits, contact (sinew/plugin/force_elements.hpp)
};

class SimbodyModel {
public:
    explicit SimbodyModel(Model model, SimbodyModelOptions options = {});
    SimbodyModel(const SimbodyModel&) = delete;
    SimbodyModel& operator=(const SimbodyModel&) = delete;

    const Model& getModel() const { return model_; }
    const SimTK::MultibodySystem& getSystem() const { return *system_; }
    SimTK::MultibodySystem& updSystem() { return *system_; }
    const SimTK::SimbodyMatterSubsystem& getMatter() const { return *matter_; }
    // For adding force elements of one's own (then call updSystem().realizeTopology()).
    SimTK::GeneralForceSubsystem& updForces() { return *forces_; }
    // Loop k's Constraint::Ball.
    const SimTK::Constraint::Ball& getLoopConstraint(int loop) const;
    const SimTK::MobilizedBody& getMobilizedBody(int link) const;  // throws sinew::Error for a virtual link
    // Wire w's force element and its implementation (for its length, speed and tension); throws sinew::Error
    // for a wire through a virtual link.
    const SimTK::Force& getWireForceElement(int wire) const;
    const WireForce& getWireForce(int wire) const;
    // The force element of the wires through virtual links; nullptr when there are none (or no wires).
    const VirtualLinkWireForce* getVirtualLinkWireForce() const { return virtualLinkWireForce_; }
    // The wires' shared evaluation (paths, speeds, tensions per state); nullptr without wires.
    const SimbodyWirePaths* getWirePaths() const { return wirePaths_; }

    // Every wire's tension (N) at a state realized to Velocity.
    Eigen::VectorXd calcWireTensions(const SimTK::State& state) const;
    // sinew's q (nq) and u (nu) at a state realized to Velocity: Simbody's, then the virtual links' poses and
    // quasi-static twists from their equilibrium.
    void calcCoordinates(const SimTK::State& state, Eigen::VectorXd& q, Eigen::VectorXd& u) const;

    // The system's default state with sinew's q (nq) and u (nu) in it, realized to `stage` (the virtual
    // links' entries are not part of Simbody's state and are ignored).
    SimTK::State makeState(const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                           SimTK::Stage stage = SimTK::Stage::Velocity) const;
    // The model's default pose, at rest; loop closures satisfied to `accuracy` (projected when needed).
    SimTK::State makeDefaultState(double accuracy = 1e-10) const;

private:
    Model model_;
    std::unique_ptr<SimTK::MultibodySystem> system_;
    // Handles to subsystems the system owns; declared after it so they go first.
    std::unique_ptr<SimTK::SimbodyMatterSubsystem> matter_;
    std::unique_ptr<SimTK::GeneralForceSubsystem> forces_;
    std::unique_ptr<SimTK::GeneralContactSubsystem> contacts_;  // Hunt-Crossley contact; null without
    std::vector<SimTK::MobilizedBodyIndex> mobilizedBodies_;
    std::vector<SimTK::ForceIndex> wireForces_;
    std::vector<SimTK::ConstraintIndex> loopConstraints_;
    std::vector<const WireForce*> wireImplementations_;  // nullptr for a wire through a virtual link
    const VirtualLinkWireForce* virtualLinkWireForce_ = nullptr;  // owned by the system
    const SimbodyWirePaths* wirePaths_ = nullptr;                 // owned by the system
};

SimTK::Vector toSimTK(const Eigen::VectorXd& v);
Eigen::VectorXd toEigen(const SimTK::Vector& v);

}  // namespace sinew

#pragma once
// Coupled and locked coordinates (OpenSim's CoordinateCouplerConstraint, Model::getCouplers; Coordinate::
// locked): putting a pose on the couplers, and the rows both engines enforce in forward dynamics
// (calcForwardDynamics; Simbody's Constraint::CoordinateCoupler and PrescribedMotion,
// sinew/plugin/coordinate_constraints.hpp).
#include <Eigen/Core>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

// Sets every coupler's dependent coordinate from its independent one, q_dep = scaleFactor * f(q_indep), as
// OpenSim's assembly does before an analysis (Model::assemble, which gives dependent coordinates no goal of
// their own): for motions whose table lacks the dependent column, or whose values drift from it. OpenSim's
// InverseDynamicsTool does not do this (a missing column is held at its default value, a present one used
// as it is), so inverse dynamics should be given the motion as it stands. Allocates nothing.
void applyCoordinateCouplers(const Model& model, Eigen::Ref<Eigen::VectorXd> q);

// One constraint on a single coordinate (docs/closed-chain.md, "Coordinate constraints"): a coupler's
// q_dep = s f(q_ind), or a locked coordinate held at its default value. In velocity form
// u[speed] - slope u[otherSpeed] = 0, with slope = s f'(q_ind) for a coupler; a lock has no other speed.
struct CoordinateConstraint {
    int coordinate = 0;   // the constrained coordinate, in q (qdot = u for it)
    int speed = 0;        // its speed, in u
    int coupler = -1;     // index into Model::getCouplers(), or -1 for a lock
    int otherSpeed = -1;  // the coupler's independent speed, or -1
};

// Calls f with every coupler's constraint, then every locked coordinate's in q order; allocates nothing.
template <typename F>
void forEachCoordinateConstraint(const Model& model, F&& f) {
    for (std::size_t k = 0; k < model.getCouplers().size(); ++k) {
        const CoordinateCoupler& c = model.getCouplers()[k];
        f(CoordinateConstraint{c.dependentQ, c.dependentU, static_cast<int>(k), c.independentU});
    }
    for (std::size_t q = 0; q < model.getCoordinates().size(); ++q) {
        const Coordinate& coordinate = model.getCoordinates()[q];
        if (!coordinate.locked) continue;
        const Joint& joint = model.getJoint(coordinate.joint);  // a custom joint's coordinate: qdot = u
        f(CoordinateConstraint{static_cast<int>(q), joint.uStart + static_cast<int>(q) - joint.qStart});
    }
}

// The same, as a list.
std::vector<CoordinateConstraint> getCoordinateConstraints(const Model& model);

// s f'(q_ind) for a coupler's row, 0 for a lock's.
double calcCoordinateConstraintSlope(const Model& model, const CoordinateConstraint& constraint, const Eigen::VectorXd& q);

// The position gap at q: q_dep - s f(q_ind) for a coupler, q - default for a lock (rad or m).
double calcCoordinateConstraintGap(const Model& model, const CoordinateConstraint& constraint, const Eigen::VectorXd& q);

}  // namespace sinew

#pragma once
// Moment arms of the wires about the mobilities: r = -dL/du, the generalized force a unit tension exerts
// (OpenSim's GeometryPath::computeMomentArm, r = -dL/dq, for coordinates with qdot = u), taken along the
// coordinate couplers as OpenSim's MomentArmSolver takes them.
#include <Eigen/Core>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

// R (numWires x nu): for a pin or custom-joint coordinate, -dL/dq (m, or dimensionless for a translation);
// for a ball or free joint, about the axes of its F frame. Needs calcPositionKinematics and calcWirePaths.
//
// Couplers (Model::getCouplers, q_d = s f(q_i)): with a = s f'(q_i), the independent coordinate's column is
// the total derivative along the constraint, -dL/dq_i - a dL/dq_d; the dependent coordinate's column is
// -dL/dq_d along the constraint, i.e. the independent column / a, which is what OpenSim's MomentArmSolver
// reports for it (its coupling vector, from projecting a unit speed of q_d onto the constraint, is 1/a on
// q_i). Where a = 0 OpenSim divides 0 by 0 and reports NaN; sinew reports 0 there. Without couplers
// R = -J (calcWireJacobian). Allocates nothing.
void calcMomentArms(const Model& model, Data& data, Eigen::Ref<Eigen::MatrixXd> R);

}  // namespace sinew

#pragma once
// Moment arms of the wires about the mobilities: r = -dL/du, the generalized force a unit tension exerts
// (OpenSim's GeometryPath::computeMomentArm, r = -dL/dq, for coordinates with qdot = u).
#include <Eigen/Core>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

// R (numWires x nu) = -J: for a pin or custom-joint coordinate, -dL/dq (m, or dimensionless for a
// translation); for a ball or free joint, about the axes of its F frame. Needs calcPositionKinematics and
// calcWirePaths.
void calcMomentArms(const Model& model, Data& data, Eigen::Ref<Eigen::MatrixXd> R);

}  // namespace sinew

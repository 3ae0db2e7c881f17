#pragma once
// Wire geometry: a wire is a polyline through its points (origin, via-points, insertion), each fixed on a
// link. Length, lengthening speed, and tension from the wire's force law.
#include <Eigen/Core>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

// Fills Data::p_GP, dLdp_GP and wireLength. Needs calcPositionKinematics.
void calcWirePaths(const Model& model, Data& data);

// Fills Data::v_GP and wireSpeed (the time derivative of wireLength). Needs calcVelocityKinematics and
// calcWirePaths.
void calcWireSpeeds(const Model& model, Data& data);

// Tension of every wire (N, >= 0) from its force law at the lengths and speeds in `data`.
void calcWireTensions(const Model& model, const Data& data, double time, Eigen::Ref<Eigen::VectorXd> tensions);

// Energy stored in the wires' conservative force laws (J) at the lengths in `data`.
double calcWirePotentialEnergy(const Model& model, const Data& data);

}  // namespace sinew

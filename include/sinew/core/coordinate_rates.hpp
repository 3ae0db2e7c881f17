#pragma once
// The generalized speeds u and their rates u̇ of a motion known by its coordinates' time derivatives q̇ and
// q̈: the inverse of the kinematic differential equation q̇ = N(q) u. A motion table (IK output, motion
// capture) gives q(t) only, and a ball or free joint's quaternion has four rates for its three angular
// speeds. The quaternion may be off unit length (splined or filtered components): its rotation, and so
// w_FM, is that of q/|q|.
#include <Eigen/Core>

#include "sinew/core/model.hpp"

namespace sinew {

// With p a joint's quaternion (w, x, y, z) and ⊗ the Hamilton product, u = w_FM in F (core/kinematics.cpp):
//   w = 2 vec(ṗ ⊗ p*) / |p|²,   ẇ = 2 vec(p̈ ⊗ p*) / |p|² − w (2 p·ṗ) / |p|²;
// a free joint's translational speeds are the rates of its position (expressed in F); the other joints'
// speeds are their coordinates' rates. q, qdot, qddot have nq entries; u and udot get nu. A zero
// quaternion has no rotation: sinew::Error naming the joint.
void calcSpeedsFromCoordinateRates(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                   const Eigen::VectorXd& qddot, Eigen::VectorXd& u, Eigen::VectorXd& udot);

// Whether the model has ball or free joints, whose coordinates are quaternion components (nq != nu).
bool hasQuaternionJoints(const Model& model);

}  // namespace sinew

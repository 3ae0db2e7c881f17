#pragma once
// The kinematics of a custom joint (OpenSim's CustomJoint, built on Simbody's MobilizedBody::FunctionBased):
// theta_k = f_k(q_c(k)) along six axes of F; R_FM = R(theta_0, a_0) R(theta_1, a_1) R(theta_2, a_2), a
// body-fixed sequence; p_FM = sum_{k=3..5} theta_k a_k in F. Equations in docs/opensim-joints.md.
#include <Eigen/Core>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"

namespace sinew {

// X_FM and the motion subspace H_FM (6 x nu, [angular; linear] in F) at the joint's coordinates q
// (joint.nq values).
void calcCustomJointTransform(const Joint& joint, const double* q, Eigen::Matrix3d& R_FM, Eigen::Vector3d& p_FM,
                              JointMotion& H_FM);

// d(H_FM)/dt (6 x nu) at coordinates q moving with speeds u (qdot = u; joint.nu values each).
void calcCustomJointHDot(const Joint& joint, const double* q, const double* u, JointMotion& HDot_FM);

// d(H_FM)/dt u: the relative acceleration of M in F (angular; of M's origin, both differentiated in F and
// expressed in F) when udot = 0, at coordinates q and speeds u (joint.nu values each).
SpatialVector calcCustomJointBias(const Joint& joint, const double* q, const double* u);

}  // namespace sinew

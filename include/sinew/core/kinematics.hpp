#pragma once
// Forward kinematics of the link tree and the projection of link forces onto the joints.
// Conventions are in model.hpp; the equations in docs/wire-jacobian.md.
#include <Eigen/Core>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

// The joint's transform at q (the model's nq): R_FM and p_FM (M's origin in F, F axes), and for a custom
// joint its H_FM (left alone for the other types). Quaternions need not be normalised.
void calcJointTransform(const Joint& joint, const Eigen::VectorXd& q, Eigen::Matrix3d& R_FM, Eigen::Vector3d& p_FM,
                        JointMotion& H_FM);

// Fills Data::R_GB, p_GB, R_GF, p_GM (and H_FM of custom joints) from q (nq). Quaternions need not be
// normalised.
void calcPositionKinematics(const Model& model, Data& data, const Eigen::VectorXd& q);

// Fills Data::w_GB, v_GB from u (nu). Needs calcPositionKinematics first.
void calcVelocityKinematics(const Model& model, Data& data, const Eigen::VectorXd& u);

// Generalized forces (nu) equivalent to the spatial forces in Data::scratchF_G (moment about each link's
// origin, force): tau = sum over links of J_link^T F. Consumes Data::scratchF_G (it accumulates subtree
// forces in place, tip to base). Needs calcPositionKinematics first.
void calcGeneralizedForcesFromLinkForces(const Model& model, Data& data, Eigen::Ref<Eigen::VectorXd> tau);

// The generalized force (joint.nu values written at tauJoint) that a spatial force F_G (moment about the
// point p_ref; force; ground axes) acting on the subtree of `link` exerts on its joint: H^T F with H the
// joint's motion subspace, F taken about the joint centre in F axes. Reads the link's R_GF, p_GM and H_FM
// from calcPositionKinematics.
void projectOntoJoint(const Joint& joint, const Data& data, int link, const Eigen::Vector3d& p_ref,
                      const SpatialVector& F_G, double* tauJoint);

// The joint's motion subspace in ground axes: column c (of joint.nu) is the twist [angular velocity;
// velocity of the point p_ref] that a unit speed of mobility c gives the link relative to its parent.
// Reads what projectOntoJoint reads.
JointMotion calcJointMotion_G(const Joint& joint, const Data& data, int link, const Eigen::Vector3d& p_ref);

// Adds a link's spatial force in Data::scratchF_G (moment about its origin) to its parent's there (moment
// about the parent's origin).
void addToParent(const Model& model, Data& data, int link);

// q advanced along u for a time dt on the configuration manifold (quaternions by exact rotation about the
// angular velocity in F): the exponential map that finite-difference checks and integrators need.
Eigen::VectorXd integrateCoordinates(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                                     double dt);

// The same for one joint: its entries of `result` (nq) become its entries of q advanced along u for dt.
void integrateJointCoordinates(const Joint& joint, const Eigen::VectorXd& q, const Eigen::VectorXd& u, double dt,
                               Eigen::VectorXd& result);

}  // namespace sinew

#include "sinew/core/inverse_dynamics.hpp"

#include "sinew/core/custom_joint.hpp"
#include "sinew/core/kinematics.hpp"

namespace sinew {
namespace {

// The acceleration of M relative to F ([angular; of M's origin], differentiated in F, F axes): H udot plus,
// for a custom joint, its bias Hdot u. Free, ball and pin joints have constant H in F.
SpatialVector calcRelativeAcceleration(const Joint& joint, const Data& data, int link, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& u, const Eigen::VectorXd& udot) {
    SpatialVector A = SpatialVector::Zero();
    switch (joint.type) {
        case JointType::Free: A = udot.segment<6>(joint.uStart); break;
        case JointType::Ball: A.head<3>() = udot.segment<3>(joint.uStart); break;
        case JointType::Pin: A[2] = udot[joint.uStart]; break;
        case JointType::Weld: break;
        case JointType::Custom:
            A = data.H_FM[static_cast<std::size_t>(link)] * udot.segment(joint.uStart, joint.nu) +
                calcCustomJointBias(joint, q.data() + joint.qStart, u.data() + joint.uStart);
            break;
    }
    return A;
}

}  // namespace

void calcInverseDynamics(const Model& model, Data& data, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                         const Eigen::VectorXd& udot, const std::vector<SpatialVector>& appliedLinkForces,
                         Eigen::Ref<Eigen::VectorXd> tau) {
    calcPositionKinematics(model, data, q);
    calcInverseDynamicsAtPositions(model, data, q, u, udot, appliedLinkForces, tau);
}

void calcInverseDynamicsAtPositions(const Model& model, Data& data, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                                    const Eigen::VectorXd& udot, const std::vector<SpatialVector>& appliedLinkForces,
                                    Eigen::Ref<Eigen::VectorXd> tau) {
    calcVelocityKinematics(model, data, u);
    const Eigen::Vector3d& g = model.getGravity();
    // Base to tip: accelerations, then each link's inertial force less gravity and the applied force.
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Joint& joint = model.getJoint(i);
        const std::size_t b = static_cast<std::size_t>(i);
        Eigen::Vector3d w_P = Eigen::Vector3d::Zero(), alpha_P = Eigen::Vector3d::Zero(), a_PM = Eigen::Vector3d::Zero();
        Eigen::Vector3d v_PM = Eigen::Vector3d::Zero();  // velocity of the parent's point at the joint centre
        if (joint.parent != kGround) {
            const std::size_t p = static_cast<std::size_t>(joint.parent);
            const Eigen::Vector3d r = data.p_GM[b] - data.p_GB[p];
            w_P = data.w_GB[p];
            alpha_P = data.alpha_GB[p];
            v_PM = data.v_GB[p] + w_P.cross(r);
            a_PM = data.a_GB[p] + alpha_P.cross(r) + w_P.cross(w_P.cross(r));
        }
        const Eigen::Vector3d& w_B = data.w_GB[b];
        const Eigen::Vector3d d = data.p_GB[b] - data.p_GM[b];
        // Relative velocity of M in F, ground axes: the joint's motion seen from the rotating parent.
        const Eigen::Vector3d wRel = w_B - w_P;
        const Eigen::Vector3d vRel = data.v_GB[b] - w_B.cross(d) - v_PM;
        const SpatialVector A_FM = calcRelativeAcceleration(joint, data, i, q, u, udot);
        const Eigen::Matrix3d& R_GF = data.R_GF[b];
        // Differentiating in ground what was differentiated in F adds w_P x (...): the Coriolis terms.
        data.alpha_GB[b] = alpha_P + w_P.cross(wRel) + R_GF * A_FM.head<3>();
        const Eigen::Vector3d a_M = a_PM + 2 * w_P.cross(vRel) + R_GF * A_FM.tail<3>();
        data.a_GB[b] = a_M + data.alpha_GB[b].cross(d) + w_B.cross(w_B.cross(d));

        const Link& link = model.getLink(i);
        const Eigen::Matrix3d& R_GB = data.R_GB[b];
        const Eigen::Vector3d r_c = R_GB * link.com_B;
        const Eigen::Matrix3d I_c = R_GB * link.inertia_Bcom * R_GB.transpose();
        const Eigen::Vector3d a_c = data.a_GB[b] + data.alpha_GB[b].cross(r_c) + w_B.cross(w_B.cross(r_c));
        const Eigen::Vector3d f = link.mass * (a_c - g);
        SpatialVector F;
        F << I_c * data.alpha_GB[b] + w_B.cross(I_c * w_B) + r_c.cross(f), f;
        data.scratchF_G[b] = F - appliedLinkForces[b];
    }
    // Tip to base: each joint carries its subtree's net force, projected onto its motion subspace.
    for (int i = model.getNumLinks() - 1; i >= 0; --i) {
        const Joint& joint = model.getJoint(i);
        const std::size_t b = static_cast<std::size_t>(i);
        projectOntoJoint(joint, data, i, data.p_GB[b], data.scratchF_G[b], tau.data() + joint.uStart);
        addToParent(model, data, i);
    }
}

}  // namespace sinew

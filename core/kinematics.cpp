#include "sinew/core/kinematics.hpp"

#include <Eigen/Geometry>

#include "sinew/core/custom_joint.hpp"

namespace sinew {
namespace {

Eigen::Quaterniond readQuaternion(const Eigen::VectorXd& q, int start) {
    return Eigen::Quaterniond(q[start], q[start + 1], q[start + 2], q[start + 3]).normalized();
}

}  // namespace

void calcJointTransform(const Joint& joint, const Eigen::VectorXd& q, Eigen::Matrix3d& R_FM, Eigen::Vector3d& p_FM,
                        JointMotion& H_FM) {
    R_FM.setIdentity();
    p_FM.setZero();
    switch (joint.type) {
        case JointType::Free:
            R_FM = readQuaternion(q, joint.qStart).toRotationMatrix();
            p_FM = q.segment<3>(joint.qStart + 4);
            break;
        case JointType::Ball: R_FM = readQuaternion(q, joint.qStart).toRotationMatrix(); break;
        case JointType::Pin: R_FM = Eigen::AngleAxisd(q[joint.qStart], Eigen::Vector3d::UnitZ()).toRotationMatrix(); break;
        case JointType::Weld: break;
        case JointType::Custom: calcCustomJointTransform(joint, q.data() + joint.qStart, R_FM, p_FM, H_FM); break;
    }
}

void calcPositionKinematics(const Model& model, Data& data, const Eigen::VectorXd& q) {
    data.q = q;  // for the wire points that depend on coordinates
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Joint& joint = model.getJoint(i);
        const std::size_t b = static_cast<std::size_t>(i);
        Eigen::Matrix3d R_GP = Eigen::Matrix3d::Identity();
        Eigen::Vector3d p_GP = Eigen::Vector3d::Zero();
        if (joint.parent != kGround) {
            R_GP = data.R_GB[static_cast<std::size_t>(joint.parent)];
            p_GP = data.p_GB[static_cast<std::size_t>(joint.parent)];
        }
        Eigen::Matrix3d R_FM;
        Eigen::Vector3d p_FM;
        calcJointTransform(joint, q, R_FM, p_FM, data.H_FM[b]);
        data.R_GF[b] = R_GP * joint.R_PF;
        data.p_GM[b] = p_GP + R_GP * joint.p_PF + data.R_GF[b] * p_FM;
        data.R_GB[b] = data.R_GF[b] * R_FM * joint.R_BM.transpose();
        data.p_GB[b] = data.p_GM[b] - data.R_GB[b] * joint.p_BM;
    }
}

void calcVelocityKinematics(const Model& model, Data& data, const Eigen::VectorXd& u) {
    data.u = u;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Joint& joint = model.getJoint(i);
        const std::size_t b = static_cast<std::size_t>(i);
        Eigen::Vector3d w_GP = Eigen::Vector3d::Zero();
        Eigen::Vector3d v_GM = Eigen::Vector3d::Zero();  // velocity of the parent's point at the joint centre
        if (joint.parent != kGround) {
            const std::size_t p = static_cast<std::size_t>(joint.parent);
            w_GP = data.w_GB[p];
            v_GM = data.v_GB[p] + w_GP.cross(data.p_GM[b] - data.p_GB[p]);
        }
        Eigen::Vector3d w_GB = w_GP;
        switch (joint.type) {
            case JointType::Free:
                w_GB += data.R_GF[b] * u.segment<3>(joint.uStart);
                v_GM += data.R_GF[b] * u.segment<3>(joint.uStart + 3);
                break;
            case JointType::Ball: w_GB += data.R_GF[b] * u.segment<3>(joint.uStart); break;
            case JointType::Pin: w_GB += data.R_GF[b].col(2) * u[joint.uStart]; break;
            case JointType::Weld: break;
            case JointType::Custom: {
                const SpatialVector V_FM = data.H_FM[b] * u.segment(joint.uStart, joint.nu);
                w_GB += data.R_GF[b] * V_FM.head<3>();
                v_GM += data.R_GF[b] * V_FM.tail<3>();
                break;
            }
        }
        data.w_GB[b] = w_GB;
        data.v_GB[b] = v_GM + w_GB.cross(data.p_GB[b] - data.p_GM[b]);
    }
}

void projectOntoJoint(const Joint& joint, const Data& data, int link, const Eigen::Vector3d& p_ref,
                      const SpatialVector& F_G, double* tauJoint) {
    const std::size_t b = static_cast<std::size_t>(link);
    const Eigen::Matrix3d& R_GF = data.R_GF[b];
    const Eigen::Vector3d f = F_G.tail<3>();
    const Eigen::Vector3d momentAboutJoint = shiftForce(F_G, data.p_GM[b] - p_ref).head<3>();
    switch (joint.type) {
        case JointType::Free:
            Eigen::Map<Eigen::Vector3d>{tauJoint} = R_GF.transpose() * momentAboutJoint;
            Eigen::Map<Eigen::Vector3d>{tauJoint + 3} = R_GF.transpose() * f;
            break;
        case JointType::Ball: Eigen::Map<Eigen::Vector3d>{tauJoint} = R_GF.transpose() * momentAboutJoint; break;
        case JointType::Pin: tauJoint[0] = R_GF.col(2).dot(momentAboutJoint); break;
        case JointType::Weld: break;
        case JointType::Custom: {
            SpatialVector F_F;
            F_F << R_GF.transpose() * momentAboutJoint, R_GF.transpose() * f;
            Eigen::Map<Eigen::VectorXd>(tauJoint, joint.nu) = data.H_FM[b].transpose() * F_F;
            break;
        }
    }
}

JointMotion calcJointMotion_G(const Joint& joint, const Data& data, int link, const Eigen::Vector3d& p_ref) {
    // By virtual work, H^T F for unit spatial forces F (about p_ref) reads H row by row.
    JointMotion H_G(6, joint.nu);
    for (int k = 0; k < 6; ++k) {
        double row[6];
        projectOntoJoint(joint, data, link, p_ref, SpatialVector::Unit(k), row);
        for (int c = 0; c < joint.nu; ++c) H_G(k, c) = row[c];
    }
    return H_G;
}

void calcGeneralizedForcesFromLinkForces(const Model& model, Data& data, Eigen::Ref<Eigen::VectorXd> tau) {
    for (int i = model.getNumLinks() - 1; i >= 0; --i) {
        const Joint& joint = model.getJoint(i);
        const std::size_t b = static_cast<std::size_t>(i);
        projectOntoJoint(joint, data, i, data.p_GB[b], data.scratchF_G[b], tau.data() + joint.uStart);
        addToParent(model, data, i);
    }
}

void addToParent(const Model& model, Data& data, int link) {
    const int parent = model.getJoint(link).parent;
    if (parent == kGround) return;
    const std::size_t b = static_cast<std::size_t>(link), p = static_cast<std::size_t>(parent);
    data.scratchF_G[p] += shiftForce(data.scratchF_G[b], data.p_GB[p] - data.p_GB[b]);
}

void integrateJointCoordinates(const Joint& joint, const Eigen::VectorXd& q, const Eigen::VectorXd& u, double dt,
                               Eigen::VectorXd& result) {
    auto rotate = [&](int qStart, const Eigen::Vector3d& w_F) {
        const Eigen::Vector3d rotation = w_F * dt;
        const double angle = rotation.norm();
        const Eigen::Quaterniond delta = angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, rotation / angle))
                                                   : Eigen::Quaterniond::Identity();
        // w_FM is expressed in F, so the increment multiplies from the F side: R_FM(t+dt) = exp(w dt) R_FM(t).
        const Eigen::Quaterniond next = (delta * readQuaternion(q, qStart)).normalized();
        result.segment<4>(qStart) << next.w(), next.x(), next.y(), next.z();
    };
    switch (joint.type) {
        case JointType::Free:
            rotate(joint.qStart, u.segment<3>(joint.uStart));
            result.segment<3>(joint.qStart + 4) = q.segment<3>(joint.qStart + 4) + dt * u.segment<3>(joint.uStart + 3);
            break;
        case JointType::Ball: rotate(joint.qStart, u.segment<3>(joint.uStart)); break;
        case JointType::Pin: result[joint.qStart] = q[joint.qStart] + dt * u[joint.uStart]; break;
        case JointType::Weld: break;
        case JointType::Custom:
            result.segment(joint.qStart, joint.nq) = q.segment(joint.qStart, joint.nq) + dt * u.segment(joint.uStart, joint.nu);
            break;
    }
}

Eigen::VectorXd integrateCoordinates(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                                     double dt) {
    Eigen::VectorXd result = q;
    for (const Joint& joint : model.getJoints()) integrateJointCoordinates(joint, q, u, dt, result);
    return result;
}

}  // namespace sinew

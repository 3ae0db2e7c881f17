#include "sinew/core/coordinate_rates.hpp"

#include <Eigen/Geometry>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

Eigen::Quaterniond quaternionAt(const Eigen::VectorXd& v, int start) {
    return Eigen::Quaterniond(v[start], v[start + 1], v[start + 2], v[start + 3]);
}

}  // namespace

bool hasQuaternionJoints(const Model& model) {
    for (const Joint& joint : model.getJoints())
        if (joint.type == JointType::Ball || joint.type == JointType::Free) return true;
    return false;
}

void calcSpeedsFromCoordinateRates(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                   const Eigen::VectorXd& qddot, Eigen::VectorXd& u, Eigen::VectorXd& udot) {
    u.resize(model.getNumU());
    udot.resize(model.getNumU());
    for (const Joint& joint : model.getJoints()) {
        if (joint.type != JointType::Ball && joint.type != JointType::Free) {
            u.segment(joint.uStart, joint.nu) = qdot.segment(joint.qStart, joint.nq);
            udot.segment(joint.uStart, joint.nu) = qddot.segment(joint.qStart, joint.nq);
            continue;
        }
        const Eigen::Quaterniond p = quaternionAt(q, joint.qStart);
        const double norm2 = p.squaredNorm();
        if (!(norm2 > 0))
            throw Error("joint '" + joint.name + "': its quaternion is zero (or not finite), which is no rotation");
        const Eigen::Quaterniond pConjugate = p.conjugate();
        const Eigen::Vector3d w = 2 * (quaternionAt(qdot, joint.qStart) * pConjugate).vec() / norm2;
        const double normRate = 2 * p.coeffs().dot(quaternionAt(qdot, joint.qStart).coeffs()) / norm2;
        u.segment<3>(joint.uStart) = w;
        udot.segment<3>(joint.uStart) = 2 * (quaternionAt(qddot, joint.qStart) * pConjugate).vec() / norm2 - w * normRate;
        if (joint.type == JointType::Free) {
            u.segment<3>(joint.uStart + 3) = qdot.segment<3>(joint.qStart + 4);
            udot.segment<3>(joint.uStart + 3) = qddot.segment<3>(joint.qStart + 4);
        }
    }
}

}  // namespace sinew

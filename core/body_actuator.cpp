#include "sinew/core/body_actuator.hpp"

#include "sinew/core/kinematics.hpp"

namespace sinew {
namespace {

// Adds sign * J^T F for the spatial force F_G (moment about p_ref; force) acting on `link`: every joint
// from the link to the root carries it.
void addLinkForce(const Model& model, const Data& data, int link, const Eigen::Vector3d& p_ref,
                  const SpatialVector& F_G, double sign, Eigen::Ref<Eigen::VectorXd> tau) {
    double column[6];
    for (int i = link; i != kGround; i = model.getJoint(i).parent) {
        const Joint& joint = model.getJoint(i);
        projectOntoJoint(joint, data, i, p_ref, F_G, column);
        for (int c = 0; c < joint.nu; ++c) tau[joint.uStart + c] += sign * column[c];
    }
}

}  // namespace

void calcBodyActuatorGeneralizedForce(const Model& model, const Data& data, const BodyActuator& actuator,
                                      Eigen::Ref<Eigen::VectorXd> tau) {
    tau.setZero();
    const std::size_t b = static_cast<std::size_t>(actuator.link);
    // A torque's link may be ground (OpenSim allows bodyA = ground): its frame is then ground's.
    Eigen::Vector3d axis_G = actuator.axis.normalized();
    if (!actuator.axisInGround && actuator.link != kGround) axis_G = data.R_GB[b] * axis_G;
    SpatialVector F_G = SpatialVector::Zero();
    if (actuator.kind == BodyActuator::Kind::PointForce) {
        const Eigen::Vector3d p_G =
            actuator.pointInGround ? actuator.point : Eigen::Vector3d(data.p_GB[b] + data.R_GB[b] * actuator.point);
        F_G.tail<3>() = axis_G;
        addLinkForce(model, data, actuator.link, p_G, F_G, 1.0, tau);
        return;
    }
    // A pure couple: the same about every point.
    F_G.head<3>() = axis_G;
    addLinkForce(model, data, actuator.link, Eigen::Vector3d::Zero(), F_G, 1.0, tau);
    if (actuator.reactionLink != kGround)
        addLinkForce(model, data, actuator.reactionLink, Eigen::Vector3d::Zero(), F_G, -1.0, tau);
}

}  // namespace sinew

#pragma once
// A force or torque applied to links without a path: OpenSim's PointActuator (a force along a direction at
// a point of a link) and TorqueActuator (a torque about an axis on one link, its reaction on another), the
// residual actuators of static optimization on a floating root. Their generalized force per unit of
// actuation is the spatial force mapped through the links' Jacobians, tau = J^T F (docs/tensions-from-motion.md).
#include <Eigen/Core>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

struct BodyActuator {
    enum class Kind { PointForce, Torque };
    Kind kind = Kind::PointForce;
    // PointForce: the link pushed; Torque: the link turned (OpenSim's bodyA; kGround allowed, then only
    // the reaction acts).
    int link = 0;
    int reactionLink = kGround;  // Torque: the link that takes the opposite torque (bodyB); kGround: none
    // PointForce: the point of application, in the link's frame, or a ground point when pointInGround
    // (then the force acts on the link's material point that is there at this state, as OpenSim's
    // point_is_global).
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  // m
    bool pointInGround = false;
    // Direction of the force or axis of the torque, in the link's frame, or in ground when axisInGround
    // (OpenSim's force_is_global / torque_is_global). Normalised when used; it must not be zero.
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
    bool axisInGround = false;
};

// The generalized forces (nu) of one unit of actuation (1 N or 1 N m) at the configuration in `data`
// (calcPositionKinematics first). Allocates nothing.
void calcBodyActuatorGeneralizedForce(const Model& model, const Data& data, const BodyActuator& actuator,
                                      Eigen::Ref<Eigen::VectorXd> tau);

}  // namespace sinew

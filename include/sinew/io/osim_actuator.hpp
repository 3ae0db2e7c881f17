#pragma once
// OpenSim's scalar actuators that act without a path (CoordinateActuator, PointActuator, TorqueActuator),
// as found in a model's ForceSet or in a force-set file (the reserve and residual actuators of static
// optimization). Values absent from the XML take OpenSim's defaults, written here.
#include <Eigen/Core>
#include <limits>
#include <string>

namespace sinew {

// What every OpenSim ScalarActuator has: its force per unit control and the control's bounds.
struct OsimActuatorLimits {
    double optimalForce = 1;  // N or N m per unit control
    double minControl = -std::numeric_limits<double>::infinity();
    double maxControl = std::numeric_limits<double>::infinity();
    bool appliesForce = true;  // false: OpenSim leaves the actuator out (<appliesForce> or <isDisabled>)
};

// A generalized force on one coordinate: tau = optimalForce * control.
struct OsimCoordinateActuator {
    std::string name;
    std::string coordinate;  // coordinate name
    OsimActuatorLimits limits;
    std::string where;  // "file:line" of its XML element
};

// A force of optimalForce * control along `direction`, applied at `point` on `body`.
struct OsimPointActuator {
    std::string name;
    std::string body;                                          // body name, as written
    Eigen::Vector3d point = Eigen::Vector3d::Zero();            // m, in the body, or ground when pointIsGlobal
    bool pointIsGlobal = false;
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();       // in the body, or ground when forceIsGlobal
    bool forceIsGlobal = false;
    OsimActuatorLimits limits;
    std::string where;
};

// A torque of optimalForce * control about `axis`, on bodyA and its reaction on bodyB.
struct OsimTorqueActuator {
    std::string name;
    std::string bodyA, bodyB;                              // body names, as written
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();       // in ground when torqueIsGlobal, else in bodyA
    bool torqueIsGlobal = true;
    OsimActuatorLimits limits;
    std::string where;
};

}  // namespace sinew

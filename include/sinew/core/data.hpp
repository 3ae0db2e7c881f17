#pragma once
// Per-evaluation buffers for one Model, sized once at construction; the calc* algorithms fill them and
// allocate nothing. One Data per thread.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"

namespace sinew {

struct Data {
    explicit Data(const Model& model);

    // calcPositionKinematics, per link (numLinks):
    std::vector<Eigen::Matrix3d> R_GB;  // link frame orientation in ground
    std::vector<Eigen::Vector3d> p_GB;  // m, link frame origin in ground
    std::vector<Eigen::Matrix3d> R_GF;  // orientation of the link's joint frame F (on the parent) in ground
    std::vector<Eigen::Vector3d> p_GM;  // m, origin of the joint's M frame (the joint centre) in ground

    // calcVelocityKinematics, per link (numLinks):
    std::vector<Eigen::Vector3d> w_GB;  // rad/s, angular velocity in ground
    std::vector<Eigen::Vector3d> v_GB;  // m/s, velocity of the link frame origin in ground

    // calcWirePaths / calcWireSpeeds, per wire point (Model::getWirePoints().size()):
    std::vector<Eigen::Vector3d> p_GP;  // m, point position in ground
    std::vector<Eigen::Vector3d> v_GP;  // m/s, point velocity in ground
    // d(wire length)/d(p_GP) = e_in - e_out, the unit directions of the segments arriving at and leaving the
    // point (zero at the wire's ends and for zero-length segments); dimensionless.
    std::vector<Eigen::Vector3d> dLdp_GP;
    // Per wire (numWires):
    Eigen::VectorXd wireLength;  // m
    Eigen::VectorXd wireSpeed;   // m/s, positive when lengthening

    // Per link: spatial force [moment about the link's origin p_GB; force], ground axes. Moments about the
    // link rather than the ground origin keep their digits when the model is far from the origin. Filled
    // by calcWireLinkForces; tip-to-base passes use it as workspace.
    std::vector<SpatialVector> F_G;
};

}  // namespace sinew

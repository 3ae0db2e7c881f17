#include "sinew/core/data.hpp"

namespace sinew {

Data::Data(const Model& model) {
    const std::size_t links = static_cast<std::size_t>(model.getNumLinks());
    const std::size_t points = model.getWirePoints().size();
    R_GB.assign(links, Eigen::Matrix3d::Identity());
    p_GB.assign(links, Eigen::Vector3d::Zero());
    R_GF.assign(links, Eigen::Matrix3d::Identity());
    p_GM.assign(links, Eigen::Vector3d::Zero());
    w_GB.assign(links, Eigen::Vector3d::Zero());
    v_GB.assign(links, Eigen::Vector3d::Zero());
    p_GP.assign(points, Eigen::Vector3d::Zero());
    v_GP.assign(points, Eigen::Vector3d::Zero());
    dLdp_GP.assign(points, Eigen::Vector3d::Zero());
    wireLength = Eigen::VectorXd::Zero(model.getNumWires());
    wireSpeed = Eigen::VectorXd::Zero(model.getNumWires());
    F_G.assign(links, SpatialVector::Zero());
}

}  // namespace sinew

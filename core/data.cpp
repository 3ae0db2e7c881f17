#include "sinew/core/data.hpp"

#include <algorithm>

#include "sinew/core/wire_path.hpp"

namespace sinew {

Data::Data(const Model& model) {
    const std::size_t links = static_cast<std::size_t>(model.getNumLinks());
    const std::size_t points = model.getWirePoints().size();
    R_GB.assign(links, Eigen::Matrix3d::Identity());
    p_GB.assign(links, Eigen::Vector3d::Zero());
    R_GF.assign(links, Eigen::Matrix3d::Identity());
    p_GM.assign(links, Eigen::Vector3d::Zero());
    for (const Joint& joint : model.getJoints())
        H_FM.push_back(JointMotion::Zero(6, joint.type == JointType::Custom ? joint.nu : 0));
    w_GB.assign(links, Eigen::Vector3d::Zero());
    v_GB.assign(links, Eigen::Vector3d::Zero());
    alpha_GB.assign(links, Eigen::Vector3d::Zero());
    a_GB.assign(links, Eigen::Vector3d::Zero());
    p_GP.assign(points, Eigen::Vector3d::Zero());
    v_GP.assign(points, Eigen::Vector3d::Zero());
    dLdp_GP.assign(points, Eigen::Vector3d::Zero());
    wireLength = Eigen::VectorXd::Zero(model.getNumWires());
    wireSpeed = Eigen::VectorXd::Zero(model.getNumWires());
    q = model.getDefaultQ();
    u = Eigen::VectorXd::Zero(model.getNumU());
    int pathEntries = 0;
    for (const Wire& wire : model.getWires()) {
        wirePathStart.push_back(pathEntries);
        if (!wire.isPolyline()) pathEntries += wire.numPoints + 2 * static_cast<int>(wire.wraps.size());
    }
    wirePath.resize(static_cast<std::size_t>(pathEntries));
    wirePathSize.assign(wirePathStart.size(), 0);
    int gradientRows = 0, longestPath = 0;
    for (int w = 0; w < model.getNumWires(); ++w) {
        const bool numerical = isLengthDifferentiatedNumerically(model, w);
        wireGradientRow.push_back(numerical ? gradientRows++ : -1);
        const Wire& wire = model.getWire(w);
        if (numerical) longestPath = std::max(longestPath, wire.numPoints + 2 * static_cast<int>(wire.wraps.size()));
    }
    wireLengthGradient = Eigen::MatrixXd::Zero(gradientRows, model.getNumU());
    if (gradientRows > 0) {
        displacedR_GB = R_GB;
        displacedP_GB = p_GB;
        displacedP_GP = p_GP;
        displacedQ = q;
        displacedPath.resize(static_cast<std::size_t>(longestPath));
    }
    F_G.assign(links, SpatialVector::Zero());
    scratchF_G.assign(links, SpatialVector::Zero());
}

}  // namespace sinew

#include "sinew/core/wire_jacobian.hpp"

#include "sinew/core/kinematics.hpp"

namespace sinew {
namespace {

// Adds the spatial force (about the ground origin) of point force f_G applied at p_G to its link.
void addPointForce(Data& data, int link, const Eigen::Vector3d& p_G, const Eigen::Vector3d& f_G) {
    SpatialVector& F = data.F_G[static_cast<std::size_t>(link)];
    F.head<3>() += (p_G - data.p_GB[static_cast<std::size_t>(link)]).cross(f_G);
    F.tail<3>() += f_G;
}

}  // namespace

void calcWireJacobian(const Model& model, Data& data, Eigen::Ref<Eigen::MatrixXd> J) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    J.setZero();
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        for (int link : wire.supportLinks) data.F_G[static_cast<std::size_t>(link)].setZero();
        // Row w is the generalized force of unit "forces" dL/dp applied at the points (virtual work).
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k);
            addPointForce(data, points[kk].link, data.p_GP[kk], data.dLdp_GP[kk]);
        }
        for (int link : wire.supportLinks) {
            const Joint& joint = model.getJoint(link);
            const std::size_t b = static_cast<std::size_t>(link);
            double column[6];
            projectOntoJoint(joint, data.R_GF[b], data.p_GM[b], data.p_GB[b], data.F_G[b], column);
            for (int c = 0; c < joint.nu; ++c) J(w, joint.uStart + c) = column[c];
            addToParent(model, data, link);
        }
    }
}

void calcWireLinkForces(const Model& model, Data& data, const Eigen::VectorXd& tensions) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    for (SpatialVector& F : data.F_G) F.setZero();
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k);
            addPointForce(data, points[kk].link, data.p_GP[kk], -tensions[w] * data.dLdp_GP[kk]);
        }
    }
}

void calcWireGeneralizedForces(const Model& model, Data& data, const Eigen::VectorXd& tensions,
                               Eigen::Ref<Eigen::VectorXd> tau) {
    calcWireLinkForces(model, data, tensions);
    calcGeneralizedForcesFromLinkForces(model, data, tau);
}

}  // namespace sinew

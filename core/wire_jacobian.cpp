#include "sinew/core/wire_jacobian.hpp"

#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"

namespace sinew {
namespace {

// Adds the spatial force (about the link's origin) of point force f_G applied at p_G to its link's entry
// in F (per link).
void addPointForce(std::vector<SpatialVector>& F, const Data& data, int link, const Eigen::Vector3d& p_G,
                   const Eigen::Vector3d& f_G) {
    SpatialVector& F_link = F[static_cast<std::size_t>(link)];
    F_link.head<3>() += (p_G - data.p_GB[static_cast<std::size_t>(link)]).cross(f_G);
    F_link.tail<3>() += f_G;
}

// Adds to F (per link) the point forces `scale` * dL/dp at every point of wire w's path (tangent points on
// their objects' links).
void addWirePointForces(const Model& model, const Data& data, int w, double scale, std::vector<SpatialVector>& F) {
    const Wire& wire = model.getWire(w);
    if (wire.isPolyline()) {
        const std::vector<WirePoint>& points = model.getWirePoints();
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k);
            addPointForce(F, data, points[kk].link, data.p_GP[kk], scale * data.dLdp_GP[kk]);
        }
        return;
    }
    const Data::WirePathPoint* path = data.wirePath.data() + data.wirePathStart[static_cast<std::size_t>(w)];
    for (int i = 0; i < data.wirePathSize[static_cast<std::size_t>(w)]; ++i)
        addPointForce(F, data, path[i].link, path[i].p_G, scale * path[i].dLdp_G);
}

// Calls f(u index, dL/du through the point's own motion) for each moving component on wire w's path:
// dL/dp . R_GB e_axis dp_B[axis]/dq, the term a moving point adds to its coordinate's column.
template <typename F>
void forEachMotionTerm(const Model& model, const Data& data, int w, F&& f) {
    const Wire& wire = model.getWire(w);
    if (wire.motions.empty()) return;
    const Data::WirePathPoint* path = data.wirePath.data() + data.wirePathStart[static_cast<std::size_t>(w)];
    for (int i = 0; i < data.wirePathSize[static_cast<std::size_t>(w)]; ++i) {
        if (path[i].point < 0) continue;
        for (const WirePointMotion& m : wire.motions) {
            if (m.point != path[i].point) continue;
            const Eigen::Matrix3d& R_GB = data.R_GB[static_cast<std::size_t>(path[i].link)];
            f(m.u, path[i].dLdp_G.dot(R_GB.col(m.axis)) * calcWirePointMotionRate(model, m, data.q));
        }
    }
}

}  // namespace

void calcWireJacobian(const Model& model, Data& data, Eigen::Ref<Eigen::MatrixXd> J) {
    J.setZero();
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        const int row = data.wireGradientRow[static_cast<std::size_t>(w)];
        if (row >= 0) {
            J.row(w) = data.wireLengthGradient.row(row);
            continue;
        }
        for (int link : wire.supportLinks) data.scratchF_G[static_cast<std::size_t>(link)].setZero();
        // Row w is the generalized force of unit "forces" dL/dp applied at the points (virtual work).
        addWirePointForces(model, data, w, 1.0, data.scratchF_G);
        for (int link : wire.supportLinks) {
            const Joint& joint = model.getJoint(link);
            const std::size_t b = static_cast<std::size_t>(link);
            double column[6];
            projectOntoJoint(joint, data, link, data.p_GB[b], data.scratchF_G[b], column);
            for (int c = 0; c < joint.nu; ++c) J(w, joint.uStart + c) = column[c];
            addToParent(model, data, link);
        }
        forEachMotionTerm(model, data, w, [&](int u, double dLdu) { J(w, u) += dLdu; });
    }
}

void calcWireLinkForces(const Model& model, Data& data, const Eigen::VectorXd& tensions) {
    for (SpatialVector& F : data.F_G) F.setZero();
    for (int w = 0; w < model.getNumWires(); ++w)
        if (data.wireGradientRow[static_cast<std::size_t>(w)] < 0)
            addWirePointForces(model, data, w, -tensions[w], data.F_G);
}

void addWireCoordinateForces(const Model& model, const Data& data, const Eigen::VectorXd& tensions,
                             Eigen::Ref<Eigen::VectorXd> tau) {
    for (int w = 0; w < model.getNumWires(); ++w) {
        const int row = data.wireGradientRow[static_cast<std::size_t>(w)];
        if (row >= 0)
            tau -= tensions[w] * data.wireLengthGradient.row(row).transpose();
        else
            forEachMotionTerm(model, data, w, [&](int u, double dLdu) { tau[u] -= tensions[w] * dLdu; });
    }
}

void calcWireGeneralizedForces(const Model& model, Data& data, const Eigen::VectorXd& tensions,
                               Eigen::Ref<Eigen::VectorXd> tau) {
    calcWireLinkForces(model, data, tensions);
    data.scratchF_G = data.F_G;  // the projection consumes its input; F_G keeps the wires' link forces
    calcGeneralizedForcesFromLinkForces(model, data, tau);
    addWireCoordinateForces(model, data, tensions, tau);
}

}  // namespace sinew

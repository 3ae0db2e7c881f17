#include "sinew/core/wire_jacobian.hpp"

#include <algorithm>
#include <string>

#include "sinew/core/error.hpp"
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

// Calls f(link, p_G, dL/dp_G) for every point of wire w's path (tangent points on their objects' links).
template <typename F>
void forEachWirePoint(const Model& model, const Data& data, const Wire& wire, int w, F&& f) {
    if (wire.isPolyline()) {
        const std::vector<WirePoint>& points = model.getWirePoints();
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k);
            f(points[kk].link, data.p_GP[kk], data.dLdp_GP[kk]);
        }
        return;
    }
    const Data::WirePathPoint* path = data.wirePath.data() + data.wirePathStart[static_cast<std::size_t>(w)];
    for (int i = 0; i < data.wirePathSize[static_cast<std::size_t>(w)]; ++i) f(path[i].link, path[i].p_G, path[i].dLdp_G);
}

// Adds to F (per link) the point forces `scale` * dL/dp at every point of wire w's path.
void addWirePointForces(const Model& model, const Data& data, int w, double scale, std::vector<SpatialVector>& F) {
    forEachWirePoint(model, data, model.getWire(w), w, [&](int link, const Eigen::Vector3d& p_G, const Eigen::Vector3d& dLdp_G) {
        addPointForce(F, data, link, p_G, scale * dLdp_G);
    });
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

// Row w of J (a wire off the numerical-gradient path): set(uStart, nu, values) once for each span link's
// joint, then add(u, value) for its moving points' own terms. Row w is the generalized force of unit
// "forces" dL/dp at the points (virtual work), summed tip to base with their moments about ground's origin,
// so they move up the tree without a shift; the anchors at or above the span's top move rigidly and add
// nothing. (Moments about the wire's first point instead keep more digits far from the origin, but moved the
// QP of WireProblem.LpAndQpAreOptimalOverAMotionOfAFloatingModel to a dual KKT residual of 1.01e-6 on two
// frames, docs/wire-jacobian.md.)
template <typename Set, typename Add>
void calcWireJacobianRow(const Model& model, Data& data, int w, Set&& set, Add&& add) {
    const Wire& wire = model.getWire(w);
    std::vector<SpatialVector>& W = data.scratchF_G;
    // Only the span links and their top (the lowest common link, which takes the last sum) are touched, so
    // a wire costs its span, not its depth in the tree. A support link lies among them iff its index is at
    // least the top's (parents' indices are lower).
    const int* links = model.getSupportLinks().data() + wire.firstSupportLink;
    const int touched = std::min(wire.numSupportLinks, wire.numSpanLinks + 1);
    const int top = touched == 0 ? kGround : links[touched - 1];
    for (int i = 0; i < touched; ++i) W[static_cast<std::size_t>(links[i])].setZero();
    forEachWirePoint(model, data, wire, w, [&](int link, const Eigen::Vector3d& p_G, const Eigen::Vector3d& dLdp_G) {
        if (link < top) return;  // above the span: moves with every anchor
        SpatialVector& W_link = W[static_cast<std::size_t>(link)];
        W_link.head<3>() += p_G.cross(dLdp_G);
        W_link.tail<3>() += dLdp_G;
    });
    for (int i = 0; i < wire.numSpanLinks; ++i) {
        const int link = links[i];
        const Joint& joint = model.getJoint(link);
        const SpatialVector& W_link = W[static_cast<std::size_t>(link)];
        double column[6];
        if (joint.type == JointType::Ball) {  // most span links: H^T W inline, the moment taken about the centre
            const std::size_t b = static_cast<std::size_t>(link);
            Eigen::Map<Eigen::Vector3d>{column} =
                data.R_GF[b].transpose() * (W_link.head<3>() - data.p_GM[b].cross(W_link.tail<3>()));
        } else {
            projectOntoJoint(joint, data, link, Eigen::Vector3d::Zero(), W_link, column);
        }
        if (joint.nu > 0) set(joint.uStart, joint.nu, column);
        if (joint.parent != kGround) W[static_cast<std::size_t>(joint.parent)] += W_link;
    }
    forEachMotionTerm(model, data, w, std::forward<Add>(add));
}

}  // namespace

void calcWireJacobian(const Model& model, Data& data, Eigen::Ref<Eigen::MatrixXd> J) {
    J.setZero();
    for (int w = 0; w < model.getNumWires(); ++w) {
        const int row = data.wireGradientRow[static_cast<std::size_t>(w)];
        if (row >= 0) {
            J.row(w) = data.wireLengthGradient.row(row);
            continue;
        }
        calcWireJacobianRow(
            model, data, w, [&](int uStart, int nu, const double* values) {
                for (int c = 0; c < nu; ++c) J(w, uStart + c) = values[c];
            },
            [&](int u, double value) { J(w, u) += value; });
    }
}

Eigen::SparseMatrix<double> makeWireJacobianTransposePattern(const Model& model) {
    std::vector<Eigen::Triplet<double>> entries;
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        for (int i = 0; i < wire.numSpanLinks; ++i) {
            const Joint& joint = model.getJoint(model.getSupportLinks()[static_cast<std::size_t>(wire.firstSupportLink + i)]);
            for (int c = 0; c < joint.nu; ++c) entries.emplace_back(joint.uStart + c, w, 0.0);
        }
        for (const WirePointMotion& m : wire.motions) entries.emplace_back(m.u, w, 0.0);
    }
    Eigen::SparseMatrix<double> Jt(model.getNumU(), model.getNumWires());
    Jt.setFromTriplets(entries.begin(), entries.end(), [](double a, double) { return a; });
    Jt.makeCompressed();
    return Jt;
}

void calcWireJacobianTranspose(const Model& model, Data& data, Eigen::SparseMatrix<double>& Jt) {
    if (Jt.rows() != model.getNumU() || Jt.cols() != model.getNumWires() || !Jt.isCompressed())
        throw Error("wire Jacobian: the sparse J^T is " + std::to_string(Jt.rows()) + " x " + std::to_string(Jt.cols()) +
                    (Jt.isCompressed() ? "" : ", uncompressed") + "; expected the nu x numWires matrix of "
                    "makeWireJacobianTransposePattern");
    double* values = Jt.valuePtr();
    const int* rows = Jt.innerIndexPtr();
    const int* columnStart = Jt.outerIndexPtr();
    for (int w = 0; w < model.getNumWires(); ++w) {
        const int* first = rows + columnStart[w];
        const int* last = rows + columnStart[w + 1];
        // The span joints' entries are overwritten; only a moving point's own coordinate is added to.
        if (!model.getWire(w).motions.empty()) std::fill(values + columnStart[w], values + columnStart[w + 1], 0.0);
        // The pattern holds every speed the row can touch; the lookups are within one wire's few entries.
        auto entry = [&](int u) -> double& {
            const int* it = std::lower_bound(first, last, u);
            if (it == last || *it != u)
                throw Error("wire Jacobian: wire '" + model.getWire(w).name + "' reaches speed " + std::to_string(u) +
                            ", outside the sparse J^T's pattern (made for another model?)");
            return values[it - rows];
        };
        const int row = data.wireGradientRow[static_cast<std::size_t>(w)];
        if (row >= 0) {
            for (const int* it = first; it != last; ++it) values[it - rows] = data.wireLengthGradient(row, *it);
            continue;
        }
        // A joint's speeds are consecutive rows of the column. A ball's three are written inline: a copy of
        // run-time length compiles to a memmove call per joint, 8 % of the pass on the whole body.
        calcWireJacobianRow(
            model, data, w,
            [&](int uStart, int nu, const double* block) {
                double* column = &entry(uStart);
                if (nu == 3)
                    column[0] = block[0], column[1] = block[1], column[2] = block[2];
                else
                    std::copy(block, block + nu, column);
            },
            [&](int u, double value) { entry(u) += value; });
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

#include "sinew/tensions/contact_columns.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"

namespace sinew {
namespace {

Eigen::Vector3d calcVertex_G(const Data& data, int link, const Eigen::Vector3d& p_B) {
    const std::size_t b = static_cast<std::size_t>(link);
    return data.p_GB[b] + data.R_GB[b] * p_B;
}

}  // namespace

void calcPointForceGeneralizedForce(const Model& model, const Data& data, int link, const Eigen::Vector3d& p_B,
                                    const Eigen::Vector3d& F_G, Eigen::Ref<Eigen::VectorXd> tau) {
    tau.setZero();
    const Eigen::Vector3d p_G = calcVertex_G(data, link, p_B);
    SpatialVector F;
    F << Eigen::Vector3d::Zero(), F_G;  // about the point itself
    // Each joint from the link to the root carries the force: H^T F (docs/wire-jacobian.md).
    for (int l = link; l != kGround; l = model.getJoint(l).parent) {
        const Joint& joint = model.getJoint(l);
        projectOntoJoint(joint, data, l, p_G, F, tau.data() + joint.uStart);
    }
}

ContactColumns::ContactColumns(const Model& model, int pyramidEdges, double cost)
    : model_(model), numEdges_(pyramidEdges), cost_(cost), inContact_(model.getContacts().size(), 0),
      unitForces_(model.getNumU(), 3) {
    if (!(cost >= 0) || !std::isfinite(cost))
        throw Error("contact: the LP cost of a contact force must be finite and >= 0, got " + std::to_string(cost));
    if (pyramidEdges < 3)
        throw Error("contact: the friction pyramid needs at least 3 edges, got " + std::to_string(pyramidEdges));
    const double g = model.getGravity().norm();
    if (!(g > 0)) throw Error("contact: model '" + model.getName() + "' has no gravity, so the ground has no 'up'");
    normal_ = -model.getGravity() / g;
    // Any two axes of the ground plane: the pyramid's edges are symmetric about n, whichever are chosen.
    Eigen::Index least;
    normal_.cwiseAbs().minCoeff(&least);
    const Eigen::Vector3d t1 = normal_.cross(Eigen::Vector3d::Unit(least)).normalized();
    const Eigen::Vector3d t2 = normal_.cross(t1);
    for (const Contact& contact : model.getContacts()) {
        firstColumn_.push_back(numColumns_);
        numColumns_ += static_cast<int>(contact.sole_B.size()) * numEdges_;
        for (int k = 0; k < numEdges_; ++k) {
            const double theta = 2 * M_PI * k / numEdges_;
            edges_.push_back(normal_ + contact.friction * (std::cos(theta) * t1 + std::sin(theta) * t2));
        }
    }
}

void ContactColumns::setInContact(const std::vector<char>& inContact) {
    if (inContact.size() != inContact_.size())
        throw Error("contact: " + std::to_string(inContact.size()) + " contact flags for " +
                    std::to_string(inContact_.size()) + " contacts");
    std::copy(inContact.begin(), inContact.end(), inContact_.begin());
}

const Eigen::Vector3d& ContactColumns::getEdge(int contact, int k) const {
    return edges_[static_cast<std::size_t>(contact * numEdges_ + k)];
}

void ContactColumns::addPattern(int columnOffset, std::vector<Eigen::Triplet<double>>& entries) const {
    for (std::size_t c = 0; c < model_.getContacts().size(); ++c) {
        const Contact& contact = model_.getContacts()[c];
        const int columns = static_cast<int>(contact.sole_B.size()) * numEdges_;
        for (int l = contact.link; l != kGround; l = model_.getJoint(l).parent) {
            const Joint& joint = model_.getJoint(l);
            for (int j = 0; j < columns; ++j)
                for (int r = 0; r < joint.nu; ++r) entries.emplace_back(joint.uStart + r, columnOffset + firstColumn_[c] + j, 1.0);
        }
    }
}

void ContactColumns::markEqualityRows(std::vector<bool>& isEquality) const {
    for (std::size_t c = 0; c < model_.getContacts().size(); ++c) {
        if (!inContact_[c]) continue;
        int root = model_.getContacts()[c].link;
        while (model_.getJoint(root).parent != kGround) root = model_.getJoint(root).parent;
        const Joint& joint = model_.getJoint(root);
        if (joint.type != JointType::Free) continue;
        for (int k = 3; k < 6; ++k) isEquality[static_cast<std::size_t>(joint.uStart + k)] = true;
    }
}

void ContactColumns::update(const Data& data, const std::vector<char>& inContact, int columnOffset,
                            Eigen::SparseMatrix<double>& A) {
    for (std::size_t c = 0; c < model_.getContacts().size(); ++c) {
        const Contact& contact = model_.getContacts()[c];
        for (std::size_t v = 0; v < contact.sole_B.size(); ++v) {
            if (inContact[c])
                for (int axis = 0; axis < 3; ++axis)
                    calcPointForceGeneralizedForce(model_, data, contact.link, contact.sole_B[v],
                                                   Eigen::Vector3d::Unit(axis), unitForces_.col(axis));
            for (int k = 0; k < numEdges_; ++k) {
                const Eigen::Vector3d& d = getEdge(static_cast<int>(c), k);
                const int column = columnOffset + firstColumn_[c] + static_cast<int>(v) * numEdges_ + k;
                for (Eigen::SparseMatrix<double>::InnerIterator it(A, column); it; ++it)
                    it.valueRef() = inContact[c] ? unitForces_.row(it.row()).dot(d) : 0.0;
            }
        }
    }
}

void ContactColumns::setVariables(double wireWeight, Eigen::Ref<Eigen::VectorXd> lower, Eigen::Ref<Eigen::VectorXd> upper,
                                  Eigen::Ref<Eigen::VectorXd> cost, Eigen::Ref<Eigen::VectorXd> weight) const {
    lower.setZero();
    cost.setConstant(cost_);
    weight.setConstant(wireWeight);
    for (std::size_t c = 0; c < model_.getContacts().size(); ++c) {
        const int n = static_cast<int>(model_.getContacts()[c].sole_B.size()) * numEdges_;
        upper.segment(firstColumn_[c], n).setConstant(inContact_[c] ? std::numeric_limits<double>::infinity() : 0.0);
    }
}

ContactWrench ContactColumns::calcWrench(const Data& data, int contact, const Eigen::Ref<const Eigen::VectorXd>& beta) const {
    const Contact& c = model_.getContacts()[static_cast<std::size_t>(contact)];
    const auto vertexForce = [&](std::size_t v) {
        Eigen::Vector3d f = Eigen::Vector3d::Zero();
        const int first = firstColumn_[static_cast<std::size_t>(contact)] + static_cast<int>(v) * numEdges_;
        for (int k = 0; k < numEdges_; ++k) f += beta[first + k] * getEdge(contact, k);
        return f;
    };
    ContactWrench wrench;
    double normalForce = 0;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    for (std::size_t v = 0; v < c.sole_B.size(); ++v) {
        const Eigen::Vector3d f = vertexForce(v);
        wrench.force += f;
        normalForce += normal_.dot(f);
        weighted += normal_.dot(f) * calcVertex_G(data, c.link, c.sole_B[v]);
    }
    wrench.centreOfPressure = normalForce > 0 ? Eigen::Vector3d(weighted / normalForce)
                                              : calcVertex_G(data, c.link, c.sole_B[0]);
    for (std::size_t v = 0; v < c.sole_B.size(); ++v)
        wrench.moment += (calcVertex_G(data, c.link, c.sole_B[v]) - wrench.centreOfPressure).cross(vertexForce(v));
    return wrench;
}

}  // namespace sinew

#include "sinew/tensions/unactuated_rows.hpp"

#include <algorithm>
#include <cmath>

#include "sinew/core/kinematics.hpp"

namespace sinew {

UnactuatedRows::UnactuatedRows(const Model& model, double threshold)
    : model_(model), threshold_(threshold), rigidMotion_(Eigen::MatrixXd::Zero(model.getNumU(), 6)),
      rowSize_(Eigen::VectorXd::Zero(model.getNumU())), unbalanced_(Eigen::VectorXd::Zero(model.getNumU())) {
    for (int link = 0; link < model.getNumLinks(); ++link)
        if (model.getLink(link).isVirtual && model.getJoint(link).parent == kGround) virtualLinksOnGround_.push_back(link);
    virtualLinkMotion_.resize(virtualLinksOnGround_.size());
}

// The largest |column . r| over the internal columns, r the rigid motion along each of the root's
// mobilities, into rowSize_; r . tau into unbalanced_.
void UnactuatedRows::judgeByRigidMotion(const Data& data, const DistributionProblem& problem,
                                        const Eigen::VectorXd& tau, int rootLink, int externalBegin, int externalEnd) {
    const Joint& joint = model_.getJoint(rootLink);
    const Eigen::Vector3d& p_ref = data.p_GM[static_cast<std::size_t>(rootLink)];
    const JointMotion H_root = calcJointMotion_G(joint, data, rootLink, p_ref);
    for (std::size_t v = 0; v < virtualLinksOnGround_.size(); ++v) {
        const int link = virtualLinksOnGround_[v];
        virtualLinkMotion_[v].compute(calcJointMotion_G(model_.getJoint(link), data, link, p_ref));
    }
    // Column c of rigidMotion_: the u of the rigid motion along mobility c; one pass over A for all of them.
    rigidMotion_.setZero();  // the columns past the root's mobilities stay zero, so whole rows can be added
    for (int c = 0; c < joint.nu; ++c) {
        rigidMotion_(joint.uStart + c, c) = 1;
        for (std::size_t v = 0; v < virtualLinksOnGround_.size(); ++v) {
            const Joint& free = model_.getJoint(virtualLinksOnGround_[v]);
            rigidMotion_.block(free.uStart, c, free.nu, 1) = virtualLinkMotion_[v].solve(SpatialVector(H_root.col(c)));
        }
    }
    SpatialVector actuation = SpatialVector::Zero(), along;
    for (Eigen::Index k = 0; k < problem.A.outerSize(); ++k) {
        if (k >= externalBegin && k < externalEnd) continue;
        along.setZero();
        for (Eigen::SparseMatrix<double>::InnerIterator it(problem.A, k); it; ++it)
            along += it.value() * rigidMotion_.row(it.row()).transpose();
        actuation = actuation.cwiseMax(along.cwiseAbs());
    }
    for (int c = 0; c < joint.nu; ++c) {
        rowSize_[joint.uStart + c] = actuation[c];
        unbalanced_[joint.uStart + c] = rigidMotion_.col(c).dot(tau);
    }
}

double UnactuatedRows::apply(const Data& data, const Eigen::VectorXd& tau, int externalBegin, int externalEnd,
                             DistributionProblem& problem, std::vector<char>& unactuated) {
    const Eigen::Index nu = problem.getNumRows();
    const auto addEntries = [&](Eigen::Index begin, Eigen::Index end) {
        for (Eigen::Index k = begin; k < end; ++k)
            for (Eigen::SparseMatrix<double>::InnerIterator it(problem.A, k); it; ++it)
                rowSize_[it.row()] = std::max(rowSize_[it.row()], std::abs(it.value()));  // finite: validated
    };
    rowSize_.setZero();
    unbalanced_ = tau;
    addEntries(0, externalBegin);
    addEntries(externalEnd, problem.A.outerSize());
    if (!virtualLinksOnGround_.empty())
        for (int link = 0; link < model_.getNumLinks(); ++link) {
            const Joint& joint = model_.getJoint(link);
            if (joint.parent != kGround || model_.getLink(link).isVirtual) continue;
            judgeByRigidMotion(data, problem, tau, link, externalBegin, externalEnd);
        }
    addEntries(externalBegin, externalEnd);
    const double threshold = threshold_ * rowSize_.maxCoeff();
    double residual = 0;
    for (Eigen::Index i = 0; i < nu; ++i) {
        const bool isUnactuated = !(rowSize_[i] > threshold);
        unactuated[static_cast<std::size_t>(i)] = isUnactuated;
        if (isUnactuated) {
            residual += unbalanced_[i] * unbalanced_[i];
            problem.target[i] = tau[i] - unbalanced_[i];
        }
    }
    return std::sqrt(residual);
}

}  // namespace sinew

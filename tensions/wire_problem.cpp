#include "sinew/tensions/wire_problem.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/core/loop_force_columns.hpp"
#include "sinew/core/wire_jacobian.hpp"

namespace sinew {
namespace {

// The DOF rows of `link`'s joint and of all its ancestors' joints: what a force on the link can reach.
void addPathToRoot(const Model& model, int link, std::vector<bool>& rows) {
    for (; link != kGround; link = model.getJoint(link).parent) {
        const Joint& joint = model.getJoint(link);
        for (int k = 0; k < joint.nu; ++k) rows[static_cast<std::size_t>(joint.uStart + k)] = true;
    }
}

// Zeroes the entries of column j that are roundoff (below 1e-12 of its largest). Internal forces give the
// free root's rows exactly zero in exact arithmetic and ~1e-17 in floating point; left in, such rows would
// look like DOFs needing enormous tensions, and an LP's row scaling would blow them up.
void dropRoundoff(Eigen::SparseMatrix<double>& A, int j) {
    double largest = 0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) largest = std::max(largest, std::abs(it.value()));
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
        if (std::abs(it.value()) <= 1e-12 * largest) it.valueRef() = 0;
}

}  // namespace

WireProblemBuilder::WireProblemBuilder(const Model& model, Eigen::VectorXd maxTension, WireProblemOptions options,
                                       std::vector<std::shared_ptr<ProblemColumns>> columns)
    : model_(model), maxTension_(std::move(maxTension)), options_(options), columns_(std::move(columns)) {
    if (maxTension_.size() != model.getNumWires())
        throw Error("wire problem: " + std::to_string(maxTension_.size()) + " maximum tensions for " +
                    std::to_string(model.getNumWires()) + " wires");
    for (int w = 0; w < model.getNumWires(); ++w)
        if (!(maxTension_[w] > 0) || !std::isfinite(maxTension_[w]))
            throw Error("wire problem: wire '" + model.getWire(w).name + "' has maximum tension " +
                        std::to_string(maxTension_[w]) + " N, expected a finite value > 0");
    const int nu = model.getNumU(), numWires = model.getNumWires();
    virtualLinkRows_.assign(static_cast<std::size_t>(nu), false);
    for (int link = 0; link < model.getNumLinks(); ++link) {
        if (!model.getLink(link).isVirtual) continue;
        const Joint& joint = model.getJoint(link);
        for (int k = 0; k < joint.nu; ++k) virtualLinkRows_[static_cast<std::size_t>(joint.uStart + k)] = true;
    }
    std::vector<Eigen::Triplet<double>> entries;
    std::vector<bool> rows;
    const auto addColumn = [&](int column) {
        for (int i = 0; i < nu; ++i)
            if (rows[static_cast<std::size_t>(i)]) entries.emplace_back(i, column, 1.0);
    };
    // The wires' columns are -J^T's, in its pattern, so a sparse J^T is copied value for value.
    const Eigen::SparseMatrix<double> wirePattern = makeWireJacobianTransposePattern(model);
    for (int w = 0; w < numWires; ++w)
        for (Eigen::SparseMatrix<double>::InnerIterator it(wirePattern, w); it; ++it) entries.emplace_back(it.row(), w, 1.0);
    blockStart_.assign(1, numWires);
    for (const std::shared_ptr<ProblemColumns>& block : columns_) {
        block->addPattern(blockStart_.back(), entries);
        blockStart_.push_back(blockStart_.back() + block->count());
    }
    const int loopStart = getBlocksEnd();
    for (int l = 0; l < model.getNumLoops(); ++l) {
        rows.assign(static_cast<std::size_t>(nu), false);
        addPathToRoot(model, model.getLoop(l).linkA, rows);
        addPathToRoot(model, model.getLoop(l).linkB, rows);
        for (int c = 0; c < 3; ++c) addColumn(loopStart + 3 * l + c);
    }
    pattern_.resize(nu, loopStart + 3 * model.getNumLoops());
    pattern_.setFromTriplets(entries.begin(), entries.end());
    pattern_.makeCompressed();
}

DistributionProblem WireProblemBuilder::makeProblem() const {
    const int nu = model_.getNumU(), numWires = model_.getNumWires();
    DistributionProblem problem;
    problem.A = pattern_;
    problem.A.coeffs().setZero();
    problem.numFree = 3 * model_.getNumLoops();
    const int numBounded = getBlocksEnd();
    problem.lower.setZero(numBounded);
    problem.upper.setZero(numBounded);
    problem.upper.head(numWires) = maxTension_;
    problem.cost.setConstant(numBounded, options_.wireCost);
    problem.weight.setOnes(numBounded);
    for (int b = 0; b < getNumBlocks(); ++b) {
        const int start = getBlockStart(b), size = columns_[static_cast<std::size_t>(b)]->count();
        columns_[static_cast<std::size_t>(b)]->setVariables(1.0, problem.lower.segment(start, size),
                                                            problem.upper.segment(start, size),
                                                            problem.cost.segment(start, size),
                                                            problem.weight.segment(start, size));
    }
    problem.target.setZero(nu);
    problem.tolerance.setConstant(nu, options_.torqueTolerance);
    problem.isEquality = virtualLinkRows_;
    return problem;
}

void WireProblemBuilder::checkFrame(const Eigen::VectorXd& tau, const DistributionProblem& problem) const {
    if (tau.size() != model_.getNumU())
        throw Error("wire problem: tau has " + std::to_string(tau.size()) + " entries, expected nu = " +
                    std::to_string(model_.getNumU()));
    if (problem.A.nonZeros() != pattern_.nonZeros() || problem.A.cols() != pattern_.cols() || !problem.A.isCompressed())
        throw Error("wire problem: the problem was not made by this builder's makeProblem()");
}

void WireProblemBuilder::update(Data& data, const Eigen::MatrixXd& J, const Eigen::VectorXd& tau,
                                DistributionProblem& problem) const {
    const int nu = model_.getNumU(), numWires = model_.getNumWires();
    if (J.rows() != numWires || J.cols() != nu)
        throw Error("wire problem: J is " + std::to_string(J.rows()) + " x " + std::to_string(J.cols()) +
                    ", expected numWires x nu = " + std::to_string(numWires) + " x " + std::to_string(nu));
    checkFrame(tau, problem);
    for (int w = 0; w < numWires; ++w)
        for (Eigen::SparseMatrix<double>::InnerIterator it(problem.A, w); it; ++it) it.valueRef() = -J(w, it.row());
    updateAfterWires(data, tau, problem);
}

void WireProblemBuilder::update(Data& data, const Eigen::SparseMatrix<double>& Jt, const Eigen::VectorXd& tau,
                                DistributionProblem& problem) const {
    const int numWires = model_.getNumWires();
    checkFrame(tau, problem);
    const bool samePattern = Jt.rows() == model_.getNumU() && Jt.cols() == numWires && Jt.isCompressed() &&
                             std::equal(Jt.outerIndexPtr(), Jt.outerIndexPtr() + numWires + 1, problem.A.outerIndexPtr()) &&
                             std::equal(Jt.innerIndexPtr(), Jt.innerIndexPtr() + Jt.nonZeros(), problem.A.innerIndexPtr());
    if (!samePattern)
        throw Error("wire problem: the sparse J^T (" + std::to_string(Jt.rows()) + " x " + std::to_string(Jt.cols()) +
                    ") is not in this model's pattern; make it by makeWireJacobianTransposePattern");
    std::transform(Jt.valuePtr(), Jt.valuePtr() + Jt.nonZeros(), problem.A.valuePtr(), std::negate<double>());
    updateAfterWires(data, tau, problem);
}

void WireProblemBuilder::updateAfterWires(Data& data, const Eigen::VectorXd& tau, DistributionProblem& problem) const {
    const int nu = model_.getNumU(), numWires = model_.getNumWires();
    double meanSquaredArm = 0;
    for (int w = 0; w < numWires; ++w) {
        dropRoundoff(problem.A, w);
        meanSquaredArm += problem.A.col(w).squaredNorm();
    }
    meanSquaredArm = numWires ? meanSquaredArm / numWires : 0;
    const double wireWeight = options_.regularization * (meanSquaredArm > 0 ? meanSquaredArm : 1.0);
    problem.weight.head(numWires).setConstant(wireWeight);
    problem.isEquality = virtualLinkRows_;
    for (int b = 0; b < getNumBlocks(); ++b) {
        ProblemColumns& block = *columns_[static_cast<std::size_t>(b)];
        const int start = getBlockStart(b), size = block.count();
        block.update(data, start, problem.A);
        block.markEqualityRows(problem.isEquality);
        block.setVariables(wireWeight, problem.lower.segment(start, size), problem.upper.segment(start, size),
                           problem.cost.segment(start, size), problem.weight.segment(start, size));
    }
    // Loop columns: the transposed loop-constraint Jacobian, in the fixed pattern.
    const int loopStart = getBlocksEnd();
    Eigen::MatrixXd columns(nu, 3);
    for (int l = 0; l < model_.getNumLoops(); ++l) {
        calcLoopForceColumns(model_, data, l, columns);
        for (int c = 0; c < 3; ++c) {
            const int j = loopStart + 3 * l + c;
            for (Eigen::SparseMatrix<double>::InnerIterator it(problem.A, j); it; ++it) it.valueRef() = columns(it.row(), c);
            dropRoundoff(problem.A, j);
        }
    }
    problem.target = tau;
}

}  // namespace sinew

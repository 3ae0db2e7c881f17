#include "sinew/tensions/static_optimization.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew {

void validateStaticOptimizationSettings(StaticOptimizationSettings& settings) {
    const Eigen::Index numWires = settings.maxIsometricForce.size();
    if (settings.minActivation.size() == 0) settings.minActivation.setZero(numWires);
    if (settings.maxActivation.size() == 0) settings.maxActivation.setOnes(numWires);
    if (settings.minActivation.size() != numWires || settings.maxActivation.size() != numWires)
        throw Error("static optimization: " + std::to_string(settings.minActivation.size()) + " minimum and " +
                    std::to_string(settings.maxActivation.size()) + " maximum activations for " +
                    std::to_string(numWires) + " wires");
    for (Eigen::Index w = 0; w < numWires; ++w) {
        const std::string at = "wire " + std::to_string(w);
        if (!(settings.maxIsometricForce[w] > 0) || !std::isfinite(settings.maxIsometricForce[w]))
            throw Error("static optimization: " + at + " has max isometric force " +
                        std::to_string(settings.maxIsometricForce[w]) + ", expected a finite value > 0");
        if (!(settings.minActivation[w] <= settings.maxActivation[w]))
            throw Error("static optimization: " + at + " has activation bounds [" +
                        std::to_string(settings.minActivation[w]) + ", " + std::to_string(settings.maxActivation[w]) +
                        "], expected min <= max");
    }
    for (const ReserveActuator& reserve : settings.reserves) checkReserveLimits(reserve);
}

StaticOptimization::StaticOptimization(StaticOptimizationSettings settings, ActiveSetOptions options)
    : settings_(std::move(settings)), solver_(settings_.activationExponent, options) {
    validateStaticOptimizationSettings(settings_);
}

bool StaticOptimization::hasPatternOf(const DistributionProblem& wireProblem, bool denseReserves) const {
    const Eigen::SparseMatrix<double>& A = wireProblem.A;
    return denseReserves == denseReserves_ && A.isCompressed() && A.rows() == wirePattern_.rows() &&
           A.cols() == wirePattern_.cols() && A.nonZeros() == wirePattern_.nonZeros() &&
           std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1, wirePattern_.outerIndexPtr()) &&
           std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), wirePattern_.innerIndexPtr());
}

void StaticOptimization::buildPattern(const DistributionProblem& wireProblem, bool denseReserves) {
    const int numWires = static_cast<int>(settings_.maxIsometricForce.size());
    const int numReserves = static_cast<int>(settings_.reserves.size());
    const int rows = wireProblem.getNumRows(), numBounded = numWires + numReserves;
    wirePattern_ = wireProblem.A;
    wirePattern_.makeCompressed();
    denseReserves_ = denseReserves;
    // Each frame copies the wire problem's values column by column into problem_.A, whose rows are sorted.
    for (int j = 0; j < wirePattern_.cols(); ++j) {
        const auto* rowIndex = wirePattern_.innerIndexPtr();
        if (!std::is_sorted(rowIndex + wirePattern_.outerIndexPtr()[j], rowIndex + wirePattern_.outerIndexPtr()[j + 1]))
            throw Error("static optimization: column " + std::to_string(j) + " of the wire problem has unsorted rows");
    }
    std::vector<Eigen::Triplet<double>> entries;
    for (int j = 0; j < wirePattern_.cols(); ++j)
        for (Eigen::SparseMatrix<double>::InnerIterator it(wirePattern_, j); it; ++it)
            entries.emplace_back(it.row(), j < numWires ? j : j + numReserves, 0.0);
    for (int r = 0; r < numReserves; ++r) {
        const ReserveActuator& reserve = settings_.reserves[static_cast<std::size_t>(r)];
        if (!(denseReserves && reserve.body)) {
            entries.emplace_back(reserve.dof, numWires + r, 0.0);
            continue;
        }
        for (int i = 0; i < rows; ++i) entries.emplace_back(i, numWires + r, 0.0);
    }
    problem_.A.resize(rows, numBounded + wireProblem.numFree);
    problem_.A.setFromTriplets(entries.begin(), entries.end());
    problem_.A.makeCompressed();
}

void StaticOptimization::solve(const DistributionProblem& wireProblem, const Eigen::VectorXd& forceMultiplier,
                               StaticOptimizationResult& result, const Eigen::MatrixXd* reserveColumns) {
    const int numWires = static_cast<int>(settings_.maxIsometricForce.size());
    const int numReserves = static_cast<int>(settings_.reserves.size());
    const int rows = wireProblem.getNumRows(), numFree = wireProblem.numFree;
    if (wireProblem.getNumBounded() != numWires || forceMultiplier.size() != numWires)
        throw Error("static optimization: the wire problem has " + std::to_string(wireProblem.getNumBounded()) +
                    " wires and the frame " + std::to_string(forceMultiplier.size()) + " force multipliers, expected " +
                    std::to_string(numWires));
    if (reserveColumns && (reserveColumns->rows() != rows || reserveColumns->cols() != numReserves))
        throw Error("static optimization: reserve columns are " + std::to_string(reserveColumns->rows()) + " x " +
                    std::to_string(reserveColumns->cols()) + ", expected " + std::to_string(rows) + " x " +
                    std::to_string(numReserves));
    for (const ReserveActuator& reserve : settings_.reserves)
        if (!reserveColumns && (reserve.body || reserve.dof < 0 || reserve.dof >= rows))
            throw Error("static optimization: reserve '" + reserve.name + "' " +
                        (reserve.body ? std::string("acts on links: its generalized forces (reserve columns) must be given")
                                      : "acts on DOF " + std::to_string(reserve.dof) + ", expected 0 to " +
                                            std::to_string(rows - 1)));
    for (int w = 0; w < numWires; ++w)
        if (!(forceMultiplier[w] >= 0) || !std::isfinite(forceMultiplier[w]))
            throw Error("static optimization: wire " + std::to_string(w) + " has force multiplier " +
                        std::to_string(forceMultiplier[w]) + ", expected a finite value >= 0");

    // Columns [wires scaled to activations; reserves; free], all rows exact, Σ |x|^p as Σ (p / p) |x|^p
    // (for p = 2 the QP's ½ Σ 2 x²). The pattern is built once; each frame writes the values in its order.
    const int numBounded = numWires + numReserves;
    if (!hasPatternOf(wireProblem, reserveColumns != nullptr)) buildPattern(wireProblem, reserveColumns != nullptr);
    double* value = problem_.A.valuePtr();
    for (int w = 0; w < numWires; ++w) {
        const double force = settings_.maxIsometricForce[w] * forceMultiplier[w];
        for (Eigen::SparseMatrix<double>::InnerIterator it(wireProblem.A, w); it; ++it) *value++ = it.value() * force;
    }
    for (int r = 0; r < numReserves; ++r) {
        const ReserveActuator& reserve = settings_.reserves[static_cast<std::size_t>(r)];
        if (!reserveColumns)
            *value++ = reserve.optimalForce;
        else if (!reserve.body)
            *value++ = (*reserveColumns)(reserve.dof, r) * reserve.optimalForce;
        else
            for (int i = 0; i < rows; ++i) *value++ = (*reserveColumns)(i, r) * reserve.optimalForce;
    }
    for (int k = 0; k < numFree; ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(wireProblem.A, numWires + k); it; ++it) *value++ = it.value();
    problem_.numFree = numFree;
    problem_.lower.resize(numBounded);
    problem_.upper.resize(numBounded);
    problem_.lower.head(numWires) = settings_.minActivation;
    problem_.upper.head(numWires) = settings_.maxActivation;
    for (int r = 0; r < numReserves; ++r) {
        problem_.lower[numWires + r] = settings_.reserves[static_cast<std::size_t>(r)].minControl;
        problem_.upper[numWires + r] = settings_.reserves[static_cast<std::size_t>(r)].maxControl;
    }
    problem_.cost.setZero(numBounded);
    const double exponent = settings_.activationExponent;
    problem_.weight.setConstant(numBounded, exponent);
    problem_.target = wireProblem.target;
    problem_.tolerance.setZero(rows);
    problem_.isEquality.assign(static_cast<std::size_t>(rows), true);

    solver_.solve(problem_, result.distribution);
    const Eigen::VectorXd& x = result.distribution.x;
    result.activation = x.head(numWires);
    result.tension = result.activation.cwiseProduct(settings_.maxIsometricForce).cwiseProduct(forceMultiplier);
    result.reserveControl = x.segment(numWires, numReserves);
    result.reserveForce.resize(numReserves);
    for (int r = 0; r < numReserves; ++r)
        result.reserveForce[r] = result.reserveControl[r] * settings_.reserves[static_cast<std::size_t>(r)].optimalForce;
    result.loopForce = x.tail(numFree);
}

}  // namespace sinew

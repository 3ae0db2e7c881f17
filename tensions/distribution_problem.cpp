#include "sinew/tensions/distribution_problem.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

void checkSize(const char* field, Eigen::Index size, Eigen::Index expected, const char* what) {
    if (size != expected)
        throw Error("distribution problem: " + std::string(field) + " has " + std::to_string(size) +
                    " entries, expected " + std::to_string(expected) + " (" + what + ")");
}

// Clp takes magnitudes of 1e30 and more as infinite and its tolerances break down well before (an
// assertion in ClpNonLinearCost, not an error status), so every number of a problem stays below this.
constexpr double kMaxMagnitude = 1e20;

bool isBounded(double v) { return std::abs(v) <= kMaxMagnitude; }

std::string describe(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

void checkFinite(const char* field, const Eigen::VectorXd& v) {
    for (Eigen::Index i = 0; i < v.size(); ++i)
        if (!isBounded(v[i]))
            throw Error("distribution problem: " + std::string(field) + "[" + std::to_string(i) + "] is " +
                        describe(v[i]) + ", expected a finite number within +-1e20");
}

// A x, and max(1, |tau|, max_i sum_j |A_ij x_j|): the size of the generalized forces in play. One pass.
double calcRowProducts(const DistributionProblem& problem, const Eigen::VectorXd& x, Eigen::VectorXd& Ax) {
    Ax.setZero(problem.getNumRows());
    Eigen::VectorXd magnitude = Eigen::VectorXd::Zero(problem.getNumRows());
    for (int j = 0; j < problem.A.outerSize(); ++j)
        for (Eigen::SparseMatrix<double>::InnerIterator it(problem.A, j); it; ++it) {
            const double product = it.value() * x[j];
            Ax[it.row()] += product;
            magnitude[it.row()] += std::abs(product);
        }
    return std::max({1.0, problem.target.cwiseAbs().maxCoeff(), magnitude.maxCoeff()});
}

double boundScale(double bound) { return std::isfinite(bound) ? std::max(1.0, std::abs(bound)) : 1.0; }

// Bound violation, and the Lagrangian's projected gradient g_j = first_j - (A^T y)_j: a variable at its
// lower bound may only have g >= 0, at its upper g <= 0, free variables g = 0. Relative to the largest of
// the two terms.
// scaleFloor: the least size of the gradient's terms (a proximal QP's regulariser force at x, where its
// own terms vanish at convergence).
void addVariableResiduals(const DistributionProblem& problem, const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                          const Eigen::VectorXd& first, KktResiduals& kkt, double scaleFloor = 0) {
    const int numBounded = problem.getNumBounded();
    Eigen::VectorXd Aty = Eigen::VectorXd::Zero(problem.getNumVariables());
    double largestMagnitude = 0;
    for (int j = 0; j < problem.A.outerSize(); ++j) {
        double product = 0, magnitude = 0;
        for (Eigen::SparseMatrix<double>::InnerIterator it(problem.A, j); it; ++it) {
            const double term = it.value() * y[it.row()];
            product += term;
            magnitude += std::abs(term);
        }
        Aty[j] = product;
        largestMagnitude = std::max(largestMagnitude, magnitude);
    }
    double scale = std::max({first.cwiseAbs().maxCoeff(), largestMagnitude, scaleFloor});
    if (!(scale > 0)) scale = 1;
    double dual = 0;
    for (int j = 0; j < problem.getNumVariables(); ++j) {
        const double g = first[j] - Aty[j];
        double violation = std::abs(g);
        if (j < numBounded) {
            const double lower = problem.lower[j], upper = problem.upper[j];
            kkt.primal = std::max(kkt.primal, std::max(lower - x[j], x[j] - upper) / boundScale(std::max(std::abs(lower), std::abs(upper))));
            const bool atLower = x[j] <= lower + 1e-9 * boundScale(lower);
            const bool atUpper = x[j] >= upper - 1e-9 * boundScale(upper);
            if (atLower && atUpper) violation = 0;
            else if (atLower) violation = std::max(0.0, -g);
            else if (atUpper) violation = std::max(0.0, g);
        }
        dual = std::max(dual, violation / scale);
    }
    kkt.dual = dual;
}

}  // namespace

void validateDistributionProblem(const DistributionProblem& problem) {
    const Eigen::Index rows = problem.A.rows();
    if (problem.numFree < 0 || problem.numFree > problem.A.cols())
        throw Error("distribution problem: numFree is " + std::to_string(problem.numFree) + ", expected 0 to " +
                    std::to_string(problem.A.cols()) + " (the number of columns of A)");
    if (!problem.A.isCompressed()) throw Error("distribution problem: A is not compressed (call makeCompressed())");
    const Eigen::Index numBounded = problem.getNumBounded();
    checkSize("lower", problem.lower.size(), numBounded, "one per bounded variable");
    checkSize("upper", problem.upper.size(), numBounded, "one per bounded variable");
    checkSize("cost", problem.cost.size(), numBounded, "one per bounded variable");
    checkSize("weight", problem.weight.size(), numBounded, "one per bounded variable");
    checkSize("target", problem.target.size(), rows, "one per row of A");
    checkSize("tolerance", problem.tolerance.size(), rows, "one per row of A");
    checkSize("isEquality", static_cast<Eigen::Index>(problem.isEquality.size()), rows, "one per row of A");
    for (int j = 0; j < problem.A.outerSize(); ++j)
        for (Eigen::SparseMatrix<double>::InnerIterator it(problem.A, j); it; ++it)
            if (!isBounded(it.value()))
                throw Error("distribution problem: A(" + std::to_string(it.row()) + ", " + std::to_string(j) +
                            ") is " + describe(it.value()) + ", expected a finite number within +-1e20");
    checkFinite("cost", problem.cost);
    checkFinite("weight", problem.weight);
    checkFinite("target", problem.target);
    checkFinite("tolerance", problem.tolerance);
    for (Eigen::Index j = 0; j < numBounded; ++j) {
        const auto at = [j] { return "[" + std::to_string(j) + "]"; };
        const double lower = problem.lower[j], upper = problem.upper[j];
        if (std::isnan(lower) || std::isnan(upper) || lower > upper || (std::isfinite(lower) && !isBounded(lower)) ||
            (std::isfinite(upper) && !isBounded(upper)))
            throw Error("distribution problem: bounds" + at() + " are [" + std::to_string(problem.lower[j]) + ", " +
                        std::to_string(problem.upper[j]) + "], expected lower <= upper, each infinite or within +-1e20");
        if (!(problem.weight[j] > 0))
            throw Error("distribution problem: weight" + at() + " is " + std::to_string(problem.weight[j]) +
                        ", expected > 0");
    }
    for (Eigen::Index i = 0; i < rows; ++i)
        if (problem.tolerance[i] < 0)
            throw Error("distribution problem: tolerance[" + std::to_string(i) + "] is " +
                        std::to_string(problem.tolerance[i]) + ", expected >= 0");
}

const char* toString(DistributionStatus status) {
    switch (status) {
        case DistributionStatus::Optimal: return "optimal";
        case DistributionStatus::Infeasible: return "infeasible";
        case DistributionStatus::Failed: return "failed";
    }
    return "unknown";
}

double KktResiduals::getMax() const { return std::max({primal, dual, complementarity}); }

KktResiduals calcLpKktResiduals(const DistributionProblem& problem, const Eigen::VectorXd& x,
                                const Eigen::VectorXd& y) {
    KktResiduals kkt;
    Eigen::VectorXd Ax;
    const double rowScale = calcRowProducts(problem, x, Ax);
    const double yScale = std::max(y.size() ? y.cwiseAbs().maxCoeff() : 0.0, 1e-300);
    for (int i = 0; i < problem.getNumRows(); ++i) {
        const double band = problem.isEquality[static_cast<std::size_t>(i)] ? 0 : problem.tolerance[i];
        const double below = problem.target[i] - band - Ax[i], above = Ax[i] - problem.target[i] - band;
        kkt.primal = std::max(kkt.primal, std::max(below, above) / rowScale);
        if (band == 0) continue;
        // y_i > 0 holds the row at its lower side, y_i < 0 at its upper side.
        const double slack = y[i] > 0 ? -below : -above;
        kkt.complementarity = std::max(kkt.complementarity, std::abs(y[i]) * std::max(0.0, slack) / (yScale * rowScale));
    }
    Eigen::VectorXd first = Eigen::VectorXd::Zero(problem.getNumVariables());
    first.head(problem.getNumBounded()) = problem.cost;
    addVariableResiduals(problem, x, y, first, kkt);
    return kkt;
}

KktResiduals calcQpKktResiduals(const DistributionProblem& problem, const Eigen::VectorXd& x,
                                const Eigen::VectorXd& y, const Eigen::VectorXd& center) {
    KktResiduals kkt;
    Eigen::VectorXd residual;
    const double rowScale = calcRowProducts(problem, x, residual);
    residual = problem.target - residual;
    Eigen::VectorXd yAll = y;
    for (int i = 0; i < problem.getNumRows(); ++i) {
        if (problem.isEquality[static_cast<std::size_t>(i)])
            kkt.primal = std::max(kkt.primal, std::abs(residual[i]) / rowScale);
        else
            yAll[i] = residual[i];
    }
    Eigen::VectorXd first = Eigen::VectorXd::Zero(problem.getNumVariables());
    first.head(problem.getNumBounded()) = problem.weight.cwiseProduct(x.head(problem.getNumBounded()));
    const double regulariserForce = first.cwiseAbs().maxCoeff();
    if (center.size() == problem.getNumBounded()) first.head(problem.getNumBounded()) -= problem.weight.cwiseProduct(center);
    addVariableResiduals(problem, x, yAll, first, kkt, regulariserForce);
    return kkt;
}

void calcResultSummary(const DistributionProblem& problem, DistributionResult& result) {
    result.residual = problem.target;
    result.residual.noalias() -= problem.A * result.x;
    result.torqueError = 0.5 * result.residual.squaredNorm();
    result.activeVariables = 0;
    for (int j = 0; j < problem.getNumBounded(); ++j)
        if (result.x[j] > problem.lower[j]) ++result.activeVariables;
}

}  // namespace sinew

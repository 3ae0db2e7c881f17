#include "sinew/tensions/ipopt_solver.hpp"

#include <IpIpoptApplication.hpp>
#include <IpIpoptData.hpp>
#include <IpTNLP.hpp>

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

using Ipopt::Index;
using Ipopt::Number;
using SparseColumn = Eigen::SparseMatrix<double>::InnerIterator;

// Ipopt's "no bound".
constexpr double kIpoptInfinity = 2e19;

// The problem as Ipopt's TNLP: constraints are the equality rows; the tolerance rows' least squares and
// the variables' |x|^p terms are the objective. Jacobian and Hessian are sparse; their patterns are built
// once per frame.
class DistributionTnlp : public Ipopt::TNLP {
public:
    DistributionTnlp(const DistributionProblem& problem, double exponent) : problem_(problem), p_(exponent) {
        const int rows = problem.getNumRows(), n = problem.getNumVariables();
        std::vector<int> constraintOf(static_cast<std::size_t>(rows), -1);
        for (int i = 0; i < rows; ++i)
            if (problem.isEquality[static_cast<std::size_t>(i)]) constraintOf[static_cast<std::size_t>(i)] = numConstraints_++;
        Eigen::SparseMatrix<double> leastSquaresRows(rows, rows);  // selects the tolerance rows
        std::vector<Eigen::Triplet<double>> selected;
        for (int i = 0; i < rows; ++i)
            if (constraintOf[static_cast<std::size_t>(i)] < 0) selected.emplace_back(i, i, 1.0);
        leastSquaresRows.setFromTriplets(selected.begin(), selected.end());
        for (int j = 0; j < n; ++j)
            for (SparseColumn it(problem.A, j); it; ++it)
                if (constraintOf[static_cast<std::size_t>(it.row())] >= 0)
                    jacobian_.emplace_back(constraintOf[static_cast<std::size_t>(it.row())], j, it.value());
        A_tolerance_ = leastSquaresRows * problem.A;
        // Hessian: A_tol^T A_tol (lower triangle) plus the bounded variables' diagonal, explicit zeros kept.
        const Eigen::SparseMatrix<double> gram = Eigen::SparseMatrix<double>(A_tolerance_.transpose()) * A_tolerance_;
        std::vector<Eigen::Triplet<double>> hessian;
        for (int j = 0; j < gram.outerSize(); ++j)
            for (SparseColumn it(gram, j); it; ++it)
                if (it.row() >= j) hessian.emplace_back(static_cast<int>(it.row()), j, it.value());
        for (int j = 0; j < problem.getNumBounded(); ++j) hessian.emplace_back(j, j, 0.0);
        hessian_.resize(n, n);
        hessian_.setFromTriplets(hessian.begin(), hessian.end());
        hessian_.makeCompressed();
        gramValues_.assign(hessian_.valuePtr(), hessian_.valuePtr() + hessian_.nonZeros());
        diagonalEntry_.assign(static_cast<std::size_t>(problem.getNumBounded()), 0);
        for (int j = 0; j < problem.getNumBounded(); ++j)
            for (Eigen::Index k = hessian_.outerIndexPtr()[j]; k < hessian_.outerIndexPtr()[j + 1]; ++k)
                if (hessian_.innerIndexPtr()[k] == j) diagonalEntry_[static_cast<std::size_t>(j)] = k;
    }

    bool finished = false;
    Ipopt::SolverReturn status = Ipopt::INTERNAL_ERROR;
    Eigen::VectorXd x, constraintMultipliers;
    int iterations = 0;

    bool get_nlp_info(Index& n, Index& m, Index& nnzJacobian, Index& nnzHessian, IndexStyleEnum& style) override {
        n = problem_.getNumVariables();
        m = numConstraints_;
        nnzJacobian = static_cast<Index>(jacobian_.size());
        nnzHessian = static_cast<Index>(hessian_.nonZeros());
        style = C_STYLE;
        return true;
    }
    bool get_bounds_info(Index n, Number* xLower, Number* xUpper, Index, Number* gLower, Number* gUpper) override {
        for (Index j = 0; j < n; ++j) {
            const bool bounded = j < problem_.getNumBounded();
            xLower[j] = bounded && std::isfinite(problem_.lower[j]) ? problem_.lower[j] : -kIpoptInfinity;
            xUpper[j] = bounded && std::isfinite(problem_.upper[j]) ? problem_.upper[j] : kIpoptInfinity;
        }
        for (int i = 0, k = 0; i < problem_.getNumRows(); ++i)
            if (problem_.isEquality[static_cast<std::size_t>(i)]) gLower[k] = gUpper[k] = problem_.target[i], ++k;
        return true;
    }
    // Mid-box, or 0 projected into a half-bounded box: strictly inside for the interior-point method.
    bool get_starting_point(Index n, bool, Number* x0, bool, Number*, Number*, Index, bool, Number*) override {
        for (Index j = 0; j < n; ++j) {
            const bool bounded = j < problem_.getNumBounded();
            const double lower = bounded ? problem_.lower[j] : -INFINITY, upper = bounded ? problem_.upper[j] : INFINITY;
            x0[j] = std::isfinite(lower) && std::isfinite(upper) ? 0.5 * (lower + upper)
                    : std::isfinite(lower)                        ? std::max(0.0, lower + 1)
                    : std::isfinite(upper)                        ? std::min(0.0, upper - 1)
                                                                  : 0;
        }
        return true;
    }
    bool eval_f(Index n, const Number* x0, bool, Number& value) override {
        const Eigen::Map<const Eigen::VectorXd> xv(x0, n);
        value = 0;
        for (int j = 0; j < problem_.getNumBounded(); ++j) value += problem_.weight[j] / p_ * std::pow(std::abs(xv[j]), p_);
        value += 0.5 * (A_tolerance_ * xv - selectTolerance(problem_.target)).squaredNorm();
        return true;
    }
    bool eval_grad_f(Index n, const Number* x0, bool, Number* gradient) override {
        const Eigen::Map<const Eigen::VectorXd> xv(x0, n);
        Eigen::Map<Eigen::VectorXd> g(gradient, n);
        g = A_tolerance_.transpose() * (A_tolerance_ * xv - selectTolerance(problem_.target));
        for (int j = 0; j < problem_.getNumBounded(); ++j)
            g[j] += problem_.weight[j] * std::copysign(std::pow(std::abs(xv[j]), p_ - 1), xv[j]);
        return true;
    }
    bool eval_g(Index, const Number* x0, bool, Index m, Number* g) override {
        std::fill(g, g + m, 0.0);
        for (const Eigen::Triplet<double>& e : jacobian_) g[e.row()] += e.value() * x0[e.col()];
        return true;
    }
    bool eval_jac_g(Index, const Number*, bool, Index, Index, Index* iRow, Index* jCol, Number* values) override {
        for (std::size_t e = 0; e < jacobian_.size(); ++e) {
            if (values) values[e] = jacobian_[e].value();
            else iRow[e] = jacobian_[e].row(), jCol[e] = jacobian_[e].col();
        }
        return true;
    }
    bool eval_h(Index, const Number* x0, bool, Number factor, Index, const Number*, bool, Index, Index* iRow,
                Index* jCol, Number* values) override {
        if (!values) {
            for (int j = 0; j < hessian_.outerSize(); ++j)
                for (Eigen::Index k = hessian_.outerIndexPtr()[j]; k < hessian_.outerIndexPtr()[j + 1]; ++k)
                    iRow[k] = hessian_.innerIndexPtr()[k], jCol[k] = j;
            return true;
        }
        for (std::size_t k = 0; k < gramValues_.size(); ++k) values[k] = factor * gramValues_[k];
        for (int j = 0; j < problem_.getNumBounded(); ++j) {
            // |x|^(p-2) is unbounded at 0 for p < 2: a variable sitting exactly there gets a large, finite curvature.
            const double magnitude = std::max(std::abs(x0[j]), 1e-12);
            values[diagonalEntry_[static_cast<std::size_t>(j)]] +=
                factor * problem_.weight[j] * (p_ - 1) * std::pow(magnitude, p_ - 2);
        }
        return true;
    }
    void finalize_solution(Ipopt::SolverReturn solverStatus, Index n, const Number* x0, const Number*, const Number*,
                           Index m, const Number*, const Number* lambda, Number, const Ipopt::IpoptData* data,
                           Ipopt::IpoptCalculatedQuantities*) override {
        finished = true;
        status = solverStatus;
        x = Eigen::Map<const Eigen::VectorXd>(x0, n);
        constraintMultipliers = lambda ? Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(lambda, m))
                                       : Eigen::VectorXd::Zero(m);
        iterations = data ? data->iter_count() : 0;
    }

private:
    // tau on the tolerance rows, zero on the equality rows (A_tolerance_ has zero rows there).
    Eigen::VectorXd selectTolerance(const Eigen::VectorXd& rowVector) const {
        Eigen::VectorXd selected = rowVector;
        for (int i = 0; i < problem_.getNumRows(); ++i)
            if (problem_.isEquality[static_cast<std::size_t>(i)]) selected[i] = 0;
        return selected;
    }

    const DistributionProblem& problem_;
    double p_;
    int numConstraints_ = 0;
    std::vector<Eigen::Triplet<double>> jacobian_;  // (constraint, variable, value) of the equality rows
    Eigen::SparseMatrix<double> A_tolerance_;        // A with its equality rows zeroed
    Eigen::SparseMatrix<double> hessian_;            // lower triangle pattern
    std::vector<double> gramValues_;                 // A_tol^T A_tol in hessian_'s order (0 on pure diagonal)
    std::vector<Eigen::Index> diagonalEntry_;        // (numBounded) position of (j, j) in hessian_
};

}  // namespace

struct IpoptSolver::Backend {
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    bool initialized = false;
    DistributionProblem quadratic;  // for the KKT residuals
};

IpoptSolver::IpoptSolver(IpoptSolverOptions options)
    : backend_(std::make_unique<Backend>()), exponent_(options.exponent) {
    Ipopt::OptionsList& list = *backend_->app->Options();
    list.SetNumericValue("tol", options.tolerance);
    list.SetIntegerValue("max_iter", options.maxIterations);
    list.SetIntegerValue("print_level", 0);
    list.SetStringValue("sb", "yes");
    list.SetStringValue("jac_c_constant", "yes");
    backend_->initialized = backend_->app->Initialize() == Ipopt::Solve_Succeeded;
}

IpoptSolver::~IpoptSolver() = default;

void IpoptSolver::solve(const DistributionProblem& problem, double exponent, DistributionResult& result) {
    validateDistributionProblem(problem);
    if (!(exponent >= 1) || !std::isfinite(exponent))
        throw Error("Ipopt tension solver: cost exponent " + std::to_string(exponent) +
                    ", expected a finite value >= 1 (the cost must be convex)");
    const int rows = problem.getNumRows(), numBounded = problem.getNumBounded();
    backend_->app->Options()->SetStringValue("hessian_constant", exponent == 2 ? "yes" : "no");
    Ipopt::SmartPtr<DistributionTnlp> nlp = new DistributionTnlp(problem, exponent);
    if (backend_->initialized) backend_->app->OptimizeTNLP(Ipopt::GetRawPtr(nlp));

    result.usedIpopt = true;
    result.iterations = nlp->iterations;
    result.reserve.setZero(rows);
    result.x.setZero(problem.getNumVariables());
    result.multipliers.setZero(rows);
    result.status = DistributionStatus::Failed;
    if (nlp->finished && nlp->x.allFinite() && nlp->constraintMultipliers.allFinite()) {
        result.x = nlp->x;
        if (nlp->status == Ipopt::SUCCESS || nlp->status == Ipopt::STOP_AT_ACCEPTABLE_POINT)
            result.status = DistributionStatus::Optimal;
        else if (nlp->status == Ipopt::LOCAL_INFEASIBILITY)
            result.status = DistributionStatus::Infeasible;
    }
    // Ipopt relaxes bounds by ~1e-8 relative: back into them. An interior point never reaches a bound, so a
    // variable within 1e-8 of its box's size of one is put on it (as the active set would have it).
    for (int j = 0; j < numBounded; ++j) {
        const double lower = problem.lower[j], upper = problem.upper[j];
        const double near = 1e-8 * (std::isfinite(upper - lower) ? std::max(1.0, upper - lower) : 1.0);
        double& xj = result.x[j];
        xj = xj <= lower + near ? lower : xj >= upper - near ? upper : xj;
    }
    calcResultSummary(problem, result);
    // Ipopt's Lagrangian is f + lambda^T g: the multiplier d f / d tau is -lambda; tolerance rows' is their residual.
    for (int i = 0, k = 0; i < rows; ++i)
        if (problem.isEquality[static_cast<std::size_t>(i)]) {
            if (nlp->constraintMultipliers.size() > k) result.multipliers[i] = -nlp->constraintMultipliers[k];
            ++k;
        } else {
            result.multipliers[i] = result.residual[i];
        }
    result.objective = 0;
    // The QP's KKT residuals with per-variable weights w_j |x_j|^(p-2): their gradient w_j x_j is this cost's.
    DistributionProblem& quadratic = backend_->quadratic;
    quadratic = problem;
    for (int j = 0; j < numBounded; ++j) {
        const double magnitude = std::abs(result.x[j]);
        result.objective += problem.weight[j] / exponent * std::pow(magnitude, exponent);
        if (magnitude > 0) quadratic.weight[j] *= std::pow(magnitude, exponent - 2);
    }
    for (int i = 0; i < rows; ++i)
        if (!problem.isEquality[static_cast<std::size_t>(i)]) result.objective += 0.5 * result.residual[i] * result.residual[i];
    result.kkt = calcQpKktResiduals(quadratic, result.x, result.multipliers);
}

}  // namespace sinew

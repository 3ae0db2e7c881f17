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
#include "sinew/tensions/equality_rows_polish.hpp"

namespace sinew {
namespace {

using Ipopt::Index;
using Ipopt::Number;
using SparseColumn = Eigen::SparseMatrix<double>::InnerIterator;

// Ipopt's "no bound".
constexpr double kIpoptInfinity = 2e19;

// The problem as Ipopt's TNLP, in variables [x; r]: every row is a constraint, A_i x = tau_i on the equality
// rows and A_i x + r_i = tau_i on the tolerance rows, whose residuals r enter the objective
// ½ |r|² + Σ weight_j / p |x_j|^p. So the Hessian is diagonal and the Jacobian A's pattern (plus r's identity):
// with the least squares written as ½ |tau - A x|² instead, the Hessian would be AᵀA, dense over the wires that
// share a DOF (a 1,100-square block on the whole-body model, 0.2 s per Ipopt iteration to factor).
class DistributionTnlp : public Ipopt::TNLP {
public:
    DistributionTnlp(const DistributionProblem& problem, double exponent) : problem_(problem), p_(exponent) {
        const int rows = problem.getNumRows(), n = problem.getNumVariables();
        std::vector<int> constraintOf(static_cast<std::size_t>(rows), -1);
        for (int i = 0; i < rows; ++i)
            if (problem.isEquality[static_cast<std::size_t>(i)]) constraintOf[static_cast<std::size_t>(i)] = numEqualities_++;
        for (int i = 0; i < rows; ++i) {
            if (problem.isEquality[static_cast<std::size_t>(i)]) continue;
            // r_k, tolerance row i's residual, is variable n + k and belongs to constraint numEqualities_ + k.
            const int k = numResiduals_++;
            constraintOf[static_cast<std::size_t>(i)] = numEqualities_ + k;
            jacobian_.emplace_back(numEqualities_ + k, n + k, 1.0);
        }
        targets_.resize(static_cast<std::size_t>(rows));
        for (int i = 0; i < rows; ++i) targets_[static_cast<std::size_t>(constraintOf[static_cast<std::size_t>(i)])] = problem.target[i];
        for (int j = 0; j < n; ++j)
            for (SparseColumn it(problem.A, j); it; ++it)
                jacobian_.emplace_back(constraintOf[static_cast<std::size_t>(it.row())], j, it.value());
    }

    bool finished = false;
    Ipopt::SolverReturn status = Ipopt::INTERNAL_ERROR;
    Eigen::VectorXd x, constraintMultipliers;  // x: the problem's variables (r left out); multipliers: equality rows'
    int iterations = 0;

    bool get_nlp_info(Index& n, Index& m, Index& nnzJacobian, Index& nnzHessian, IndexStyleEnum& style) override {
        n = problem_.getNumVariables() + numResiduals_;
        m = numEqualities_ + numResiduals_;
        nnzJacobian = static_cast<Index>(jacobian_.size());
        nnzHessian = problem_.getNumBounded() + numResiduals_;
        style = C_STYLE;
        return true;
    }
    bool get_bounds_info(Index n, Number* xLower, Number* xUpper, Index m, Number* gLower, Number* gUpper) override {
        for (Index j = 0; j < n; ++j) {
            const bool bounded = j < problem_.getNumBounded();
            xLower[j] = bounded && std::isfinite(problem_.lower[j]) ? problem_.lower[j] : -kIpoptInfinity;
            xUpper[j] = bounded && std::isfinite(problem_.upper[j]) ? problem_.upper[j] : kIpoptInfinity;
        }
        for (Index k = 0; k < m; ++k) gLower[k] = gUpper[k] = targets_[static_cast<std::size_t>(k)];
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
    bool eval_f(Index, const Number* x0, bool, Number& value) override {
        value = 0;
        for (int j = 0; j < problem_.getNumBounded(); ++j) value += problem_.weight[j] / p_ * std::pow(std::abs(x0[j]), p_);
        const Number* r = x0 + problem_.getNumVariables();
        for (int k = 0; k < numResiduals_; ++k) value += 0.5 * r[k] * r[k];
        return true;
    }
    bool eval_grad_f(Index n, const Number* x0, bool, Number* gradient) override {
        std::fill(gradient, gradient + n, 0.0);
        for (int j = 0; j < problem_.getNumBounded(); ++j)
            gradient[j] = problem_.weight[j] * std::copysign(std::pow(std::abs(x0[j]), p_ - 1), x0[j]);
        for (int k = problem_.getNumVariables(); k < n; ++k) gradient[k] = x0[k];
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
    // The diagonal: the bounded variables' cost curvature, then 1 per residual.
    bool eval_h(Index, const Number* x0, bool, Number factor, Index, const Number*, bool, Index, Index* iRow,
                Index* jCol, Number* values) override {
        const int numBounded = problem_.getNumBounded(), n = problem_.getNumVariables();
        if (!values) {
            for (int k = 0; k < numBounded + numResiduals_; ++k) iRow[k] = jCol[k] = k < numBounded ? k : n + k - numBounded;
            return true;
        }
        for (int j = 0; j < numBounded; ++j) {
            // |x|^(p-2) is unbounded at 0 for p < 2: a variable sitting exactly there gets a large, finite curvature.
            const double magnitude = std::max(std::abs(x0[j]), 1e-12);
            values[j] = factor * problem_.weight[j] * (p_ - 1) * std::pow(magnitude, p_ - 2);
        }
        for (int k = 0; k < numResiduals_; ++k) values[numBounded + k] = factor;
        return true;
    }
    void finalize_solution(Ipopt::SolverReturn solverStatus, Index, const Number* x0, const Number*, const Number*,
                           Index, const Number*, const Number* lambda, Number, const Ipopt::IpoptData* data,
                           Ipopt::IpoptCalculatedQuantities*) override {
        finished = true;
        status = solverStatus;
        x = Eigen::Map<const Eigen::VectorXd>(x0, problem_.getNumVariables());
        constraintMultipliers = lambda ? Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(lambda, numEqualities_))
                                       : Eigen::VectorXd::Zero(numEqualities_);
        iterations = data ? data->iter_count() : 0;
    }

private:
    const DistributionProblem& problem_;
    double p_;
    int numEqualities_ = 0, numResiduals_ = 0;
    std::vector<Eigen::Triplet<double>> jacobian_;  // (constraint, variable, value): A's entries and r's identity
    std::vector<double> targets_;                   // per constraint, its row's tau
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
    // Ipopt's Lagrangian is f + lambda^T g: the multiplier d f / d tau is -lambda.
    for (int i = 0, k = 0; i < rows; ++i)
        if (problem.isEquality[static_cast<std::size_t>(i)]) {
            if (nlp->constraintMultipliers.size() > k) result.multipliers[i] = -nlp->constraintMultipliers[k];
            ++k;
        }
    // The QP's weights w_j |x_j|^(p-2) at x: their gradient w_j x_j is this cost's, and (p - 1) times them
    // its curvature.
    DistributionProblem& quadratic = backend_->quadratic;
    quadratic = problem;
    auto setQuadraticWeights = [&] {
        for (int j = 0; j < numBounded; ++j) {
            const double magnitude = std::abs(result.x[j]);
            quadratic.weight[j] = magnitude > 0 ? problem.weight[j] * std::pow(magnitude, exponent - 2) : problem.weight[j];
        }
    };
    setQuadraticWeights();
    // Ipopt meets the equality rows to its constraint tolerance, and the snap onto the bounds moves them
    // by up to 1e-8: projected back onto them.
    if (result.status == DistributionStatus::Optimal) {
        polishEqualityRows(problem, (exponent - 1) * quadratic.weight, result.x, result.multipliers);
        setQuadraticWeights();
    }
    calcResultSummary(problem, result);
    result.objective = 0;
    for (int j = 0; j < numBounded; ++j) result.objective += problem.weight[j] / exponent * std::pow(std::abs(result.x[j]), exponent);
    // A tolerance row's multiplier is its residual, and its cost half the residual's square.
    for (int i = 0; i < rows; ++i) {
        if (problem.isEquality[static_cast<std::size_t>(i)]) continue;
        result.multipliers[i] = result.residual[i];
        result.objective += 0.5 * result.residual[i] * result.residual[i];
    }
    result.kkt = calcQpKktResiduals(quadratic, result.x, result.multipliers);
}

}  // namespace sinew

#pragma once
// Ipopt (interior point, MUMPS) as the independent reference for the tension-distribution tests: it solves
// the LP or the QP of a DistributionProblem (distribution_problem.hpp) from its definition, with exact
// derivatives and a dense Hessian, so keep the problems small (tens of variables).
#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "sinew/tensions/distribution_problem.hpp"

namespace sinew::test {

struct IpoptReference {
    bool solved = false;
    Eigen::VectorXd x;
    double objective = 0;
};

class DistributionNlp : public Ipopt::TNLP {
public:
    enum class Kind { Lp, Qp };
    DistributionNlp(const DistributionProblem& problem, Kind kind) : problem_(problem), kind_(kind) {
        dense_ = Eigen::MatrixXd(problem.A);
        for (int i = 0; i < problem.getNumRows(); ++i)
            if (kind == Kind::Lp || problem.isEquality[static_cast<std::size_t>(i)]) constraintRows_.push_back(i);
            else leastSquaresRows_.push_back(i);
    }
    IpoptReference result;

    bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnzJacobian, Ipopt::Index& nnzHessian,
                      IndexStyleEnum& style) override {
        n = problem_.getNumVariables();
        m = static_cast<Ipopt::Index>(constraintRows_.size());
        nnzJacobian = m * n;
        nnzHessian = n * (n + 1) / 2;
        style = C_STYLE;
        return true;
    }
    bool get_bounds_info(Ipopt::Index n, Ipopt::Number* xLower, Ipopt::Number* xUpper, Ipopt::Index m,
                         Ipopt::Number* gLower, Ipopt::Number* gUpper) override {
        for (Ipopt::Index j = 0; j < n; ++j) {
            const bool bounded = j < problem_.getNumBounded();
            xLower[j] = bounded && std::isfinite(problem_.lower[j]) ? problem_.lower[j] : -2e19;
            xUpper[j] = bounded && std::isfinite(problem_.upper[j]) ? problem_.upper[j] : 2e19;
        }
        for (Ipopt::Index k = 0; k < m; ++k) {
            const int i = constraintRows_[static_cast<std::size_t>(k)];
            const double band = problem_.isEquality[static_cast<std::size_t>(i)] ? 0 : problem_.tolerance[i];
            gLower[k] = problem_.target[i] - band;
            gUpper[k] = problem_.target[i] + band;
        }
        return true;
    }
    bool get_starting_point(Ipopt::Index n, bool, Ipopt::Number* x, bool, Ipopt::Number*, Ipopt::Number*,
                            Ipopt::Index, bool, Ipopt::Number*) override {
        for (Ipopt::Index j = 0; j < n; ++j) {
            const bool bounded = j < problem_.getNumBounded();
            const double lower = bounded ? problem_.lower[j] : -INFINITY, upper = bounded ? problem_.upper[j] : INFINITY;
            x[j] = std::isfinite(lower) && std::isfinite(upper) ? 0.5 * (lower + upper)
                   : std::isfinite(lower)                        ? lower + 1
                   : std::isfinite(upper)                        ? upper - 1
                                                                 : 0;
        }
        return true;
    }
    bool eval_f(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Number& value) override {
        value = objective(Eigen::Map<const Eigen::VectorXd>(x, n));
        return true;
    }
    bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Number* gradient) override {
        const Eigen::Map<const Eigen::VectorXd> xv(x, n);
        Eigen::Map<Eigen::VectorXd> g(gradient, n);
        g.setZero();
        const int numBounded = problem_.getNumBounded();
        if (kind_ == Kind::Lp) {
            g.head(numBounded) = problem_.cost;
            return true;
        }
        g.head(numBounded) = problem_.weight.cwiseProduct(xv.head(numBounded));
        const Eigen::VectorXd r = problem_.target - dense_ * xv;
        for (const int i : leastSquaresRows_) g -= dense_.row(i).transpose() * r[i];
        return true;
    }
    bool eval_g(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Index m, Ipopt::Number* g) override {
        const Eigen::Map<const Eigen::VectorXd> xv(x, n);
        for (Ipopt::Index k = 0; k < m; ++k) g[k] = dense_.row(constraintRows_[static_cast<std::size_t>(k)]).dot(xv);
        return true;
    }
    bool eval_jac_g(Ipopt::Index n, const Ipopt::Number*, bool, Ipopt::Index m, Ipopt::Index, Ipopt::Index* iRow,
                    Ipopt::Index* jCol, Ipopt::Number* values) override {
        Ipopt::Index e = 0;
        for (Ipopt::Index k = 0; k < m; ++k)
            for (Ipopt::Index j = 0; j < n; ++j, ++e) {
                if (values) values[e] = dense_(constraintRows_[static_cast<std::size_t>(k)], j);
                else iRow[e] = k, jCol[e] = j;
            }
        return true;
    }
    bool eval_h(Ipopt::Index n, const Ipopt::Number*, bool, Ipopt::Number factor, Ipopt::Index, const Ipopt::Number*,
                bool, Ipopt::Index, Ipopt::Index* iRow, Ipopt::Index* jCol, Ipopt::Number* values) override {
        Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
        if (kind_ == Kind::Qp) {
            H.diagonal().head(problem_.getNumBounded()) = problem_.weight;
            for (const int i : leastSquaresRows_) H += dense_.row(i).transpose() * dense_.row(i);
        }
        Ipopt::Index e = 0;
        for (Ipopt::Index r = 0; r < n; ++r)
            for (Ipopt::Index c = 0; c <= r; ++c, ++e) {
                if (values) values[e] = factor * H(r, c);
                else iRow[e] = r, jCol[e] = c;
            }
        return true;
    }
    void finalize_solution(Ipopt::SolverReturn status, Ipopt::Index n, const Ipopt::Number* x, const Ipopt::Number*,
                           const Ipopt::Number*, Ipopt::Index, const Ipopt::Number*, const Ipopt::Number*,
                           Ipopt::Number, const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
        result.solved = status == Ipopt::SUCCESS;
        result.x = Eigen::Map<const Eigen::VectorXd>(x, n);
        result.objective = objective(result.x);
    }

private:
    double objective(const Eigen::VectorXd& x) const {
        const int numBounded = problem_.getNumBounded();
        if (kind_ == Kind::Lp) return problem_.cost.dot(x.head(numBounded));
        double value = 0.5 * problem_.weight.dot(x.head(numBounded).cwiseAbs2());
        const Eigen::VectorXd r = problem_.target - dense_ * x;
        for (const int i : leastSquaresRows_) value += 0.5 * r[i] * r[i];
        return value;
    }

    const DistributionProblem& problem_;
    Kind kind_;
    Eigen::MatrixXd dense_;
    std::vector<int> constraintRows_, leastSquaresRows_;
};

// Ipopt to 1e-12 on the problem's LP or QP.
inline IpoptReference solveWithIpopt(const DistributionProblem& problem, DistributionNlp::Kind kind) {
    Ipopt::SmartPtr<DistributionNlp> nlp = new DistributionNlp(problem, kind);
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    app->Options()->SetNumericValue("tol", 1e-12);
    app->Options()->SetIntegerValue("print_level", 0);
    app->Options()->SetStringValue("sb", "yes");
    app->Options()->SetIntegerValue("max_iter", 3000);
    if (kind == DistributionNlp::Kind::Qp) app->Options()->SetStringValue("hessian_constant", "yes");
    if (app->Initialize() != Ipopt::Solve_Succeeded) return {};
    app->OptimizeTNLP(Ipopt::GetRawPtr(nlp));
    return nlp->result;
}

}  // namespace sinew::test

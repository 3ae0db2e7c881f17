// OpenSim-style static optimization: a hand-worked two-muscle joint, Ipopt on random problems with loops,
// reserves and activation bounds (exponent 2, and 1.5 and 3 against Ipopt in tension units), and infeasible
// frames against Ipopt's smallest reserve.
#include <gtest/gtest.h>

#include <cmath>

#include "support/ipopt_reference.hpp"
#include "support/random_distribution_problems.hpp"
#include "sinew/core/error.hpp"
#include "sinew/tensions/static_optimization.hpp"

namespace sinew {
namespace {

ReserveActuator makeReserve(const std::string& name, int dof, double optimalForce, double minControl = -INFINITY,
                            double maxControl = INFINITY) {
    ReserveActuator reserve;
    reserve.name = name;
    reserve.dof = dof;
    reserve.optimalForce = optimalForce;
    reserve.minControl = minControl;
    reserve.maxControl = maxControl;
    return reserve;
}

// One DOF, two muscles with moment arms r, strengths F and multipliers m: min a1² + a2² s.t.
// c1 a1 + c2 a2 = tau with c = r F m gives a = tau c / |c|² while within [0, 1].
TEST(StaticOptimization, TwoMuscleJointByHand) {
    DistributionProblem wires;
    wires.A.resize(1, 2);
    wires.A.insert(0, 0) = 0.04;
    wires.A.insert(0, 1) = 0.02;
    wires.A.makeCompressed();
    wires.lower.setZero(2), wires.upper.setOnes(2), wires.cost.setOnes(2), wires.weight.setOnes(2);
    wires.tolerance.setZero(1);
    wires.isEquality = {false};
    StaticOptimizationSettings settings;
    settings.maxIsometricForce = Eigen::Vector2d(1000, 500);
    StaticOptimization so(settings);
    const Eigen::Vector2d multiplier(0.8, 0.5);
    const Eigen::Vector2d c(0.04 * 1000 * 0.8, 0.02 * 500 * 0.5);
    StaticOptimizationResult result;

    wires.target = Eigen::VectorXd::Constant(1, 10.0);
    so.solve(wires, multiplier, result);
    ASSERT_EQ(result.distribution.status, DistributionStatus::Optimal);
    EXPECT_LE((result.activation - 10.0 * c / c.squaredNorm()).cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_NEAR(result.tension[0], result.activation[0] * 800, 1e-9);
    EXPECT_NEAR(result.distribution.objective, result.activation.squaredNorm(), 1e-12);

    // Muscle 1 saturates at activation 1; muscle 2 makes up the rest.
    wires.target[0] = 34.0;
    so.solve(wires, multiplier, result);
    ASSERT_EQ(result.distribution.status, DistributionStatus::Optimal);
    EXPECT_NEAR(result.activation[0], 1.0, 1e-12);
    EXPECT_NEAR(result.activation[1], (34.0 - c[0]) / c[1], 1e-10);

    // Beyond both muscles: infeasible without a reserve, the missing torque reported.
    wires.target[0] = 40.0;
    so.solve(wires, multiplier, result);
    EXPECT_EQ(result.distribution.status, DistributionStatus::Infeasible);
    EXPECT_NEAR(result.distribution.reserve[0], 40.0 - c.sum(), 1e-6);

    // A reserve with optimal force 10 takes it: min 1 + a2² + u² s.t. c1 + c2 a2 + 10 u = 40 (a1 stays 1).
    settings.reserves.push_back(makeReserve("reserve", 0, 10.0));
    StaticOptimization withReserve(settings);
    withReserve.solve(wires, multiplier, result);
    ASSERT_EQ(result.distribution.status, DistributionStatus::Optimal);
    const double rest = 40.0 - c[0];
    EXPECT_NEAR(result.activation[1], rest * c[1] / (c[1] * c[1] + 100), 1e-10);
    EXPECT_NEAR(result.reserveForce[0], rest * 100 / (c[1] * c[1] + 100), 1e-9);
}

// A random static-optimization case on a random wire problem: strengths, activation bounds [0.01, 1],
// force multipliers, and (withReserves) a reserve of control bounds ±50 on every DOF.
struct RandomCase {
    DistributionProblem wires;
    StaticOptimizationSettings settings;
    Eigen::VectorXd multiplier;
};

RandomCase makeRandomCase(const test::RandomProblemOptions& options, bool withReserves) {
    RandomCase c;
    c.wires = test::makeRandomProblem(options);
    const int numWires = c.wires.getNumBounded(), rows = c.wires.getNumRows();
    std::mt19937 rng(options.seed);
    std::uniform_real_distribution<double> unit(0, 1);
    c.settings.maxIsometricForce = c.wires.upper;
    c.settings.minActivation = Eigen::VectorXd::Constant(numWires, 0.01);
    c.settings.maxActivation = Eigen::VectorXd::Ones(numWires);
    for (int i = 0; i < rows; ++i) {
        const double optimalForce = 1 + 4 * unit(rng);
        if (withReserves) c.settings.reserves.push_back(makeReserve("reserve" + std::to_string(i), i, optimalForce, -50, 50));
    }
    c.multiplier.resize(numWires);
    for (int w = 0; w < numWires; ++w) c.multiplier[w] = 0.5 + unit(rng);
    return c;
}

// The activation problem written out from its definition (dense): activations, reserve controls, free
// columns; every row an equality; bounds as the settings say; weights 2 (the QP's ½ Σ 2 x² = Σ x²).
DistributionProblem makeActivationProblem(const RandomCase& c) {
    const DistributionProblem& wires = c.wires;
    const int numWires = wires.getNumBounded(), rows = wires.getNumRows();
    const int numReserves = static_cast<int>(c.settings.reserves.size()), numBounded = numWires + numReserves;
    DistributionProblem reference;
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(rows, numBounded + wires.numFree);
    const Eigen::MatrixXd A = Eigen::MatrixXd(wires.A);
    for (int w = 0; w < numWires; ++w) dense.col(w) = A.col(w) * c.settings.maxIsometricForce[w] * c.multiplier[w];
    reference.lower.resize(numBounded);
    reference.upper.resize(numBounded);
    reference.lower.head(numWires) = c.settings.minActivation;
    reference.upper.head(numWires) = c.settings.maxActivation;
    for (int r = 0; r < numReserves; ++r) {
        const ReserveActuator& reserve = c.settings.reserves[static_cast<std::size_t>(r)];
        dense(reserve.dof, numWires + r) = reserve.optimalForce;
        reference.lower[numWires + r] = reserve.minControl;
        reference.upper[numWires + r] = reserve.maxControl;
    }
    dense.rightCols(wires.numFree) = A.rightCols(wires.numFree);
    reference.A = dense.sparseView();
    reference.numFree = wires.numFree;
    reference.cost.setZero(numBounded);
    reference.weight.setConstant(numBounded, 2.0);
    reference.target = wires.target;
    reference.tolerance.setZero(rows);
    reference.isEquality.assign(static_cast<std::size_t>(rows), true);
    return reference;
}

TEST(StaticOptimization, MatchesIpoptWithLoopsReservesAndBounds) {
    for (const test::RandomProblemOptions& base : test::makeProblemSweep(0.05, 0.6, 0.05)) {
        const RandomCase c = makeRandomCase(base, true);
        const DistributionProblem& wires = c.wires;
        const StaticOptimizationSettings& settings = c.settings;
        const int numWires = wires.getNumBounded();
        StaticOptimization so(settings);
        StaticOptimizationResult result;
        so.solve(wires, c.multiplier, result);
        const std::string name = test::describe(base);
        ASSERT_EQ(result.distribution.status, DistributionStatus::Optimal) << name;
        EXPECT_LE(result.distribution.kkt.getMax(), 1e-6) << name;

        // The same problem written out from its definition for Ipopt: activations, then reserve controls.
        const DistributionProblem reference = makeActivationProblem(c);
        const test::IpoptReference ipopt = test::solveWithIpopt(reference, test::DistributionNlp::Kind::Qp);
        ASSERT_TRUE(ipopt.solved) << name;
        const double objective = result.activation.squaredNorm() + result.reserveControl.squaredNorm();
        EXPECT_NEAR(objective, ipopt.objective, 1e-6 * ipopt.objective) << name;
        EXPECT_LE((result.activation - ipopt.x.head(numWires)).cwiseAbs().maxCoeff(), 1e-5) << name;
        EXPECT_GE(result.activation.minCoeff(), 0.01) << name;
        EXPECT_LE(result.activation.maxCoeff(), 1.0) << name;
        // Every DOF's generalized force is met exactly.
        EXPECT_LE(result.distribution.residual.cwiseAbs().maxCoeff(), 1e-6 * wires.target.cwiseAbs().maxCoeff()) << name;
    }
}

// OpenSim's static optimization with exponent p in tension units, as the test's own Ipopt problem:
// variables [wire tensions f (N); reserve forces (N m); loop forces], cost Σ |f_w / (F_w m_w)|^p +
// Σ |r / F_r|^p, every row of [A_wires, e_dof, G] [f; r; λ] = tau exact, f within [min, max] F_w m_w.
class TensionUnitsNlp : public Ipopt::TNLP {
public:
    TensionUnitsNlp(const RandomCase& c, double exponent) : p_(exponent), target_(c.wires.target) {
        const int numWires = c.wires.getNumBounded(), rows = c.wires.getNumRows();
        const int numReserves = static_cast<int>(c.settings.reserves.size());
        const Eigen::MatrixXd A(c.wires.A);
        M_ = Eigen::MatrixXd::Zero(rows, numWires + numReserves + c.wires.numFree);
        M_.leftCols(numWires) = A.leftCols(numWires);
        M_.rightCols(c.wires.numFree) = A.rightCols(c.wires.numFree);
        strength_.resize(numWires + numReserves);
        lower_.resize(numWires + numReserves);
        upper_.resize(numWires + numReserves);
        for (int w = 0; w < numWires; ++w) {
            strength_[w] = c.settings.maxIsometricForce[w] * c.multiplier[w];
            lower_[w] = c.settings.minActivation[w] * strength_[w];
            upper_[w] = c.settings.maxActivation[w] * strength_[w];
        }
        for (int r = 0; r < numReserves; ++r) {
            const ReserveActuator& reserve = c.settings.reserves[static_cast<std::size_t>(r)];
            M_(reserve.dof, numWires + r) = 1;
            strength_[numWires + r] = reserve.optimalForce;
            lower_[numWires + r] = reserve.minControl * reserve.optimalForce;
            upper_[numWires + r] = reserve.maxControl * reserve.optimalForce;
        }
    }
    bool solved = false;
    Eigen::VectorXd x;

    bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnzJacobian, Ipopt::Index& nnzHessian,
                      IndexStyleEnum& style) override {
        n = static_cast<Ipopt::Index>(M_.cols());
        m = static_cast<Ipopt::Index>(M_.rows());
        nnzJacobian = n * m;
        nnzHessian = static_cast<Ipopt::Index>(strength_.size());
        style = C_STYLE;
        return true;
    }
    bool get_bounds_info(Ipopt::Index n, Ipopt::Number* xl, Ipopt::Number* xu, Ipopt::Index m, Ipopt::Number* gl,
                         Ipopt::Number* gu) override {
        for (Ipopt::Index j = 0; j < n; ++j) {
            xl[j] = j < strength_.size() ? lower_[j] : -2e19;
            xu[j] = j < strength_.size() ? upper_[j] : 2e19;
        }
        for (Ipopt::Index i = 0; i < m; ++i) gl[i] = gu[i] = target_[i];
        return true;
    }
    bool get_starting_point(Ipopt::Index n, bool, Ipopt::Number* x0, bool, Ipopt::Number*, Ipopt::Number*,
                            Ipopt::Index, bool, Ipopt::Number*) override {
        for (Ipopt::Index j = 0; j < n; ++j) x0[j] = j < strength_.size() ? 0.5 * (lower_[j] + upper_[j]) : 0;
        return true;
    }
    bool eval_f(Ipopt::Index, const Ipopt::Number* x0, bool, Ipopt::Number& value) override {
        value = 0;
        for (Eigen::Index j = 0; j < strength_.size(); ++j) value += std::pow(std::abs(x0[j] / strength_[j]), p_);
        return true;
    }
    bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x0, bool, Ipopt::Number* g) override {
        for (Ipopt::Index j = 0; j < n; ++j) {
            const double s = j < strength_.size() ? strength_[j] : 0;
            g[j] = s > 0 ? p_ / s * std::pow(std::abs(x0[j] / s), p_ - 1) * (x0[j] < 0 ? -1 : 1) : 0;
        }
        return true;
    }
    bool eval_g(Ipopt::Index n, const Ipopt::Number* x0, bool, Ipopt::Index m, Ipopt::Number* g) override {
        Eigen::Map<Eigen::VectorXd>(g, m) = M_ * Eigen::Map<const Eigen::VectorXd>(x0, n);
        return true;
    }
    bool eval_jac_g(Ipopt::Index n, const Ipopt::Number*, bool, Ipopt::Index m, Ipopt::Index, Ipopt::Index* iRow,
                    Ipopt::Index* jCol, Ipopt::Number* values) override {
        for (Ipopt::Index i = 0, e = 0; i < m; ++i)
            for (Ipopt::Index j = 0; j < n; ++j, ++e) {
                if (values) values[e] = M_(i, j);
                else iRow[e] = i, jCol[e] = j;
            }
        return true;
    }
    bool eval_h(Ipopt::Index, const Ipopt::Number* x0, bool, Ipopt::Number factor, Ipopt::Index, const Ipopt::Number*,
                bool, Ipopt::Index, Ipopt::Index* iRow, Ipopt::Index* jCol, Ipopt::Number* values) override {
        for (Ipopt::Index j = 0; j < strength_.size(); ++j) {
            const double s = strength_[j];
            if (values) values[j] = factor * p_ * (p_ - 1) / (s * s) * std::pow(std::max(std::abs(x0[j] / s), 1e-12), p_ - 2);
            else iRow[j] = jCol[j] = j;
        }
        return true;
    }
    void finalize_solution(Ipopt::SolverReturn status, Ipopt::Index n, const Ipopt::Number* x0, const Ipopt::Number*,
                           const Ipopt::Number*, Ipopt::Index, const Ipopt::Number*, const Ipopt::Number*,
                           Ipopt::Number, const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
        solved = status == Ipopt::SUCCESS;
        x = Eigen::Map<const Eigen::VectorXd>(x0, n);
    }

private:
    double p_;
    Eigen::VectorXd target_, strength_, lower_, upper_;
    Eigen::MatrixXd M_;
};

TEST(StaticOptimization, ExponentsOtherThanTwoMatchIpoptInTensionUnits) {
    for (const double exponent : {1.5, 3.0}) {
        for (const test::RandomProblemOptions& base : test::makeProblemSweep(0.05, 0.6, 0.05)) {
            RandomCase c = makeRandomCase(base, true);
            c.settings.activationExponent = exponent;
            const std::string name = test::describe(base) + ", p = " + std::to_string(exponent);
            StaticOptimization so(c.settings);
            StaticOptimizationResult result;
            so.solve(c.wires, c.multiplier, result);
            ASSERT_EQ(result.distribution.status, DistributionStatus::Optimal) << name;
            EXPECT_TRUE(result.distribution.usedIpopt) << name;
            EXPECT_LE(result.distribution.kkt.getMax(), 1e-6) << name;

            Ipopt::SmartPtr<TensionUnitsNlp> nlp = new TensionUnitsNlp(c, exponent);
            Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
            app->Options()->SetNumericValue("tol", 1e-12);
            app->Options()->SetIntegerValue("print_level", 0);
            app->Options()->SetStringValue("sb", "yes");
            ASSERT_EQ(app->Initialize(), Ipopt::Solve_Succeeded);
            app->OptimizeTNLP(Ipopt::GetRawPtr(nlp));
            ASSERT_TRUE(nlp->solved) << name;
            const int numWires = c.wires.getNumBounded();
            const double objective = result.activation.array().abs().pow(exponent).sum() +
                                     result.reserveControl.array().abs().pow(exponent).sum();
            double reference = 0;
            for (int w = 0; w < numWires; ++w)
                reference += std::pow(nlp->x[w] / (c.settings.maxIsometricForce[w] * c.multiplier[w]), exponent);
            for (std::size_t r = 0; r < c.settings.reserves.size(); ++r)
                reference += std::pow(std::abs(nlp->x[numWires + static_cast<int>(r)]) / c.settings.reserves[r].optimalForce, exponent);
            EXPECT_NEAR(objective, reference, 1e-6 * reference) << name;
            EXPECT_NEAR(result.distribution.objective, objective, 1e-12 * objective) << name;
            EXPECT_LE((result.tension - nlp->x.head(numWires)).cwiseAbs().maxCoeff(), 1e-4 * c.wires.upper.maxCoeff()) << name;
            EXPECT_GE(result.activation.minCoeff(), 0.01) << name;
            EXPECT_LE(result.activation.maxCoeff(), 1.0) << name;
            EXPECT_LE(result.distribution.residual.cwiseAbs().maxCoeff(), 1e-6 * c.wires.target.cwiseAbs().maxCoeff()) << name;
        }
    }
}

// Ipopt's smallest L1 reserve of an activation problem: min Σ (s+ + s-) s.t. A x + s+ - s- = tau, x within its
// bounds, s >= 0 (the test's own LP, not sinew's phase 1).
double solveMinimalReserveWithIpopt(const DistributionProblem& problem) {
    const int rows = problem.getNumRows(), numBounded = problem.getNumBounded(), n = problem.getNumVariables();
    DistributionProblem lp = problem;
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(rows, n + 2 * rows);
    const Eigen::MatrixXd A(problem.A);
    dense.leftCols(numBounded) = A.leftCols(numBounded);
    dense.middleCols(numBounded, rows) = Eigen::MatrixXd::Identity(rows, rows);
    dense.middleCols(numBounded + rows, rows) = -Eigen::MatrixXd::Identity(rows, rows);
    dense.rightCols(problem.numFree) = A.rightCols(problem.numFree);
    lp.A = dense.sparseView();
    lp.lower.resize(numBounded + 2 * rows);
    lp.upper.resize(numBounded + 2 * rows);
    lp.cost.resize(numBounded + 2 * rows);
    lp.lower << problem.lower, Eigen::VectorXd::Zero(2 * rows);
    lp.upper << problem.upper, Eigen::VectorXd::Constant(2 * rows, INFINITY);
    lp.cost << Eigen::VectorXd::Zero(numBounded), Eigen::VectorXd::Ones(2 * rows);
    lp.weight.setOnes(numBounded + 2 * rows);
    const test::IpoptReference ipopt = test::solveWithIpopt(lp, test::DistributionNlp::Kind::Lp);
    EXPECT_TRUE(ipopt.solved);
    return ipopt.objective;
}

// Infeasible frames between feasible ones, for p = 2 (active set) and p = 3 (Ipopt): (a) a DOF no wire
// reaches, (b) a DOF needing far more than its wires' maximum. Each frame is reported: Infeasible with the
// smallest reserve (its L1 size Ipopt's minimum), the least-squares activations (Z no more than the
// reserve's own), within their bounds; the feasible frames after it are optimal as a fresh solver's.
TEST(StaticOptimization, InfeasibleFramesReportTheSmallestReserve) {
    for (const double exponent : {2.0, 3.0}) {
        for (const bool unreachable : {true, false}) {
            test::RandomProblemOptions o;
            o.rows = 8, o.wires = 30, o.unreachableRows = unreachable ? 1 : 0;
            o.tensionLow = 0.05, o.tensionHigh = 0.45;  // within reach of every wire (multipliers >= 0.5)
            o.seed = unreachable ? 7 : 8;
            RandomCase c = makeRandomCase(o, false);
            c.settings.activationExponent = exponent;
            const std::string name = std::string(unreachable ? "unreachable DOF" : "too weak DOF") + ", p = " +
                                     std::to_string(exponent);
            const Eigen::VectorXd feasibleTarget = c.wires.target;
            DistributionProblem infeasible = c.wires;
            if (unreachable) {
                infeasible.target[0] = 4.0;
            } else {  // row 3 asks for 10 times what all its wires could give at full activation
                double capacity = 0;
                for (int w = 0; w < c.wires.getNumBounded(); ++w)
                    capacity += std::abs(c.wires.A.coeff(3, w)) * c.settings.maxIsometricForce[w] * c.multiplier[w];
                infeasible.target[3] += 10 * capacity;
            }
            StaticOptimization so(c.settings);
            StaticOptimizationResult result, fresh;
            so.solve(c.wires, c.multiplier, result);
            ASSERT_EQ(result.distribution.status, DistributionStatus::Optimal) << name;

            so.solve(infeasible, c.multiplier, result);
            const DistributionResult& d = result.distribution;
            ASSERT_EQ(d.status, DistributionStatus::Infeasible) << name;
            RandomCase reference = c;
            reference.wires = infeasible;
            const double minimal = solveMinimalReserveWithIpopt(makeActivationProblem(reference));
            EXPECT_NEAR(d.reserve.lpNorm<1>(), minimal, 1e-6 * minimal) << name;
            if (unreachable) {
                EXPECT_NEAR(d.reserve[0], 4.0, 1e-9) << name;
                EXPECT_LE(d.reserve.tail(o.rows - 1).cwiseAbs().maxCoeff(), 1e-9) << name;
            }
            // The least-squares answer: its residual no larger than the minimal reserve itself (which is one).
            EXPECT_LE(d.torqueError, 0.5 * d.reserve.squaredNorm() * (1 + 1e-6)) << name;
            EXPECT_GT(d.torqueError, 0) << name;
            ASSERT_TRUE(result.activation.allFinite()) << name;
            EXPECT_GE(result.activation.minCoeff(), 0.01) << name;
            EXPECT_LE(result.activation.maxCoeff(), 1.0) << name;
            EXPECT_EQ(result.tension, result.activation.cwiseProduct(c.settings.maxIsometricForce).cwiseProduct(c.multiplier))
                << name;

            DistributionProblem next = c.wires;
            next.target = 0.9 * feasibleTarget;
            so.solve(next, c.multiplier, result);
            StaticOptimization(c.settings).solve(next, c.multiplier, fresh);
            ASSERT_EQ(result.distribution.status, DistributionStatus::Optimal) << name;
            EXPECT_LE((result.activation - fresh.activation).cwiseAbs().maxCoeff(), 1e-6) << name;
        }
    }
}

TEST(StaticOptimization, RefusesBadSettings) {
    StaticOptimizationSettings settings;
    settings.maxIsometricForce = Eigen::Vector2d(100, -1);
    EXPECT_THROW(StaticOptimization{settings}, Error);
    settings.maxIsometricForce = Eigen::Vector2d(100, 100);
    settings.activationExponent = 0.5;  // not convex
    EXPECT_THROW(StaticOptimization{settings}, Error);
}

}  // namespace
}  // namespace sinew

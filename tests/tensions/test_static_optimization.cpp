// OpenSim-style static optimization: a hand-worked two-muscle joint, and Ipopt on random problems with
// loops, reserves and activation bounds.
#include <gtest/gtest.h>

#include <cmath>

#include "support/ipopt_reference.hpp"
#include "support/random_distribution_problems.hpp"
#include "sinew/core/error.hpp"
#include "sinew/tensions/static_optimization.hpp"

namespace sinew {
namespace {

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
    settings.reserves.push_back({"reserve", 0, 10.0});
    StaticOptimization withReserve(settings);
    withReserve.solve(wires, multiplier, result);
    ASSERT_EQ(result.distribution.status, DistributionStatus::Optimal);
    const double rest = 40.0 - c[0];
    EXPECT_NEAR(result.activation[1], rest * c[1] / (c[1] * c[1] + 100), 1e-10);
    EXPECT_NEAR(result.reserveForce[0], rest * 100 / (c[1] * c[1] + 100), 1e-9);
}

TEST(StaticOptimization, MatchesIpoptWithLoopsReservesAndBounds) {
    for (const test::RandomProblemOptions& base : test::makeProblemSweep(0.05, 0.6, 0.05)) {
        const DistributionProblem wires = test::makeRandomProblem(base);
        const int numWires = wires.getNumBounded(), rows = wires.getNumRows();
        std::mt19937 rng(base.seed);
        std::uniform_real_distribution<double> unit(0, 1);
        StaticOptimizationSettings settings;
        settings.maxIsometricForce = wires.upper;
        settings.minActivation = Eigen::VectorXd::Constant(numWires, 0.01);
        settings.maxActivation = Eigen::VectorXd::Ones(numWires);
        for (int i = 0; i < rows; ++i) settings.reserves.push_back({"reserve" + std::to_string(i), i, 1 + 4 * unit(rng), -50, 50});
        Eigen::VectorXd multiplier(numWires);
        for (int w = 0; w < numWires; ++w) multiplier[w] = 0.5 + unit(rng);
        StaticOptimization so(settings);
        StaticOptimizationResult result;
        so.solve(wires, multiplier, result);
        const std::string name = test::describe(base);
        ASSERT_EQ(result.distribution.status, DistributionStatus::Optimal) << name;
        EXPECT_LE(result.distribution.kkt.getMax(), 1e-6) << name;

        // The same problem written out from its definition for Ipopt: activations, then reserve controls.
        DistributionProblem reference;
        Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(rows, numWires + rows + wires.numFree);
        const Eigen::MatrixXd A = Eigen::MatrixXd(wires.A);
        for (int w = 0; w < numWires; ++w) dense.col(w) = A.col(w) * settings.maxIsometricForce[w] * multiplier[w];
        for (int i = 0; i < rows; ++i) dense(i, numWires + i) = settings.reserves[static_cast<std::size_t>(i)].optimalForce;
        dense.rightCols(wires.numFree) = A.rightCols(wires.numFree);
        reference.A = dense.sparseView();
        reference.numFree = wires.numFree;
        reference.lower.resize(numWires + rows);
        reference.upper.resize(numWires + rows);
        reference.lower << settings.minActivation, Eigen::VectorXd::Constant(rows, -50);
        reference.upper << settings.maxActivation, Eigen::VectorXd::Constant(rows, 50);
        reference.cost.setZero(numWires + rows);
        reference.weight.setConstant(numWires + rows, 2.0);
        reference.target = wires.target;
        reference.tolerance.setZero(rows);
        reference.isEquality.assign(static_cast<std::size_t>(rows), true);
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

TEST(StaticOptimization, RefusesBadSettings) {
    StaticOptimizationSettings settings;
    settings.maxIsometricForce = Eigen::Vector2d(100, -1);
    EXPECT_THROW(StaticOptimization{settings}, Error);
    settings.maxIsometricForce = Eigen::Vector2d(100, 100);
    settings.activationExponent = 3;
    EXPECT_THROW(StaticOptimization{settings}, Error);
}

}  // namespace
}  // namespace sinew

// The active-set QP against Ipopt on random problems with the degeneracies of real models, its warm start
// against cold solves, the Ipopt fallback against the uncapped active set, its infeasibility report, the
// KKT residuals it reports, and its proximal steps against Ipopt's least squares and the LP.
#include <gtest/gtest.h>

#include <cmath>

#include "support/ipopt_reference.hpp"
#include "support/random_distribution_problems.hpp"
#include "sinew/core/error.hpp"
#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/ipopt_solver.hpp"
#include "sinew/tensions/lp_solver.hpp"

namespace sinew {
namespace {

using test::DistributionNlp;

// The regularised QP itself (the proximal steps move its answer to a least-squares one, which Ipopt's QP
// of the same weights does not find).
ActiveSetOptions regularisedOnly() {
    ActiveSetOptions options;
    options.proximalSteps = 0;
    return options;
}

void expectWithinBounds(const DistributionProblem& p, const Eigen::VectorXd& x, const std::string& name) {
    ASSERT_TRUE(x.allFinite()) << name;
    for (int j = 0; j < p.getNumBounded(); ++j) {
        EXPECT_GE(x[j], p.lower[j]) << name << " variable " << j;
        EXPECT_LE(x[j], p.upper[j]) << name << " variable " << j;
    }
}

TEST(ActiveSetSolver, MatchesIpoptOnRandomDegenerateProblems) {
    // Tensions of the targets in [-0.5, 1.5] x maximum, plus noise: bounds active on both sides.
    for (const test::RandomProblemOptions& o : test::makeProblemSweep(-0.5, 1.5, 0.1)) {
        const DistributionProblem p = test::makeRandomProblem(o);
        ActiveSetSolver solver(regularisedOnly());
        DistributionResult result;
        solver.solve(p, result);
        const std::string name = test::describe(o);
        ASSERT_EQ(result.status, DistributionStatus::Optimal) << name;
        EXPECT_LE(result.kkt.getMax(), 1e-6) << name;
        expectWithinBounds(p, result.x, name);
        const test::IpoptReference reference = test::solveWithIpopt(p, DistributionNlp::Kind::Qp);
        ASSERT_TRUE(reference.solved) << name;
        EXPECT_NEAR(result.objective, reference.objective, 1e-6 * std::abs(reference.objective)) << name;
        // The strictly convex QP has one answer.
        EXPECT_LE((result.x.head(p.getNumBounded()) - reference.x.head(p.getNumBounded())).cwiseAbs().maxCoeff(),
                  1e-4 * p.upper.maxCoeff())
            << name;
    }
}

TEST(ActiveSetSolver, WarmStartsGiveTheColdAnswer) {
    // A smooth sequence: the same pattern, values drifting.
    test::RandomProblemOptions o;
    o.rows = 20, o.wires = 70, o.numFree = 3, o.numEquality = 2, o.duplicateWires = 2, o.unreachableRows = 1;
    o.tensionLow = -0.3, o.tensionHigh = 1.3, o.noise = 0.05;
    const DistributionProblem base = test::makeRandomProblem(o);
    ActiveSetSolver warm;
    DistributionResult warmResult, coldResult;
    int warmIterations = 0, coldIterations = 0;
    for (int frame = 0; frame < 20; ++frame) {
        DistributionProblem p = base;
        for (int k = 0; k < p.A.nonZeros(); ++k) p.A.valuePtr()[k] *= 1 + 0.02 * std::sin(0.3 * frame + k);
        for (int i = 0; i < p.getNumRows(); ++i)
            if (!p.isEquality[static_cast<std::size_t>(i)]) p.target[i] *= 1 + 0.05 * std::cos(0.2 * frame + i);
        p.target.tail(o.numEquality) = (p.A * Eigen::VectorXd::Constant(p.getNumVariables(), 10.0)).tail(o.numEquality);
        warm.solve(p, warmResult);
        ActiveSetSolver cold;
        cold.solve(p, coldResult);
        ASSERT_EQ(warmResult.status, DistributionStatus::Optimal) << "frame " << frame;
        ASSERT_EQ(coldResult.status, DistributionStatus::Optimal) << "frame " << frame;
        EXPECT_LE((warmResult.x - coldResult.x).cwiseAbs().maxCoeff(), 1e-6 * p.upper.maxCoeff()) << "frame " << frame;
        EXPECT_LE(warmResult.kkt.getMax(), 1e-6) << "frame " << frame;
        if (frame > 0) warmIterations += warmResult.iterations, coldIterations += coldResult.iterations;
    }
    EXPECT_LT(warmIterations, coldIterations);
}

// Targets the wires meet within their bounds (Z* = 0), drifting frame to frame: the proximal steps stop at
// the residual floor (ActiveSetOptions::proximalResidualFloor) from the LP's answer, warm from the last
// frame, in fewer Newton steps than cold solves; each answer is the last step's optimum (KKT), meets the
// equality rows and has at most the LP's Z.
TEST(ActiveSetSolver, ReachableTargetsStopAtTheResidualFloorWarmFromTheLastFrame) {
    test::RandomProblemOptions o;
    o.rows = 20, o.wires = 70, o.numFree = 3, o.numEquality = 2, o.duplicateWires = 2;
    o.tensionLow = 0.1, o.tensionHigh = 0.9, o.noise = 0;
    const DistributionProblem base = test::makeRandomProblem(o);
    ActiveSetSolver warm;
    DistributionResult warmResult, coldResult, lpResult;
    int warmIterations = 0, coldIterations = 0;
    for (int frame = 0; frame < 20; ++frame) {
        DistributionProblem p = base;
        for (int k = 0; k < p.A.nonZeros(); ++k) p.A.valuePtr()[k] *= 1 + 0.02 * std::sin(0.3 * frame + k);
        Eigen::VectorXd x = Eigen::VectorXd::Constant(p.getNumVariables(), 0.0);
        for (int j = 0; j < p.getNumBounded(); ++j) x[j] = p.upper[j] * (0.5 + 0.3 * std::sin(0.1 * frame + j));
        p.target = p.A * x;
        warm.solve(p, warmResult);
        ActiveSetSolver cold;
        cold.solve(p, coldResult);
        LpSolver lp;
        lp.solve(p, lpResult);
        const std::string name = "frame " + std::to_string(frame);
        ASSERT_EQ(warmResult.status, DistributionStatus::Optimal) << name;
        ASSERT_EQ(coldResult.status, DistributionStatus::Optimal) << name;
        ASSERT_EQ(lpResult.status, DistributionStatus::Optimal) << name;
        expectWithinBounds(p, warmResult.x, name);
        EXPECT_LE(warmResult.kkt.getMax(), 1e-6) << name;
        const double floorResidual = ActiveSetOptions{}.proximalResidualFloor * p.target.cwiseAbs().maxCoeff();
        const double floorError = 0.5 * (p.getNumRows() - o.numEquality) * floorResidual * floorResidual;
        EXPECT_LE(warmResult.torqueError, floorError) << name;
        EXPECT_LE(coldResult.torqueError, floorError) << name;
        EXPECT_LE(warmResult.torqueError, lpResult.torqueError * (1 + 1e-9)) << name;
        const Eigen::VectorXd residual = p.target - p.A * warmResult.x;
        for (int i = 0; i < p.getNumRows(); ++i) {
            if (p.isEquality[static_cast<std::size_t>(i)]) {
                EXPECT_LE(std::abs(residual[i]), 1e-6 * p.target.cwiseAbs().maxCoeff()) << name;
            }
        }
        if (frame > 0) warmIterations += warmResult.iterations, coldIterations += coldResult.iterations;
    }
    EXPECT_LT(warmIterations, coldIterations);
}

TEST(ActiveSetSolver, IpoptFallbackGivesTheActiveSetOptimum) {
    // An iteration cap of 1 makes the active set fail on every one of these problems; the frame then goes to
    // Ipopt (in the library), which must land on the optimum the uncapped active set finds.
    int fallbacks = 0;
    for (const test::RandomProblemOptions& o : test::makeProblemSweep(-0.5, 1.5, 0.1)) {
        const DistributionProblem p = test::makeRandomProblem(o);
        const std::string name = test::describe(o);
        ActiveSetSolver uncapped(regularisedOnly());
        DistributionResult reference;
        uncapped.solve(p, reference);
        ASSERT_EQ(reference.status, DistributionStatus::Optimal) << name;
        ASSERT_FALSE(reference.usedIpopt) << name;

        ActiveSetOptions capped = regularisedOnly();
        capped.maxIterations = 1;
        ActiveSetSolver withFallback(capped);
        DistributionResult result;
        withFallback.solve(p, result);
        if (reference.iterations <= 1) continue;  // solved in one step: no fallback needed
        ++fallbacks;
        EXPECT_TRUE(result.usedIpopt) << name;
        ASSERT_EQ(result.status, DistributionStatus::Optimal) << name;
        EXPECT_LE(result.kkt.getMax(), 1e-6) << name;
        expectWithinBounds(p, result.x, name);
        EXPECT_NEAR(result.objective, reference.objective, 1e-6 * std::abs(reference.objective)) << name;
        EXPECT_LE((result.x.head(p.getNumBounded()) - reference.x.head(p.getNumBounded())).cwiseAbs().maxCoeff(),
                  1e-4 * p.upper.maxCoeff())
            << name;
        EXPECT_LE((result.multipliers - reference.multipliers).cwiseAbs().maxCoeff(),
                  1e-4 * std::max(1.0, reference.multipliers.cwiseAbs().maxCoeff()))
            << name;

        // Ipopt's own answer (before the fallback's polishing Newton steps) is the optimum too.
        IpoptSolver ipopt;
        DistributionResult direct;
        ipopt.solve(p, 2.0, direct);
        ASSERT_EQ(direct.status, DistributionStatus::Optimal) << name;
        EXPECT_TRUE(direct.usedIpopt) << name;
        expectWithinBounds(p, direct.x, name);
        EXPECT_NEAR(direct.objective, reference.objective, 1e-6 * std::abs(reference.objective)) << name;
        EXPECT_LE((direct.x.head(p.getNumBounded()) - reference.x.head(p.getNumBounded())).cwiseAbs().maxCoeff(),
                  1e-4 * p.upper.maxCoeff())
            << name;
        EXPECT_LE(direct.kkt.getMax(), 1e-1) << name;  // an interior point: near the bounds, not on them

        // Without the fallback the capped frame is reported as failed, never as optimal.
        capped.ipoptFallback = false;
        ActiveSetSolver noFallback(capped);
        noFallback.solve(p, result);
        EXPECT_EQ(result.status, DistributionStatus::Failed) << name;
        EXPECT_FALSE(result.usedIpopt) << name;
        expectWithinBounds(p, result.x, name);
    }
    EXPECT_GE(fallbacks, 10);  // 11 of the 12 need more than one step
}

TEST(ActiveSetSolver, ProximalStepsReachTheLeastSquaresOfIpoptAndNoMoreErrorThanTheLp) {
    // Reference: Ipopt's QP with the weights a millionth of the solver's, whose Z is near the least-squares
    // minimum. Targets outside the bounds' reach (tensions in [-0.5, 1.5] x maximum) and
    // within it (the LP then meets every band, Z <= ½ Σ δ²).
    int regulariserVisible = 0;
    for (const double high : {1.5, 0.9}) {
        const double low = high > 1 ? -0.5 : 0.1;
        for (const test::RandomProblemOptions& o : test::makeProblemSweep(low, high, high > 1 ? 0.1 : 0.0)) {
            const DistributionProblem p = test::makeRandomProblem(o);
            const std::string name = test::describe(o);
            ActiveSetSolver regularised(regularisedOnly()), proximal;
            DistributionResult first, refined;
            regularised.solve(p, first);
            proximal.solve(p, refined);
            ASSERT_EQ(refined.status, DistributionStatus::Optimal) << name;
            expectWithinBounds(p, refined.x, name);
            EXPECT_LE(refined.torqueError, first.torqueError) << name;

            DistributionProblem leastSquares = p;
            leastSquares.weight *= 1e-6;
            const test::IpoptReference reference = test::solveWithIpopt(leastSquares, DistributionNlp::Kind::Qp);
            ASSERT_TRUE(reference.solved) << name;
            const Eigen::VectorXd referenceResidual = p.target - p.A * reference.x;
            const double referenceZ = 0.5 * referenceResidual.squaredNorm();
            // Z at Ipopt's optimum exceeds the least-squares minimum Z(x*) by at most ½ w ‖x*‖²; x* is the refined x.
            const double regulariserEnergy = 0.5 * leastSquares.weight.dot(refined.x.head(p.getNumBounded()).cwiseAbs2());
            const double slack = 1e-6 * first.torqueError + regulariserEnergy + 1e-12;
            EXPECT_LE(refined.torqueError, referenceZ + slack) << name;
            // Lower than Ipopt's is fine (Ipopt stops at its tolerance), if it is the Z of an x that meets the rows.
            const Eigen::VectorXd residual = p.target - p.A * refined.x;
            EXPECT_NEAR(refined.torqueError, 0.5 * residual.squaredNorm(), 1e-12 * (1 + refined.torqueError)) << name;
            const double rowScale = std::max({1.0, p.target.cwiseAbs().maxCoeff(), (p.A * refined.x).cwiseAbs().maxCoeff()});
            for (int i = 0; i < p.getNumRows(); ++i) {
                if (p.isEquality[static_cast<std::size_t>(i)]) {
                    EXPECT_LE(std::abs(residual[i]), 1e-6 * rowScale) << name << " row " << i;
                }
            }
            // The last proximal step's QP; where the targets are met to roundoff its gradient is roundoff too.
            if (refined.torqueError > 1e-20 * rowScale * rowScale) {
                EXPECT_LE(refined.kkt.getMax(), 1e-6) << name;
            }
            if (refined.torqueError < 1e-3 * first.torqueError) ++regulariserVisible;

            if (high < 1) {
                LpSolver lp;
                DistributionResult banded;
                lp.solve(p, banded);
                ASSERT_EQ(banded.status, DistributionStatus::Optimal) << name;
                EXPECT_LE(refined.torqueError, banded.torqueError * (1 + 1e-9)) << name;
            }
        }
    }
    // The regulariser's error, which the steps remove, is most of Z wherever the bounds let the targets be met.
    EXPECT_GE(regulariserVisible, 12);
}

// Two wires through a massless node must balance (an equality row, as a virtual link's) while the tolerance
// rows pull one to 2000 N and the other to 0: the node's multiplier is about 1000 N, which the dual's
// equality regulariser (1e-12 of the mean a^2 / w) turns into a 1 mN imbalance unless the answer is moved
// onto the row. Exact answers: regularised, f = 2000 / (2 + 2 w); least squares, 1000.
TEST(ActiveSetSolver, EqualityRowsHoldExactlyAgainstAHardPull) {
    DistributionProblem p;
    std::vector<Eigen::Triplet<double>> entries = {{0, 0, 1}, {0, 1, -1}, {1, 0, 1}, {2, 1, 1}};
    p.A.resize(3, 2);
    p.A.setFromTriplets(entries.begin(), entries.end());
    p.A.makeCompressed();
    p.lower = Eigen::VectorXd::Zero(2);
    p.upper = Eigen::VectorXd::Constant(2, 1e4);
    p.cost = Eigen::VectorXd::Ones(2);
    const double w = 1e-6;  // the wire problem's regulariser times the mean |a_j|^2 (1)
    p.weight = Eigen::VectorXd::Constant(2, w);
    p.target = Eigen::Vector3d(0, 2000, 0);
    p.tolerance = Eigen::Vector3d(0, 1e-3, 1e-3);
    p.isEquality = {true, false, false};
    for (const bool leastSquares : {false, true}) {
        ActiveSetSolver solver(leastSquares ? ActiveSetOptions() : regularisedOnly());
        DistributionResult result;
        solver.solve(p, result);
        ASSERT_EQ(result.status, DistributionStatus::Optimal);
        expectWithinBounds(p, result.x, leastSquares ? "least squares" : "regularised");
        EXPECT_LE(std::abs(result.residual[0]), 1e-9) << "the node's imbalance, N";
        EXPECT_NEAR(result.residual[0], p.target[0] - (p.A * result.x)[0], 1e-12);
        const double exact = leastSquares ? 1000 : 2000 / (2 + 2 * w);
        EXPECT_NEAR(result.x[0], exact, 1e-6 * exact);
        EXPECT_NEAR(result.x[1], exact, 1e-6 * exact);
        EXPECT_NEAR(result.torqueError, 0.5 * (p.target - p.A * result.x).squaredNorm(), 1e-9);
    }
}

TEST(ActiveSetSolver, UnreachableEqualityRowIsInfeasibleWithItsReserve) {
    test::RandomProblemOptions o;
    o.unreachableRows = 1;
    DistributionProblem p = test::makeRandomProblem(o);
    p.isEquality[0] = true;  // no column reaches row 0
    p.target[0] = 3.5;
    ActiveSetSolver solver;
    DistributionResult result;
    solver.solve(p, result);
    EXPECT_EQ(result.status, DistributionStatus::Infeasible);
    EXPECT_NEAR(result.reserve[0], 3.5, 1e-9);
    EXPECT_EQ(result.reserve.tail(p.getNumRows() - 1).cwiseAbs().maxCoeff(), 0);
    expectWithinBounds(p, result.x, "unreachable");
    // The other rows are solved as if row 0 were not there (it has no column).
    p.isEquality[0] = false;
    DistributionResult relaxed;
    solver.solve(p, relaxed);
    EXPECT_LE((result.x - relaxed.x).cwiseAbs().maxCoeff(), 1e-6 * p.upper.maxCoeff());
}

TEST(ActiveSetSolver, KktResidualsDetectAWrongAnswer) {
    const DistributionProblem p = test::makeRandomProblem(test::makeProblemSweep(-0.5, 1.5, 0.1)[5]);
    ActiveSetSolver solver;
    DistributionResult result;
    solver.solve(p, result);
    ASSERT_LE(result.kkt.getMax(), 1e-6);
    // Move one free (interior) variable: the projected gradient no longer vanishes.
    Eigen::VectorXd x = result.x;
    for (int j = 0; j < p.getNumBounded(); ++j)
        if (x[j] > p.lower[j] + 1 && x[j] < p.upper[j] - 1) {
            x[j] += 1;
            break;
        }
    EXPECT_GT(calcQpKktResiduals(p, x, result.multipliers).dual, 1e-4);
}

TEST(ActiveSetSolver, RefusesMalformedProblems) {
    DistributionProblem p = test::makeRandomProblem({});
    p.weight[3] = 0;
    ActiveSetSolver solver;
    DistributionResult result;
    try {
        solver.solve(p, result);
        FAIL() << "a zero weight was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("weight[3]"), std::string::npos) << e.what();
    }
    p = test::makeRandomProblem({});
    p.target.resize(3);
    EXPECT_THROW(solver.solve(p, result), Error);
}

}  // namespace
}  // namespace sinew

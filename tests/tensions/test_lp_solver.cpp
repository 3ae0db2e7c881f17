// The Clp LP against Ipopt on random problems with the degeneracies of real models, warm starts against
// cold solves, the phase-1 reserve of infeasible frames, and Z(QP) <= Z(LP).
#include <gtest/gtest.h>

#include <cmath>

#include "support/ipopt_reference.hpp"
#include "support/random_distribution_problems.hpp"
#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/lp_solver.hpp"

namespace sinew {
namespace {

using test::DistributionNlp;

TEST(LpSolver, MatchesIpoptOnRandomDegenerateProblems) {
    // Targets made by tensions inside their bounds: every LP is feasible.
    for (const test::RandomProblemOptions& o : test::makeProblemSweep(0.1, 0.9, 0)) {
        const DistributionProblem p = test::makeRandomProblem(o);
        const std::string name = test::describe(o);
        LpSolver lp;
        DistributionResult result;
        lp.solve(p, result);
        ASSERT_EQ(result.status, DistributionStatus::Optimal) << name;
        EXPECT_LE(result.kkt.getMax(), 1e-6) << name;
        for (int j = 0; j < p.getNumBounded(); ++j) {
            EXPECT_GE(result.x[j], p.lower[j]) << name;
            EXPECT_LE(result.x[j], p.upper[j]) << name;
        }
        const test::IpoptReference reference = test::solveWithIpopt(p, DistributionNlp::Kind::Lp);
        ASSERT_TRUE(reference.solved) << name;
        EXPECT_NEAR(result.objective, reference.objective, 1e-6 * std::abs(reference.objective)) << name;

        // The regularised QP's optimality against the LP's point: Z + ½ Σ w f² can only be lower at its answer.
        ActiveSetOptions regularisedOnly;
        regularisedOnly.proximalSteps = 0;
        ActiveSetSolver qp(regularisedOnly);
        DistributionResult qpResult;
        qp.solve(p, qpResult);
        ASSERT_EQ(qpResult.status, DistributionStatus::Optimal) << name;
        const Eigen::VectorXd fLp = result.x.head(p.getNumBounded()), fQp = qpResult.x.head(p.getNumBounded());
        EXPECT_LE(qpResult.torqueError + 0.5 * p.weight.dot(fQp.cwiseAbs2()),
                  result.torqueError + 0.5 * p.weight.dot(fLp.cwiseAbs2()) + 1e-12 * p.target.squaredNorm())
            << name;
    }
}

TEST(LpSolver, TorqueErrorOfTheQpIsBelowTheLpsOnNoisyTargets) {
    // Noisy targets and a wide band: the LP lands on the band's edges, the QP (tiny regulariser) nearer.
    int compared = 0;
    for (const test::RandomProblemOptions& base : test::makeProblemSweep(0.1, 0.9, 0.05)) {
        test::RandomProblemOptions o = base;
        o.tolerance = 0.2;
        const DistributionProblem p = test::makeRandomProblem(o);
        LpSolver lp;
        ActiveSetSolver qp;
        DistributionResult lpResult, qpResult;
        lp.solve(p, lpResult);
        qp.solve(p, qpResult);
        if (lpResult.status != DistributionStatus::Optimal) continue;  // the noise left the reachable set
        ASSERT_EQ(qpResult.status, DistributionStatus::Optimal);
        EXPECT_LE(qpResult.torqueError, lpResult.torqueError * (1 + 1e-9) + 1e-9) << test::describe(o);
        ++compared;
    }
    EXPECT_GE(compared, 6);
}

// A motion's problems: a random base with 20 rows and 70 wires, its moment arms varying smoothly frame to
// frame, tau made by tensions of 100 to 300 N (times targetScale).
DistributionProblem makeMotionBase(int numEquality) {
    test::RandomProblemOptions o;
    o.rows = 20, o.wires = 70, o.numFree = 3, o.numEquality = numEquality, o.duplicateWires = 2, o.zeroWires = 2;
    return test::makeRandomProblem(o);
}

DistributionProblem makeMotionFrame(const DistributionProblem& base, int frame, double targetScale) {
    DistributionProblem p = base;
    for (int k = 0; k < p.A.nonZeros(); ++k) p.A.valuePtr()[k] *= 1 + 0.02 * std::sin(0.3 * frame + k);
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(p.getNumVariables(), 100, 300 + 5 * frame);
    p.target = p.A * x * targetScale;
    return p;
}

TEST(LpSolver, WarmStartsGiveTheColdAnswer) {
    const DistributionProblem base = makeMotionBase(2);
    LpSolver warm;
    DistributionResult warmResult, coldResult;
    int warmIterations = 0, coldIterations = 0;
    for (int frame = 0; frame < 20; ++frame) {
        const DistributionProblem p = makeMotionFrame(base, frame, 1.0);
        warm.solve(p, warmResult);
        LpSolver cold;
        cold.solve(p, coldResult);
        ASSERT_EQ(warmResult.status, DistributionStatus::Optimal) << "frame " << frame;
        ASSERT_EQ(coldResult.status, DistributionStatus::Optimal) << "frame " << frame;
        EXPECT_NEAR(warmResult.objective, coldResult.objective, 1e-9 * coldResult.objective) << "frame " << frame;
        EXPECT_LE(warmResult.kkt.getMax(), 1e-6) << "frame " << frame;
        if (frame > 0) warmIterations += warmResult.iterations, coldIterations += coldResult.iterations;
    }
    EXPECT_LT(warmIterations, coldIterations);
}

// A run of infeasible frames, as a motion has them: after the first, phase 1 goes first and starts from the
// last one's basis. Each frame's least reserves (their L1 norm: no equality rows, so phase 1 prices every
// row at 1) are those of a cold solver, in a fraction of the pivots; the feasible frame after the run is
// optimal again.
TEST(LpSolver, WarmInfeasibleFramesNeedTheColdReserves) {
    const DistributionProblem base = makeMotionBase(0);
    LpSolver warm;
    DistributionResult warmResult, coldResult;
    int warmIterations = 0, coldIterations = 0;
    for (int frame = 0; frame <= 20; ++frame) {
        const bool lastFrame = frame == 20;
        // 3x: beyond what the bounded tensions reach
        const DistributionProblem p = makeMotionFrame(base, frame, lastFrame ? 1.0 : 3.0);
        warm.solve(p, warmResult);
        LpSolver cold;
        cold.solve(p, coldResult);
        const DistributionStatus expected = lastFrame ? DistributionStatus::Optimal : DistributionStatus::Infeasible;
        ASSERT_EQ(coldResult.status, expected) << "frame " << frame;
        ASSERT_EQ(warmResult.status, expected) << "frame " << frame;
        const double coldReserve = coldResult.reserve.lpNorm<1>();
        EXPECT_NEAR(warmResult.reserve.lpNorm<1>(), coldReserve, 1e-9 * std::max(1.0, coldReserve)) << "frame " << frame;
        if (lastFrame) {
            EXPECT_NEAR(warmResult.objective, coldResult.objective, 1e-9 * coldResult.objective);
        }
        if (frame > 0) warmIterations += warmResult.iterations, coldIterations += coldResult.iterations;
    }
    // 183 pivots against the cold 2,821; phase 1 cold on every frame after the warm dual took 2,015.
    EXPECT_LT(4 * warmIterations, coldIterations);
}

TEST(LpSolver, InfeasibleFrameReportsTheMissingReservePerDof) {
    test::RandomProblemOptions o;
    o.unreachableRows = 2;
    DistributionProblem p = test::makeRandomProblem(o);
    p.target[1] = -4;  // no wire reaches DOF 1; DOF 0 stays at 0
    LpSolver lp;
    DistributionResult result;
    lp.solve(p, result);
    EXPECT_EQ(result.status, DistributionStatus::Infeasible);
    // The least reserve: |target| less the band, on that DOF only.
    EXPECT_NEAR(result.reserve[1], -4 + p.tolerance[1], 1e-9);
    result.reserve[1] = 0;
    EXPECT_LE(result.reserve.cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_TRUE(result.x.allFinite());
    // The next, feasible frame is solved again.
    p.target[1] = 0;
    lp.solve(p, result);
    EXPECT_EQ(result.status, DistributionStatus::Optimal);
}

// An infeasible frame's tensions: among the points that need phase 1's least reserves, the least total cost
// (Ipopt's LP with the reserves taken off tau), not whatever point phase 1 stopped at.
TEST(LpSolver, InfeasibleFramesTakeTheLeastCostAmongTheLeastReserves) {
    int checked = 0;
    for (const test::RandomProblemOptions& o : test::makeProblemSweep(0.1, 0.9, 0)) {
        DistributionProblem p = test::makeRandomProblem(o);
        p.target *= 3;  // beyond what the bounded tensions reach
        LpSolver lp;
        DistributionResult result;
        lp.solve(p, result);
        if (result.status != DistributionStatus::Infeasible) continue;
        const std::string name = test::describe(o);
        DistributionProblem withReserves = p;
        withReserves.target -= result.reserve;
        withReserves.tolerance.array() += 1e-9 * std::max(1.0, p.target.cwiseAbs().maxCoeff());
        const test::IpoptReference reference = test::solveWithIpopt(withReserves, DistributionNlp::Kind::Lp);
        ASSERT_TRUE(reference.solved) << name;
        const double cost = p.cost.dot(result.x.head(p.getNumBounded()));
        // Ipopt relaxes the bounds by 1e-8 relative: its cost comes out a few parts per million lower.
        EXPECT_NEAR(cost, reference.objective, 2e-5 * std::max(1.0, std::abs(reference.objective))) << name;
        ++checked;
    }
    EXPECT_GT(checked, 3);
}

}  // namespace
}  // namespace sinew

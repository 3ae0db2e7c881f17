// The Clp LP against Ipopt on random problems with the degeneracies of real models, warm starts against
// cold solves, the phase-1 reserve of infeasible frames, and Z(QP) <= Z(LP); the warm path's dual simplex
// against Clp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/ipopt_reference.hpp"
#include "support/random_distribution_problems.hpp"
#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/lp_solver.hpp"
#include "sinew/tensions/warm_dual_simplex.hpp"

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
    EXPECT_GE(warm.getWarmFrames(), 15);  // the rest went to Clp; each answer is checked above either way
}

// Feasible and infeasible frames alternating: after each feasible frame the warm path tries the next and finds
// its dual unbounded; phase 1 then gives the cold solver's least reserves, and the feasible frames their
// optimum.
TEST(LpSolver, InfeasibleFramesBetweenFeasibleOnesGetTheColdReserves) {
    const DistributionProblem base = makeMotionBase(0);
    LpSolver warm;
    DistributionResult warmResult, coldResult;
    for (int frame = 0; frame < 12; ++frame) {
        const bool feasible = frame % 2 == 0;
        const DistributionProblem p = makeMotionFrame(base, frame, feasible ? 1.0 : 3.0);
        warm.solve(p, warmResult);
        LpSolver cold;
        cold.solve(p, coldResult);
        const std::string name = "frame " + std::to_string(frame);
        ASSERT_EQ(coldResult.status, feasible ? DistributionStatus::Optimal : DistributionStatus::Infeasible) << name;
        ASSERT_EQ(warmResult.status, coldResult.status) << name;
        const double coldReserve = coldResult.reserve.lpNorm<1>();
        EXPECT_NEAR(warmResult.reserve.lpNorm<1>(), coldReserve, 1e-9 * std::max(1.0, coldReserve)) << name;
        if (feasible) {
            EXPECT_NEAR(warmResult.objective, coldResult.objective, 1e-9 * coldResult.objective) << name;
        }
    }
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

// The LP of a distribution problem in WarmDualSimplex's terms (the arrays kept alive by the struct).
struct WarmLp {
    std::vector<double> columnLower, columnUpper, cost, rowLower, rowUpper;
    LinearProgram lp;

    explicit WarmLp(const DistributionProblem& p) {
        const int rows = p.getNumRows(), columns = p.getNumVariables();
        columnLower.assign(static_cast<std::size_t>(columns), -1e300);
        columnUpper.assign(static_cast<std::size_t>(columns), 1e300);
        cost.assign(static_cast<std::size_t>(columns), 0.0);
        for (int j = 0; j < p.getNumBounded(); ++j)
            columnLower[static_cast<std::size_t>(j)] = p.lower[j], columnUpper[static_cast<std::size_t>(j)] = p.upper[j],
                                                    cost[static_cast<std::size_t>(j)] = p.cost[j];
        for (int i = 0; i < rows; ++i) {
            const double band = p.isEquality[static_cast<std::size_t>(i)] ? 0 : p.tolerance[i];
            rowLower.push_back(p.target[i] - band);
            rowUpper.push_back(p.target[i] + band);
        }
        lp = {&p.A, columnLower.data(), columnUpper.data(), cost.data(), rowLower.data(), rowUpper.data()};
    }
};

// Every row's activity basic, the tensions at their lower bound, the free columns nonbasic and free: dual
// feasible whenever the costs are >= 0, so the dual simplex can start there.
std::vector<unsigned char> makeSlackBasis(const DistributionProblem& p) {
    std::vector<unsigned char> status(static_cast<std::size_t>(p.getNumVariables() + p.getNumRows()),
                                      static_cast<unsigned char>(SimplexStatus::Basic));
    for (int j = 0; j < p.getNumVariables(); ++j)
        status[static_cast<std::size_t>(j)] =
            static_cast<unsigned char>(j < p.getNumBounded() ? SimplexStatus::AtLower : SimplexStatus::Free);
    return status;
}

// WarmDualSimplex's answer against Clp's (a cold LpSolver): the optimal cost to 1e-9, the KKT conditions
// from its own x and duals, x within the bounds.
void expectClpsOptimum(const DistributionProblem& p, const WarmDualSimplex& simplex, const std::string& name) {
    LpSolver clp;
    DistributionResult reference;
    clp.solve(p, reference);
    ASSERT_EQ(reference.status, DistributionStatus::Optimal) << name;
    const Eigen::VectorXd& x = simplex.getColumnValues();
    EXPECT_NEAR(p.cost.dot(x.head(p.getNumBounded())), reference.objective, 1e-9 * std::abs(reference.objective)) << name;
    EXPECT_LE(calcLpKktResiduals(p, x, simplex.getRowDuals()).getMax(), 1e-9) << name;
    for (int j = 0; j < p.getNumBounded(); ++j) {
        EXPECT_GE(x[j], p.lower[j] - 1e-9) << name;
        EXPECT_LE(x[j], p.upper[j] + 1e-9) << name;
    }
}

TEST(WarmDualSimplex, FromTheSlackBasisReachesClpsOptimumOnRandomDegenerateProblems) {
    // Duplicate and zero wires, unreachable DOFs, free columns and equality rows (makeProblemSweep).
    WarmDualSimplexOptions options;
    options.maxPivots = 1000;
    options.refactorEvery = 7;  // several fresh factorisations inside a solve
    for (const test::RandomProblemOptions& o : test::makeProblemSweep(0.1, 0.9, 0)) {
        const DistributionProblem p = test::makeRandomProblem(o);
        const WarmLp lp(p);
        std::vector<unsigned char> status = makeSlackBasis(p);
        WarmDualSimplex simplex;
        ASSERT_EQ(simplex.solve(lp.lp, status, options), WarmDualOutcome::Optimal) << test::describe(o);
        EXPECT_GT(simplex.getPivots(), 0);
        expectClpsOptimum(p, simplex, test::describe(o));
    }
}

TEST(WarmDualSimplex, ReSolvesAMotionFromEachFramesOptimalBasis) {
    const DistributionProblem base = makeMotionBase(2);
    WarmDualSimplex simplex;
    std::vector<unsigned char> status = makeSlackBasis(base);
    WarmDualSimplexOptions fromSlacks;
    fromSlacks.maxPivots = 1000;
    int warmPivots = 0, slackPivots = 0;
    for (int frame = 0; frame < 20; ++frame) {
        const DistributionProblem p = makeMotionFrame(base, frame, 1.0);
        const WarmLp lp(p);
        const std::string name = "frame " + std::to_string(frame);
        ASSERT_EQ(simplex.solve(lp.lp, status, fromSlacks), WarmDualOutcome::Optimal) << name;
        expectClpsOptimum(p, simplex, name);
        if (frame == 0) continue;
        warmPivots += simplex.getPivots();
        WarmDualSimplex cold;
        std::vector<unsigned char> slacks = makeSlackBasis(p);
        ASSERT_EQ(cold.solve(lp.lp, slacks, fromSlacks), WarmDualOutcome::Optimal) << name;
        slackPivots += cold.getPivots();
    }
    EXPECT_LT(warmPivots, slackPivots / 4);
}

// Columns with no upper bound (the contact forces'): a reduced cost that turns negative at the lower bound
// has no other bound to flip to, and gets an artificial one that the optimum must leave.
TEST(WarmDualSimplex, ReSolvesAMotionWhoseColumnsHaveNoCap) {
    DistributionProblem base = makeMotionBase(2);
    base.upper.setConstant(std::numeric_limits<double>::infinity());
    WarmDualSimplex simplex;
    std::vector<unsigned char> status = makeSlackBasis(base);
    WarmDualSimplexOptions options;
    options.maxPivots = 1000;
    int optimal = 0;
    for (int frame = 0; frame < 20; ++frame) {
        const DistributionProblem p = makeMotionFrame(base, frame, 1.0);
        const WarmLp lp(p);
        const std::string name = "frame " + std::to_string(frame);
        const std::vector<unsigned char> before = status;
        const WarmDualOutcome outcome = simplex.solve(lp.lp, status, options);
        if (outcome != WarmDualOutcome::Optimal) {
            EXPECT_EQ(outcome, WarmDualOutcome::NotDualFeasible) << name;
            EXPECT_EQ(status, before) << name;
            status = makeSlackBasis(p);
            ASSERT_EQ(simplex.solve(lp.lp, status, options), WarmDualOutcome::Optimal) << name;
        } else {
            ++optimal;
        }
        expectClpsOptimum(p, simplex, name);
    }
    EXPECT_GE(optimal, 15);
}

TEST(WarmDualSimplex, LeavesWhatItCannotProveToClpWithTheBasisUnchanged) {
    const DistributionProblem base = makeMotionBase(0);
    const DistributionProblem feasible = makeMotionFrame(base, 0, 1.0);
    WarmDualSimplex simplex;
    // Beyond what the bounded tensions reach: no entering variable, the dual is unbounded.
    const DistributionProblem infeasible = makeMotionFrame(base, 0, 3.0);
    const WarmLp infeasibleLp(infeasible);
    std::vector<unsigned char> status = makeSlackBasis(infeasible);
    const std::vector<unsigned char> slacks = status;
    WarmDualSimplexOptions options;
    options.maxPivots = 1000;
    EXPECT_EQ(simplex.solve(infeasibleLp.lp, status, options), WarmDualOutcome::DualUnbounded);
    EXPECT_EQ(status, slacks);

    const WarmLp lp(feasible);
    options.maxPivots = 2;
    EXPECT_EQ(simplex.solve(lp.lp, status, options), WarmDualOutcome::TooManyPivots);
    EXPECT_EQ(status, slacks);

    // No basis of this problem: a status too few, a basic variable too few, a superbasic variable, a
    // variable at an infinite bound.
    std::vector<unsigned char> shortStatus(slacks.begin(), slacks.end() - 1);
    EXPECT_EQ(simplex.solve(lp.lp, shortStatus), WarmDualOutcome::NoBasis);
    std::vector<unsigned char> missingBasic = slacks;
    missingBasic.back() = static_cast<unsigned char>(SimplexStatus::AtLower);
    EXPECT_EQ(simplex.solve(lp.lp, missingBasic), WarmDualOutcome::NoBasis);
    std::vector<unsigned char> superBasic = slacks;
    superBasic[0] = static_cast<unsigned char>(SimplexStatus::SuperBasic);
    EXPECT_EQ(simplex.solve(lp.lp, superBasic), WarmDualOutcome::NoBasis);
    std::vector<unsigned char> freeAtLower = slacks;
    freeAtLower[static_cast<std::size_t>(feasible.getNumBounded())] = static_cast<unsigned char>(SimplexStatus::AtLower);
    EXPECT_EQ(simplex.solve(lp.lp, freeAtLower), WarmDualOutcome::NoBasis);

    // An unbounded LP, min -x1 + x2/2 s.t. 0 <= x1 - x2 <= 1, x >= 0: from the slack basis x1's reduced
    // cost sends it to an artificial bound, where the optimum of the bounded problem keeps it.
    Eigen::SparseMatrix<double> rayA(1, 2);
    rayA.insert(0, 0) = 1;
    rayA.insert(0, 1) = -1;
    rayA.makeCompressed();
    const double inf = std::numeric_limits<double>::infinity();
    const std::vector<double> zeros{0, 0}, infinities{inf, inf}, rayCost{-1, 0.5}, rowLow{0}, rowUp{1};
    const LinearProgram ray{&rayA, zeros.data(), infinities.data(), rayCost.data(), rowLow.data(), rowUp.data()};
    std::vector<unsigned char> rayBasis{static_cast<unsigned char>(SimplexStatus::AtLower),
                                        static_cast<unsigned char>(SimplexStatus::AtLower),
                                        static_cast<unsigned char>(SimplexStatus::Basic)};
    EXPECT_EQ(simplex.solve(ray, rayBasis), WarmDualOutcome::NotDualFeasible);
}

// A basis where a free column (a loop force) is nonbasic with a reduced cost that is not zero: it has no
// bound to flip to, gets an artificial one, and is pivoted into the basis on the way to Clp's optimum.
TEST(WarmDualSimplex, PivotsAFreeColumnInFromAnArtificialBound) {
    const DistributionProblem p = makeMotionFrame(makeMotionBase(0), 0, 1.0);
    const WarmLp lp(p);
    const int freeColumn = p.getNumBounded();
    int wire = -1, row = -1;
    for (int j = 0; j < freeColumn && wire < 0; ++j)
        for (Eigen::SparseMatrix<double>::InnerIterator it(p.A, j); it; ++it)
            if (it.value() != 0 && p.A.coeff(it.row(), freeColumn) != 0) {
                wire = j, row = static_cast<int>(it.row());
                break;
            }
    ASSERT_GE(wire, 0);
    std::vector<unsigned char> status = makeSlackBasis(p);  // the wire basic in its row's place: y != 0
    status[static_cast<std::size_t>(p.getNumVariables() + row)] = static_cast<unsigned char>(SimplexStatus::AtLower);
    status[static_cast<std::size_t>(wire)] = static_cast<unsigned char>(SimplexStatus::Basic);
    WarmDualSimplex simplex;
    WarmDualSimplexOptions options;
    options.maxPivots = 1000;
    ASSERT_EQ(simplex.solve(lp.lp, status, options), WarmDualOutcome::Optimal);
    expectClpsOptimum(p, simplex, "from the wire's basis");
}

}  // namespace
}  // namespace sinew

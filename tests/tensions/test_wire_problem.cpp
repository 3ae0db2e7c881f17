// The wire problem of a model: its columns against sinew's wire forces and loop velocities, and tensions
// (and loop forces) recovered from the generalized forces they produced by the LP, the QP and static
// optimization.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <random>

#include "sinew/core/data.hpp"
#include "sinew/core/kinematics.hpp"
#include "support/random_model.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/lp_solver.hpp"
#include "sinew/tensions/static_optimization.hpp"
#include "sinew/tensions/wire_problem.hpp"

namespace sinew {
namespace {

struct Frame {
    Eigen::VectorXd q, u;
    Eigen::MatrixXd J;
};

Frame makeFrame(const Model& model, Data& data, unsigned seed) {
    std::mt19937 rng(seed);
    Frame frame{generateRandomCoordinates(model, rng), generateRandomSpeeds(model, rng), {}};
    calcPositionKinematics(model, data, frame.q);
    calcVelocityKinematics(model, data, frame.u);
    calcWirePaths(model, data);
    frame.J.resize(model.getNumWires(), model.getNumU());
    calcWireJacobian(model, data, frame.J);
    return frame;
}

Model makeModel(int links, int wires, int loops, int virtualLinks, unsigned seed) {
    RandomModelOptions options;
    options.numLinks = links, options.numWires = wires, options.numLoops = loops;
    options.numVirtualLinks = virtualLinks, options.seed = seed;
    return generateRandomModel(options);
}

TEST(WireProblem, ColumnsAreWireForcesAndLoopConstraintDirections) {
    const Model model = makeModel(15, 40, 2, 1, 7);
    Data data(model);
    const Frame frame = makeFrame(model, data, 3);
    const WireProblemBuilder builder(model, Eigen::VectorXd::Constant(model.getNumWires(), 500));
    DistributionProblem problem = builder.makeProblem();
    builder.update(data, frame.J, Eigen::VectorXd::Zero(model.getNumU()), problem);

    // A f for the wires = sinew's generalized forces of the tensions, computed without J.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0, 1);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(problem.getNumVariables());
    Eigen::VectorXd tensions(model.getNumWires());
    for (int w = 0; w < model.getNumWires(); ++w) x[w] = tensions[w] = 500 * unit(rng);
    Eigen::VectorXd tau(model.getNumU());
    calcWireGeneralizedForces(model, data, tensions, tau);
    EXPECT_LE((problem.A * x - tau).cwiseAbs().maxCoeff(), 1e-10 * tau.cwiseAbs().maxCoeff());

    // Loop columns: G^T, i.e. column c . u = e_c . (velocity of B's loop point - velocity of A's).
    for (int l = 0; l < model.getNumLoops(); ++l) {
        const Loop& loop = model.getLoop(l);
        const auto pointVelocity = [&](int link, const Eigen::Vector3d& p_B) -> Eigen::Vector3d {
            const std::size_t k = static_cast<std::size_t>(link);
            return data.v_GB[k] + data.w_GB[k].cross(data.R_GB[k] * p_B);
        };
        const Eigen::Vector3d gap = pointVelocity(loop.linkB, loop.p_B) - pointVelocity(loop.linkA, loop.p_A);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(problem.A.col(model.getNumWires() + 3 * l + c).dot(frame.u), gap[c], 1e-10 * (1 + gap.norm()));
    }
    // Virtual links' DOFs are the equality rows.
    int equalities = 0;
    for (const bool e : problem.isEquality) equalities += e;
    EXPECT_EQ(equalities, 6);
}

// Fewer wires than DOFs and independent columns: the generalized forces determine the tensions and loop
// forces, and every method must give them back.
TEST(WireProblem, TensionsRecoveredFromTheTorquesTheyProduced) {
    const Model model = makeModel(12, 16, 1, 0, 11);
    Data data(model);
    const Frame frame = makeFrame(model, data, 4);
    const Eigen::VectorXd maxTension = Eigen::VectorXd::LinSpaced(model.getNumWires(), 200, 1200);
    WireProblemOptions options;
    options.torqueTolerance = 1e-9;
    options.regularization = 1e-14;
    const WireProblemBuilder builder(model, maxTension, options);
    DistributionProblem problem = builder.makeProblem();
    builder.update(data, frame.J, Eigen::VectorXd::Zero(model.getNumU()), problem);
    const Eigen::MatrixXd A = Eigen::MatrixXd(problem.A);
    ASSERT_LT(A.cols(), A.rows());
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A);
    ASSERT_GT(svd.singularValues().minCoeff(), 1e-4 * svd.singularValues().maxCoeff()) << "columns not independent";

    std::mt19937 rng(9);
    std::uniform_real_distribution<double> unit(0, 1);
    Eigen::VectorXd truth(problem.getNumVariables());
    for (int w = 0; w < model.getNumWires(); ++w) truth[w] = (0.2 + 0.6 * unit(rng)) * maxTension[w];
    for (int k = 0; k < problem.numFree; ++k) truth[model.getNumWires() + k] = 100 * (unit(rng) - 0.5);
    builder.update(data, frame.J, A * truth, problem);
    const double tolerance = 1e-6 * maxTension.maxCoeff();

    ActiveSetSolver qp;
    DistributionResult result;
    qp.solve(problem, result);
    ASSERT_EQ(result.status, DistributionStatus::Optimal);
    EXPECT_LE((result.x - truth).cwiseAbs().maxCoeff(), tolerance) << "QP";

    LpSolver lp;
    lp.solve(problem, result);
    ASSERT_EQ(result.status, DistributionStatus::Optimal);
    EXPECT_LE((result.x - truth).cwiseAbs().maxCoeff(), tolerance) << "LP";

    StaticOptimizationSettings settings;
    settings.maxIsometricForce = maxTension;
    StaticOptimization so(settings);
    StaticOptimizationResult soResult;
    so.solve(problem, Eigen::VectorXd::Ones(model.getNumWires()), soResult);
    ASSERT_EQ(soResult.distribution.status, DistributionStatus::Optimal);
    EXPECT_LE((soResult.tension - truth.head(model.getNumWires())).cwiseAbs().maxCoeff(), tolerance) << "SO";
    EXPECT_LE((soResult.loopForce - truth.tail(problem.numFree)).cwiseAbs().maxCoeff(), tolerance) << "SO";
}

// More wires than DOFs, free root (whose rows the internal wire and loop forces cannot reach: roundoff
// there must not pass for moment arms), loops: the LP and the QP are optimal frame after frame.
TEST(WireProblem, LpAndQpAreOptimalOverAMotionOfAFloatingModel) {
    RandomModelOptions options;
    options.numLinks = 20, options.numWires = 150, options.numLoops = 2, options.pinFraction = 0, options.seed = 21;
    const Model model = generateRandomModel(options);
    Data data(model);
    std::mt19937 rng(6);
    const Eigen::VectorXd u = generateRandomSpeeds(model, rng);
    const Eigen::VectorXd maxTension = Eigen::VectorXd::Constant(model.getNumWires(), 800);
    const WireProblemBuilder builder(model, maxTension);
    DistributionProblem problem = builder.makeProblem();
    LpSolver lp;
    ActiveSetSolver qp;
    DistributionResult lpResult, qpResult;
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    for (int frame = 0; frame < 10; ++frame) {
        const Eigen::VectorXd q = integrateCoordinates(model, model.getDefaultQ(), u, 0.01 * frame);
        calcPositionKinematics(model, data, q);
        calcWirePaths(model, data);
        calcWireJacobian(model, data, J);
        builder.update(data, J, Eigen::VectorXd::Zero(model.getNumU()), problem);
        Eigen::VectorXd x = Eigen::VectorXd::Constant(problem.getNumVariables(), 20.0);
        x.head(model.getNumWires()) = (0.3 + 0.2 * Eigen::VectorXd::LinSpaced(model.getNumWires(), 0, 20).array().sin()).matrix() * 800;
        builder.update(data, J, problem.A * x, problem);
        lp.solve(problem, lpResult);
        qp.solve(problem, qpResult);
        ASSERT_EQ(lpResult.status, DistributionStatus::Optimal) << "frame " << frame;
        ASSERT_EQ(qpResult.status, DistributionStatus::Optimal) << "frame " << frame;
        EXPECT_LE(lpResult.kkt.getMax(), 1e-6) << "frame " << frame;
        EXPECT_LE(qpResult.kkt.getMax(), 1e-6) << "frame " << frame;
        EXPECT_LE(lpResult.residual.cwiseAbs().maxCoeff(), problem.tolerance[0] * (1 + 1e-6)) << "frame " << frame;
    }
}

}  // namespace
}  // namespace sinew

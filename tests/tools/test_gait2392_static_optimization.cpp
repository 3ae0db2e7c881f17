// Static optimization on OpenSim's gait2392 in both of its muscle models (92 Thelen2003 muscles; 92
// Millard2012Equilibrium muscles, each with its own law and curves) over every frame of gait2354's walk
// with its ground reactions and a reserve on every coordinate. The reference is the test's own problem
// written from its definition and solved by Ipopt: per frame min Σ a² + Σ c² over activations a in
// [0.01, 1] and reserve controls c, with -Jᵀ (F0 m a) + F_r c = τ on every DOF, where J is the wire Jacobian,
// F0 m each muscle's force per activation from its law at the path's length and lengthening speed J u, and
// τ inverse dynamics with the measured loads.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

#include "sinew/core/data.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/external_loads.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/motion_frames.hpp"
#include "sinew/tools/tension_motion.hpp"
#include "support/ipopt_reference.hpp"

namespace sinew {
namespace {

const std::filesystem::path kShared = std::filesystem::path(SINEW_SHARED_DIR) / "data";
constexpr double kMinActivation = 0.01, kReserveForce = 20;

void checkAgainstIpopt(const char* file, const std::string& lawType) {
    const std::filesystem::path modelPath = kShared / "opensim-models" / "Models" / "Gait2392_Simbody" / file;
    const std::filesystem::path walk = kShared / "opensim" / "gait2354";
    if (!std::filesystem::exists(modelPath) || !std::filesystem::exists(walk))
        GTEST_SKIP() << "../shared/data (OpenSim's gait2392 and gait2354's walk) is absent: it ships only with "
                        "sinew's developer data";
    const Model model = loadModel(modelPath.string(), {});
    const int nu = model.getNumU(), numWires = model.getNumWires();
    ASSERT_EQ(numWires, 92);
    for (const Wire& wire : model.getWires()) ASSERT_EQ(wire.lawSpec.type, lawType) << wire.name;
    const ExternalLoads loads = readExternalLoads((walk / "subject01_walk1_grf.xml").string());
    const StorageTable motion = readStorageFile((walk / "subject01_walk1_ik.mot").string());
    const CoordinateTrajectory trajectory =
        preprocessCoordinateSamples(model, readCoordinateSamples(model, motion), 6.0, -INFINITY, INFINITY);

    TensionMotionOptions options;
    options.analysis.method = "so";
    options.analysis.minActivation = Eigen::VectorXd::Constant(numWires, kMinActivation);
    for (int dof = 0; dof < nu; ++dof) {
        ReserveActuator reserve;
        reserve.name = "reserve_" + std::to_string(dof);
        reserve.dof = dof;
        reserve.optimalForce = kReserveForce;
        options.analysis.reserves.push_back(reserve);
    }
    const TensionMotionResult run = runTensionAnalysis(model, trajectory, &loads, options);
    ASSERT_EQ(run.activations.rows.size(), static_cast<std::size_t>(trajectory.times.size()));
    EXPECT_EQ(run.flaggedFrames, 0);

    const MeasuredLoads measured(model, loads);
    Data data(model);
    Eigen::MatrixXd J(numWires, nu);
    Eigen::VectorXd tau(nu);
    // Σ x² as the QP's ½ Σ 2 x², every row an equality; reserves unbounded.
    DistributionProblem problem;
    problem.lower.resize(numWires + nu);
    problem.upper.resize(numWires + nu);
    problem.lower << Eigen::VectorXd::Constant(numWires, kMinActivation), Eigen::VectorXd::Constant(nu, -INFINITY);
    problem.upper << Eigen::VectorXd::Ones(numWires), Eigen::VectorXd::Constant(nu, INFINITY);
    problem.cost.setZero(numWires + nu);
    problem.weight.setConstant(numWires + nu, 2);
    problem.tolerance.setZero(nu);
    problem.isEquality.assign(static_cast<std::size_t>(nu), true);
    double worst = 0, largestReserve = 0;
    forEachMotionFrame(model, trajectory, &measured, [&](const MotionFrame& frame) {
        calcInverseDynamics(model, data, frame.q, frame.u, frame.udot, frame.appliedLinkForces, tau);
        calcPositionKinematics(model, data, frame.q);
        calcWirePaths(model, data);
        calcWireJacobian(model, data, J);
        const Eigen::VectorXd speed = J * frame.u;
        Eigen::MatrixXd A(nu, numWires + nu);
        for (int w = 0; w < numWires; ++w) {
            const ForceLaw& law = *model.getWire(w).law;
            const double perActivation =
                *law.getMaxIsometricForce() * law.calcActiveForceMultiplier({data.wireLength[w], speed[w], frame.time});
            A.col(w) = -J.row(w).transpose() * perActivation;
        }
        A.rightCols(nu) = kReserveForce * Eigen::MatrixXd::Identity(nu, nu);
        problem.A = A.sparseView(0, 0);
        problem.A.makeCompressed();
        problem.target = tau;
        const test::IpoptReference reference = test::solveWithIpopt(problem, test::DistributionNlp::Kind::Qp);
        ASSERT_TRUE(reference.solved) << file << " frame " << frame.index;
        const Eigen::VectorXd& x = reference.x;
        const std::vector<double>& ours = run.activations.rows[static_cast<std::size_t>(frame.index)];
        for (int w = 0; w < numWires; ++w) {
            const double difference = std::fabs(ours[static_cast<std::size_t>(w)] - x[w]);
            worst = std::max(worst, difference);
            EXPECT_LE(difference, 1e-6) << file << " frame " << frame.index << " muscle " << model.getWire(w).name;
        }
        largestReserve = std::max(largestReserve, x.tail(nu).cwiseAbs().maxCoeff() * kReserveForce);
    });
    std::cout << file << ": " << trajectory.times.size() << " frames, largest activation difference from Ipopt "
              << worst << ", largest reserve " << largestReserve << " N m or N\n";
}

TEST(Gait2392StaticOptimization, ThelenModelMatchesIpoptOnEveryFrame) {
    checkAgainstIpopt("gait2392_thelen2003muscle.osim", "thelen2003_muscle");
}

TEST(Gait2392StaticOptimization, MillardModelMatchesIpoptOnEveryFrame) {
    checkAgainstIpopt("gait2392_millard2012muscle.osim", "millard2012_muscle");
}

}  // namespace
}  // namespace sinew

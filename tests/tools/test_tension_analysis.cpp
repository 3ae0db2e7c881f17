// TensionAnalysis per frame on the shipped arm26: whatever the method, the tensions it reports must
// produce, through sinew's one-pass generalized forces of tensions (calcWireGeneralizedForces, which never
// forms J), the inverse dynamics torques less the reported residual; and Z must be that residual's size.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <random>

#include "sinew/core/error.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/tools/tension_analysis.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

// The generalized forces of `tensions` at q, computed without the Jacobian.
Eigen::VectorXd calcWireTorques(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& tensions) {
    Data data(model);
    calcPositionKinematics(model, data, q);
    calcWirePaths(model, data);
    Eigen::VectorXd tau(model.getNumU());
    calcWireGeneralizedForces(model, data, tensions, tau);
    return tau;
}

class TensionAnalysisTest : public ::testing::TestWithParam<TensionMethod> {};

TEST_P(TensionAnalysisTest, TensionsReproduceTheInverseDynamicsTorques) {
    const test::NamedModel arm = test::loadArm26();
    const Model& model = arm.model;
    TensionAnalysisOptions options;
    options.method = GetParam();
    options.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), 2000);
    options.useMusclePhysiology = false;  // spring-damper wires: force per activation is maxTension
    TensionAnalysis analysis(model, options);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(0.2, 1.2), rate(-1, 1);
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    int optimalFrames = 0;
    for (int frame = 0; frame < 20; ++frame) {
        Eigen::VectorXd q(model.getNumQ()), u(model.getNumU()), udot(model.getNumU());
        for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = angle(rng);
        for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = rate(rng), udot[i] = rate(rng);
        const TensionFrame& result = analysis.calcFrame(q, u, udot, noLoads);

        Data data(model);
        Eigen::VectorXd tau(model.getNumU());
        calcInverseDynamics(model, data, q, u, udot, noLoads, tau);
        EXPECT_LT((result.tau - tau).norm(), 1e-12 * (1 + tau.norm()));
        const Eigen::VectorXd produced = calcWireTorques(model, q, result.tension);
        EXPECT_LT((tau - produced - result.residual).norm(), 1e-8 * (1 + tau.norm())) << "frame " << frame;
        EXPECT_NEAR(result.torqueError, 0.5 * (tau - produced).squaredNorm(), 1e-9 * (1 + tau.squaredNorm()));
        EXPECT_TRUE((result.tension.array() >= -1e-9).all() && (result.tension.array() <= 2000 + 1e-6).all());
        // Random states need not be reachable by arm26's wires: the method's own promise holds on frames it
        // reports optimal; the consistency above holds on every frame.
        if (result.status != DistributionStatus::Optimal) continue;
        ++optimalFrames;
        switch (GetParam()) {
            case TensionMethod::Lp:  // within the band on every DOF
                EXPECT_LE(result.residual.cwiseAbs().maxCoeff(), options.problem.torqueTolerance * (1 + 1e-6));
                break;
            case TensionMethod::Qp: break;  // least squares: optimal with whatever residual is left
            case TensionMethod::StaticOptimization:  // rows exact; tension = activation × strength
                EXPECT_LT(result.residual.norm(), 1e-6 * (1 + tau.norm()));
                EXPECT_LT((result.tension - 2000 * result.activation).norm(), 1e-9);
                break;
        }
        EXPECT_EQ(std::count(result.unactuated.begin(), result.unactuated.end(), 1), 0);
    }
    std::cout << toString(GetParam()) << ": " << optimalFrames << " of 20 random frames optimal\n";
}

INSTANTIATE_TEST_SUITE_P(Methods, TensionAnalysisTest,
                         ::testing::Values(TensionMethod::Lp, TensionMethod::Qp, TensionMethod::StaticOptimization),
                         [](const ::testing::TestParamInfo<TensionMethod>& method) {
                             return std::string(toString(method.param));
                         });

TEST(TensionAnalysis, RefusesWiresWithoutStrength) {
    const test::NamedModel arm = test::loadArm26();
    TensionAnalysisOptions options;  // no maxTension, spring-damper wires
    try {
        TensionAnalysis analysis(arm.model, options);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("wire '"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parseTensionMethod("simplex"), Error);
}

}  // namespace
}  // namespace sinew

// Inverse dynamics and custom joints against Simbody: link poses and velocities with MobilizedBody::
// FunctionBased (the mobilizer OpenSim's CustomJoint builds), tau against SimbodyMatterSubsystem::
// calcResidualForceIgnoringConstraints (what OpenSim's inverse dynamics calls), and the round trip through
// Simbody's forward dynamics, on random models with free, ball, pin, weld and custom joints.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/plugin/simbody_model.hpp"
#include "support/allocation_counter.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

std::vector<RandomModelOptions> makeOptions() {
    std::vector<RandomModelOptions> all;
    const JointType roots[] = {JointType::Custom, JointType::Free, JointType::Ball, JointType::Pin, JointType::Weld};
    for (int i = 0; i < 20; ++i) {
        RandomModelOptions o;
        o.seed = 300 + static_cast<unsigned>(i);
        o.numLinks = 1 + (i * 7) % 25;
        o.topology = i % 2 ? RandomModelOptions::Topology::RandomTree : RandomModelOptions::Topology::Chain;
        o.rootJoint = roots[i % 5];
        o.customJointFraction = 0.6;
        o.pinFraction = 0.2;
        o.numWires = 0;
        all.push_back(o);
    }
    return all;
}

Eigen::Vector3d toEigen3(const SimTK::Vec3& v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

std::vector<SpatialVector> randomLinkForces(const Model& model, std::mt19937& rng) {
    std::uniform_real_distribution<double> f(-20, 20);
    std::vector<SpatialVector> forces(static_cast<std::size_t>(model.getNumLinks()));
    for (SpatialVector& F : forces)
        for (int k = 0; k < 6; ++k) F[k] = f(rng);
    return forces;
}

// Simbody's body forces (ground first) from sinew's link forces: both are [moment about the body origin;
// force] in ground.
SimTK::Vector_<SimTK::SpatialVec> toBodyForces(const SimbodyModel& simbody, const std::vector<SpatialVector>& F) {
    SimTK::Vector_<SimTK::SpatialVec> bodyForces(simbody.getMatter().getNumBodies(), SimTK::SpatialVec(SimTK::Vec3(0)));
    for (std::size_t i = 0; i < F.size(); ++i) {
        const SimTK::MobilizedBodyIndex b = simbody.getMobilizedBody(static_cast<int>(i)).getMobilizedBodyIndex();
        bodyForces[b] = SimTK::SpatialVec(SimTK::Vec3(F[i][0], F[i][1], F[i][2]), SimTK::Vec3(F[i][3], F[i][4], F[i][5]));
    }
    return bodyForces;
}

TEST(CustomJoint, LinkPosesAndVelocitiesMatchSimbodyFunctionBased) {
    std::mt19937 rng(11);
    for (const RandomModelOptions& o : makeOptions()) {
        const Model model = generateRandomModel(o);
        const SimbodyModel simbody(model, {"", false, false, SimbodyMobilizer::FunctionBased});
        Data data(model);
        for (int trial = 0; trial < 3; ++trial) {
            const Eigen::VectorXd q = generateRandomCoordinates(model, rng), u = generateRandomSpeeds(model, rng, 2);
            const SimTK::State state = simbody.makeState(q, u);
            calcPositionKinematics(model, data, q);
            calcVelocityKinematics(model, data, u);
            for (int i = 0; i < model.getNumLinks(); ++i) {
                const SimTK::MobilizedBody& body = simbody.getMobilizedBody(i);
                const SimTK::Transform& X_GB = body.getBodyTransform(state);
                const std::size_t b = static_cast<std::size_t>(i);
                Eigen::Matrix3d R;
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 3; ++c) R(r, c) = X_GB.R()[r][c];
                ASSERT_LT((R - data.R_GB[b]).norm(), 1e-12) << test::describe(o) << " link " << i;
                ASSERT_LT((toEigen3(X_GB.p()) - data.p_GB[b]).norm(), 1e-12) << test::describe(o) << " link " << i;
                const SimTK::SpatialVec& V = body.getBodyVelocity(state);
                ASSERT_LT((toEigen3(V[0]) - data.w_GB[b]).norm(), 1e-11) << test::describe(o) << " link " << i;
                ASSERT_LT((toEigen3(V[1]) - data.v_GB[b]).norm(), 1e-11) << test::describe(o) << " link " << i;
            }
        }
    }
}

TEST(InverseDynamics, MatchesSimbodyResidualForces) {
    std::mt19937 rng(12);
    double worst = 0;
    for (const RandomModelOptions& o : makeOptions()) {
        const Model model = generateRandomModel(o);
        const SimbodyModel simbody(model, {"", true, false, SimbodyMobilizer::FunctionBased});
        const SimTK::MultibodySystem& system = simbody.getSystem();
        Data data(model);
        Eigen::VectorXd tau(model.getNumU());
        for (int trial = 0; trial < 3; ++trial) {
            const Eigen::VectorXd q = generateRandomCoordinates(model, rng), u = generateRandomSpeeds(model, rng, 2);
            const Eigen::VectorXd udot = generateRandomSpeeds(model, rng, 5);
            const std::vector<SpatialVector> applied = randomLinkForces(model, rng);
            calcInverseDynamics(model, data, q, u, udot, applied, tau);

            SimTK::State state = simbody.makeState(q, u);
            system.realize(state, SimTK::Stage::Dynamics);  // gravity, as a force element
            SimTK::Vector_<SimTK::SpatialVec> bodyForces = system.getRigidBodyForces(state, SimTK::Stage::Dynamics);
            bodyForces += toBodyForces(simbody, applied);
            SimTK::Vector residual;
            simbody.getMatter().calcResidualForceIgnoringConstraints(
                state, system.getMobilityForces(state, SimTK::Stage::Dynamics), bodyForces, toSimTK(udot), residual);
            const Eigen::VectorXd reference = toEigen(residual);
            const double error = (tau - reference).lpNorm<Eigen::Infinity>() / std::max(1.0, reference.lpNorm<Eigen::Infinity>());
            worst = std::max(worst, error);
            ASSERT_LT(error, 1e-9) << test::describe(o) << " trial " << trial;
        }
    }
    std::ostringstream text;
    text << worst;
    RecordProperty("worst_relative_error", text.str());
}

// Simbody's forward dynamics gives udot for generalized forces tau and link forces; sinew's inverse
// dynamics of that udot gives tau back.
TEST(InverseDynamics, InvertsSimbodyForwardDynamics) {
    std::mt19937 rng(13);
    for (const RandomModelOptions& o : makeOptions()) {
        const Model model = generateRandomModel(o);
        const SimbodyModel simbody(model, {"", true, false, SimbodyMobilizer::FunctionBased});
        const SimTK::MultibodySystem& system = simbody.getSystem();
        Data data(model);
        const Eigen::VectorXd q = generateRandomCoordinates(model, rng), u = generateRandomSpeeds(model, rng, 2);
        const Eigen::VectorXd tauApplied = generateRandomSpeeds(model, rng, 10);
        const std::vector<SpatialVector> applied = randomLinkForces(model, rng);
        SimTK::State state = simbody.makeState(q, u);
        system.realize(state, SimTK::Stage::Dynamics);
        SimTK::Vector_<SimTK::SpatialVec> bodyForces = system.getRigidBodyForces(state, SimTK::Stage::Dynamics);
        bodyForces += toBodyForces(simbody, applied);
        SimTK::Vector udot;
        SimTK::Vector_<SimTK::SpatialVec> A_GB;
        simbody.getMatter().calcAccelerationIgnoringConstraints(state, toSimTK(tauApplied), bodyForces, udot, A_GB);
        Eigen::VectorXd tau(model.getNumU());
        calcInverseDynamics(model, data, q, u, toEigen(udot), applied, tau);
        EXPECT_LT((tau - tauApplied).lpNorm<Eigen::Infinity>(), 1e-9 * std::max(1.0, tauApplied.lpNorm<Eigen::Infinity>()))
            << test::describe(o);
        for (int i = 0; i < model.getNumLinks(); ++i) {  // and the link accelerations on the way
            const std::size_t b = static_cast<std::size_t>(i);
            const SimTK::SpatialVec& A = A_GB[simbody.getMobilizedBody(i).getMobilizedBodyIndex()];
            EXPECT_LT((toEigen3(A[0]) - data.alpha_GB[b]).norm(), 1e-8) << test::describe(o) << " link " << i;
            EXPECT_LT((toEigen3(A[1]) - data.a_GB[b]).norm(), 1e-8) << test::describe(o) << " link " << i;
        }
    }
}

TEST(InverseDynamics, AllocatesNothing) {
    if (!test::isCountingAllocations()) GTEST_SKIP() << "allocations are not counted under AddressSanitizer";
    RandomModelOptions o = makeOptions()[5];
    o.numLinks = 30;
    const Model model = generateRandomModel(o);
    std::mt19937 rng(14);
    const Eigen::VectorXd q = generateRandomCoordinates(model, rng), u = generateRandomSpeeds(model, rng);
    const Eigen::VectorXd udot = generateRandomSpeeds(model, rng);
    const std::vector<SpatialVector> applied = randomLinkForces(model, rng);
    Data data(model);
    Eigen::VectorXd tau(model.getNumU());
    const long long before = test::getAllocationCount();
    calcInverseDynamics(model, data, q, u, udot, applied, tau);
    EXPECT_EQ(test::getAllocationCount(), before);
}

}  // namespace
}  // namespace sinew

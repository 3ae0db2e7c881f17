// Joint and loop-closure reactions (core/joint_reactions.cpp) against Simbody: calcMobilizerReactionForces
// and Constraint::Ball's reaction at states Simbody's forward dynamics accelerates under gravity, wire
// tensions, random generalized forces and random body forces, on chains, trees with ball joints and models
// with loops; and a pendulum worked by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "sinew/core/error.hpp"
#include "sinew/core/joint_reactions.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/plugin/simbody_model.hpp"
#include "support/allocation_counter.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

Eigen::Vector3d toEigen3(const SimTK::Vec3& v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

Eigen::Matrix3d toEigen33(const SimTK::Rotation& R) {
    Eigen::Matrix3d m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m(r, c) = R[r][c];
    return m;
}

// Largest difference between sinew's reactions and Simbody's, over the problem's force scale (the weight,
// the largest tension, applied force and Simbody reaction), and whether the loops were redundant.
struct Comparison {
    double jointError = 0, loopError = 0;
    bool redundant = false;
};

// A state Simbody accelerates: assembled near the default pose when the model has loops (at it where the
// loops lock the mechanism), random otherwise, with loop-consistent random speeds.
SimTK::State makeTestState(const SimbodyModel& simbody, std::mt19937& rng) {
    const Model& model = simbody.getModel();
    const SimTK::MultibodySystem& system = simbody.getSystem();
    const Eigen::VectorXd u0 = generateRandomSpeeds(model, rng, 2.0);
    if (model.getNumLoops() == 0) return simbody.makeState(generateRandomCoordinates(model, rng), u0);
    const Eigen::VectorXd q0 = integrateCoordinates(model, model.getDefaultQ(), generateRandomSpeeds(model, rng), 0.2);
    SimTK::State state = simbody.makeState(q0, u0, SimTK::Stage::Position);
    try {
        system.project(state, 1e-13);
    } catch (const std::exception&) {
        state = simbody.makeState(model.getDefaultQ(), u0, SimTK::Stage::Position);
    }
    system.realize(state, SimTK::Stage::Velocity);
    system.projectU(state, 1e-13);
    return state;
}

Comparison compareWithSimbody(const Model& model, std::mt19937& rng) {
    SimbodyModel simbody(model);
    SimTK::Force::DiscreteForces discrete(simbody.updForces(), simbody.getMatter());
    simbody.updSystem().realizeTopology();
    const SimTK::MultibodySystem& system = simbody.getSystem();
    SimTK::State state = makeTestState(simbody, rng);

    const Eigen::VectorXd tau = generateRandomSpeeds(model, rng, 5.0);
    std::uniform_real_distribution<double> f(-20, 20);
    std::vector<SpatialVector> applied(static_cast<std::size_t>(model.getNumLinks()));
    SimTK::Vector_<SimTK::SpatialVec> bodyForces(simbody.getMatter().getNumBodies(), SimTK::SpatialVec(SimTK::Vec3(0)));
    for (int i = 0; i < model.getNumLinks(); ++i) {
        SpatialVector& F = applied[static_cast<std::size_t>(i)];
        for (int k = 0; k < 6; ++k) F[k] = f(rng);
        bodyForces[simbody.getMobilizedBody(i).getMobilizedBodyIndex()] =
            SimTK::SpatialVec(SimTK::Vec3(F[0], F[1], F[2]), SimTK::Vec3(F[3], F[4], F[5]));
    }
    discrete.setAllMobilityForces(state, toSimTK(tau));
    discrete.setAllBodyForces(state, bodyForces);
    system.realize(state, SimTK::Stage::Acceleration);
    SimTK::Vector_<SimTK::SpatialVec> reference;
    simbody.getMatter().calcMobilizerReactionForces(state, reference);

    // sinew: the wires' tensions as link forces, added to the applied ones.
    const Eigen::VectorXd q = toEigen(state.getQ()), u = toEigen(state.getU()), udot = toEigen(state.getUDot());
    Data data(model);
    calcPositionKinematics(model, data, q);
    calcVelocityKinematics(model, data, u);
    calcWirePaths(model, data);
    calcWireSpeeds(model, data);
    Eigen::VectorXd tensions(model.getNumWires());
    calcWireTensions(model, data, state.getTime(), tensions);
    calcWireLinkForces(model, data, tensions);
    std::vector<SpatialVector> linkForces = applied;
    for (std::size_t b = 0; b < linkForces.size(); ++b) linkForces[b] += data.F_G[b];
    JointReactionsData reactions(model);
    calcJointReactions(model, data, q, u, udot, tau, linkForces, reactions);

    double scale = tensions.size() ? tensions.maxCoeff() : 0.0;
    for (const Link& link : model.getLinks()) scale += link.mass * model.getGravity().norm();
    scale = std::max(scale, 20.0);
    Comparison result;
    result.redundant = model.getNumLoops() > 0 && reactions.loopSolver.rank() < 3 * model.getNumLoops();
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const SimTK::MobilizedBody& body = simbody.getMobilizedBody(i);
        const SimTK::SpatialVec& R = reference[body.getMobilizedBodyIndex()];
        SpatialVector F_GM, F_BM;
        F_GM << toEigen3(R[0]), toEigen3(R[1]);
        const Eigen::Matrix3d R_BG = toEigen33(body.getBodyRotation(state)).transpose();
        F_BM << R_BG * F_GM.head<3>(), R_BG * F_GM.tail<3>();
        const std::size_t b = static_cast<std::size_t>(i);
        scale = std::max(scale, F_GM.lpNorm<Eigen::Infinity>());
        result.jointError = std::max({result.jointError, (reactions.F_GM[b] - F_GM).lpNorm<Eigen::Infinity>(),
                                      (reactions.F_BM[b] - F_BM).lpNorm<Eigen::Infinity>()});
    }
    for (int k = 0; k < model.getNumLoops(); ++k) {
        // Simbody's "reaction on body 2" (body 2's axes) is the negative of the force the closure applies to
        // it (test_forward_dynamics.cpp checks that against calcConstraintForcesFromMultipliers).
        const Eigen::Vector3d onB_B = -toEigen3(simbody.getLoopConstraint(k).getBallReactionForceOnBody2(state));
        const std::size_t l = static_cast<std::size_t>(k);
        const Eigen::Matrix3d R_GB = data.R_GB[static_cast<std::size_t>(model.getLoop(k).linkB)];
        result.loopError = std::max({result.loopError, (reactions.loopForce_B[l] - onB_B).lpNorm<Eigen::Infinity>(),
                                     (reactions.loopForce_G[l] - R_GB * onB_B).lpNorm<Eigen::Infinity>()});
    }
    // Simbody's udot solves the equations of motion: nothing is left unexplained.
    result.jointError = std::max(result.jointError, reactions.residual.lpNorm<Eigen::Infinity>()) / scale;
    result.loopError /= scale;
    return result;
}

std::vector<test::NamedModel> makeTreeModels() {
    std::vector<test::NamedModel> models;
    const RandomModelOptions::Topology topologies[] = {RandomModelOptions::Topology::Chain,
                                                       RandomModelOptions::Topology::BinaryTree,
                                                       RandomModelOptions::Topology::RandomTree};
    const JointType roots[] = {JointType::Free, JointType::Ball, JointType::Pin, JointType::Weld, JointType::Custom};
    for (int i = 0; i < 30; ++i) {
        RandomModelOptions o;
        o.seed = 4100 + static_cast<unsigned>(i);
        o.numLinks = 1 + (i * 7) % 30;
        o.topology = topologies[i % 3];
        o.rootJoint = roots[i % 5];
        o.pinFraction = 0.2;  // the other non-root joints balls, or custom where customJointFraction picks them
        o.customJointFraction = i % 2 ? 0.3 : 0.0;
        o.numWires = 2 * o.numLinks;
        models.push_back({test::describe(o), generateRandomModel(o)});
    }
    return models;
}

TEST(JointReactions, MatchSimbodyOnChainsAndTreesWithBallJoints) {
    std::mt19937 rng(41);
    double worst = 0;
    for (const test::NamedModel& m : makeTreeModels()) {
        const Comparison c = compareWithSimbody(m.model, rng);
        EXPECT_LT(c.jointError, 1e-10) << m.name;
        worst = std::max(worst, c.jointError);
    }
    std::printf("joint reactions, 30 trees: worst difference from Simbody %.2e of the force scale\n", worst);
}

TEST(JointReactions, MatchSimbodyOnModelsWithLoops) {
    std::mt19937 rng(42);
    double worstJoint = 0, worstLoop = 0;
    int compared = 0;
    for (int i = 0; i < 40; ++i) {
        RandomModelOptions o;
        o.seed = 4200 + static_cast<unsigned>(i);
        o.numLinks = 4 + (i * 5) % 30;
        o.topology = i % 2 ? RandomModelOptions::Topology::RandomTree : RandomModelOptions::Topology::Chain;
        o.rootJoint = i % 3 ? JointType::Free : JointType::Weld;
        o.numLoops = 1 + i % 3;
        o.numWires = 2 * o.numLinks;
        const Model model = generateRandomModel(o);
        const Comparison c = compareWithSimbody(model, rng);
        if (c.redundant) continue;  // loop forces not unique: sinew's and Simbody's choices may differ
        ++compared;
        EXPECT_LT(c.jointError, 1e-9) << test::describe(o);
        EXPECT_LT(c.loopError, 1e-9) << test::describe(o);
        worstJoint = std::max(worstJoint, c.jointError);
        worstLoop = std::max(worstLoop, c.loopError);
    }
    EXPECT_GE(compared, 20);
    std::printf("joint reactions, %d models with loops: worst difference from Simbody %.2e (joints), %.2e (loops) "
                "of the force scale\n", compared, worstJoint, worstLoop);
}

// A 2 kg pendulum pinned to ground, its centre of mass 0.5 m from the pin: hanging at rest, the pin carries
// its weight and no moment; held horizontal at rest by a motor, the weight and the motor's m g l.
TEST(JointReactions, PendulumCarriesItsWeight) {
    const Model model = readModelText(R"(sinew_model: 1
name: pendulum
gravity: [0, -9.81, 0]
links:
  - {name: bob, mass: 2.0, com: [0, -0.5, 0], inertia: [0.01, 0.01, 0.01, 0, 0, 0]}
joints:
  - {name: pin, type: pin, parent: ground, child: bob, parent_point: [0, 1, 0], child_point: [0, 0, 0], axis: [0, 0, 1]}
)",
                                      "pendulum");
    Data data(model);
    JointReactionsData reactions(model);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(1);
    const std::vector<SpatialVector> none(1, SpatialVector::Zero());
    calcJointReactions(model, data, zero, zero, zero, zero, none, reactions);
    SpatialVector expected;
    expected << 0, 0, 0, 0, 2 * 9.81, 0;
    EXPECT_LT((reactions.F_GM[0] - expected).norm(), 1e-12);
    EXPECT_LT(reactions.residual.norm(), 1e-12);

    // Horizontal (q = pi/2 turns the bob's -y to +x): the motor holds +m g l about z.
    const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, M_PI / 2);
    const Eigen::VectorXd motor = Eigen::VectorXd::Constant(1, 2 * 9.81 * 0.5);
    calcJointReactions(model, data, q, zero, zero, motor, none, reactions);
    expected << 0, 0, 2 * 9.81 * 0.5, 0, 2 * 9.81, 0;
    EXPECT_LT((reactions.F_GM[0] - expected).norm(), 1e-12);
    SpatialVector expected_B;  // the same in the bob's axes, turned a quarter turn about z
    expected_B << 0, 0, 2 * 9.81 * 0.5, 2 * 9.81, 0, 0;
    EXPECT_LT((reactions.F_BM[0] - expected_B).norm(), 1e-12);
    EXPECT_LT(reactions.residual.norm(), 1e-12);
    // Without the motor the same motion leaves its torque unexplained.
    calcJointReactions(model, data, q, zero, zero, zero, none, reactions);
    EXPECT_NEAR(reactions.residual[0], 2 * 9.81 * 0.5, 1e-12);
}

// Without loops; Eigen's least-squares solve for loop forces allocates its own temporaries.
TEST(JointReactions, AllocatesNothingWithoutLoops) {
    if (!test::isCountingAllocations()) GTEST_SKIP() << "allocations are not counted under AddressSanitizer";
    RandomModelOptions o;
    o.numLinks = 20;
    o.numWires = 0;
    const Model model = generateRandomModel(o);
    std::mt19937 rng(43);
    const Eigen::VectorXd q = generateRandomCoordinates(model, rng), u = generateRandomSpeeds(model, rng);
    const Eigen::VectorXd udot = generateRandomSpeeds(model, rng), tau = generateRandomSpeeds(model, rng);
    const std::vector<SpatialVector> forces(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Ones());
    Data data(model);
    JointReactionsData reactions(model);
    const long long before = test::getAllocationCount();
    calcJointReactions(model, data, q, u, udot, tau, forces, reactions);
    EXPECT_EQ(test::getAllocationCount(), before);
}

TEST(JointReactions, RefusesInputsOfTheWrongSize) {
    const Model model = generateRandomModel(RandomModelOptions{});
    Data data(model);
    JointReactionsData reactions(model);
    const Eigen::VectorXd u = Eigen::VectorXd::Zero(model.getNumU());
    const std::vector<SpatialVector> forces(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    const Eigen::VectorXd tooShort = Eigen::VectorXd::Zero(1);
    EXPECT_THROW(calcJointReactions(model, data, model.getDefaultQ(), u, u, tooShort, forces, reactions), Error);
    const std::vector<SpatialVector> noForces;
    EXPECT_THROW(calcJointReactions(model, data, model.getDefaultQ(), u, u, u, noForces, reactions), Error);
}

}  // namespace
}  // namespace sinew

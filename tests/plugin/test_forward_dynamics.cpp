// sinew's assembly-disassembly forward dynamics against Simbody's (realize(Acceleration) with the same loop
// and coupler constraints, gravity, wires and generalized forces), on assembled states with non-zero
// velocities: random models (ball, pin, free and custom joints), OpenSim's own models.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/plugin/simbody_model.hpp"
#include "support/coupled_knee.hpp"
#include "support/error_assertions.hpp"
#include "support/force_element_model.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

struct Comparison {
    double udotError = 0;  // max abs difference / max abs Simbody udot
    // max abs difference over the force scale; 0 without loops, or with redundant ones, whose forces are
    // not unique (sinew's and Simbody's least-squares choices differ)
    double loopForceError = 0;
    int redundantConstraints = 0;
    double loopConditioning = 1;
};

struct SinewResult {
    Eigen::VectorXd udot;
    std::vector<Eigen::Vector3d> loopForces;
    int redundantConstraints = 0;
    double loopConditioning = 1;
    int levels = 0;
};

SinewResult evaluateSinew(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                          const Eigen::VectorXd& tau, double time, AssemblySchedule::Kind kind, int threads,
                          int hangLink) {
    Data data(model);
    calcPositionKinematics(model, data, q);
    calcVelocityKinematics(model, data, u);
    calcWirePaths(model, data);
    calcWireSpeeds(model, data);
    Eigen::VectorXd tensions(model.getNumWires());
    calcWireTensions(model, data, time, tensions);
    calcWireLinkForces(model, data, tensions);
    Eigen::VectorXd tauWithWires = tau;
    addWireCoordinateForces(model, data, tensions, tauWithWires);  // moving points, ellipsoid wraps
    addForceElementForces(model, data, data.F_G, tauWithWires);
    const AssemblySchedule schedule(model, kind, hangLink);
    ForwardDynamicsData fd(model, schedule);
    // Twice, as a simulation reuses its buffers: nothing may carry over from one evaluation to the next.
    calcForwardDynamics(model, schedule, data, tauWithWires, data.F_G, fd, threads);
    calcForwardDynamics(model, schedule, data, tauWithWires, data.F_G, fd, threads);
    return {fd.udot, fd.loopForce, fd.redundantConstraints, fd.loopConditioning, schedule.getNumLevels()};
}

// Custom joints enter Simbody as OpenSim builds them (FunctionBased, independent of sinew's joint code) unless
// `mobilizer` says otherwise; random models keep to the layouts where FunctionBased is exact.
Comparison compareWithSimbody(const Model& model, std::mt19937& rng, int hangLink = -1,
                              AssemblySchedule::Kind kind = AssemblySchedule::Kind::Serial,
                              SimbodyMobilizer mobilizer = SimbodyMobilizer::FunctionBased) {
    SimbodyModelOptions options;
    options.customJoints = mobilizer;
    if (hangLink >= 0) options.hangBy = model.getLink(hangLink).name;
    SimbodyModel simbody(model, options);
    SimTK::Force::DiscreteForces generalizedForces(simbody.updForces(), simbody.getMatter());
    simbody.updSystem().realizeTopology();
    const SimTK::MultibodySystem& system = simbody.getSystem();

    // An assembled state near the default pose (or at it, where random loops lock the mechanism so that
    // the perturbed pose cannot be assembled), with loop-consistent speeds.
    const Eigen::VectorXd u0 = generateRandomSpeeds(model, rng, 2.0);
    SimTK::State state = simbody.makeState(
        integrateCoordinates(model, model.getDefaultQ(), generateRandomSpeeds(model, rng), 0.2), u0, SimTK::Stage::Position);
    try {
        system.project(state, 1e-13);
    } catch (const std::exception&) {
        state = simbody.makeState(model.getDefaultQ(), u0, SimTK::Stage::Position);
    }
    system.realize(state, SimTK::Stage::Velocity);
    system.projectU(state, 1e-13);
    const Eigen::VectorXd tau = generateRandomSpeeds(model, rng, 5.0);
    generalizedForces.setAllMobilityForces(state, toSimTK(tau));
    system.realize(state, SimTK::Stage::Acceleration);
    const Eigen::VectorXd udotSimbody = toEigen(state.getUDot());

    const Eigen::VectorXd q = toEigen(state.getQ()), u = toEigen(state.getU());
    const SinewResult fd = evaluateSinew(model, q, u, tau, state.getTime(), kind, 1, hangLink);
    Data data(model);
    calcPositionKinematics(model, data, q);

    Comparison result;
    // Relative to the problem's acceleration scale: the larger of Simbody's udot and the udot the same forces
    // would give without the loops (a locked mechanism has udot ~ 0, a roundoff-sized reference).
    SimTK::Vector udotFree;
    SimTK::Vector_<SimTK::SpatialVec> bodyAccelerations;
    simbody.getMatter().calcAccelerationIgnoringConstraints(state, system.getMobilityForces(state, SimTK::Stage::Dynamics),
                                                           system.getRigidBodyForces(state, SimTK::Stage::Dynamics),
                                                           udotFree, bodyAccelerations);
    const double scale = std::max({udotSimbody.lpNorm<Eigen::Infinity>(), toEigen(udotFree).lpNorm<Eigen::Infinity>(), 1e-300});
    result.udotError = (fd.udot - udotSimbody).lpNorm<Eigen::Infinity>() / scale;
    double largest = 0, worst = 0;
    for (int k = 0; k < model.getNumLoops(); ++k) {
        // Simbody's "reaction on body 2" (in body 2's frame) is the negative of the force the constraint
        // applies to body 2 (link B), which is what sinew reports; calcConstraintForcesFromMultipliers with
        // negated multipliers, Simbody's documented way to get applied-like constraint forces, agrees.
        const SimTK::Vec3 reaction_B = simbody.getLoopConstraint(k).getBallReactionForceOnBody2(state);
        const Eigen::Vector3d reaction_G = -(data.R_GB[static_cast<std::size_t>(model.getLoop(k).linkB)] *
                                             Eigen::Vector3d(reaction_B[0], reaction_B[1], reaction_B[2]));
        largest = std::max(largest, reaction_G.lpNorm<Eigen::Infinity>());
        worst = std::max(worst, (reaction_G - fd.loopForces[static_cast<std::size_t>(k)]).lpNorm<Eigen::Infinity>());
    }
    result.redundantConstraints = fd.redundantConstraints;
    result.loopConditioning = fd.loopConditioning;
    // Relative to the problem's force scale: the largest of the loop forces, wire tensions and total weight.
    double weight = 0;
    for (const Link& link : model.getLinks()) weight += link.mass * model.getGravity().norm();
    double largestTension = 0;
    for (int w = 0; w < model.getNumWires(); ++w)
        largestTension = std::max(largestTension, simbody.getWireForce(w).calcTension(state));
    const double forceScale = std::max({largest, largestTension, weight});
    result.loopForceError = largest > 0 && fd.redundantConstraints == 0 ? worst / forceScale : 0;
    return result;
}

// Random models of 2 to 200 links with 0 to 10 loops: chains, binary and random trees, free, ball and
// weld roots, ball and pin joints, wires.
std::vector<test::NamedModel> makeClosedChainModels(int count) {
    test::RandomModelSweep sweep;
    sweep.count = count;
    sweep.firstLinks = 2;
    sweep.linkStride = 37;
    sweep.linkRange = 199;
    sweep.loopCycle = 11;
    sweep.wiresBase = 0;
    sweep.wiresPerLink = 2;
    sweep.viaCycle = 3;
    sweep.virtualLinks = false;
    sweep.seedBase = 2000;
    return test::makeRandomModels(sweep);
}

void expectAgreement(const std::vector<test::NamedModel>& models, const char* what, unsigned seed, bool hang = false,
                     AssemblySchedule::Kind kind = AssemblySchedule::Kind::Serial) {
    std::mt19937 rng(seed);
    double worstUdot = 0, worstLoop = 0;
    int redundantModels = 0;
    for (const test::NamedModel& m : models) {
        const int hangLink = hang ? m.model.getNumLinks() / 2 : -1;
        const Comparison c = compareWithSimbody(m.model, rng, hangLink, kind);
        redundantModels += c.redundantConstraints > 0;
        EXPECT_LE(c.udotError, 1e-9) << m.name << " loop conditioning " << c.loopConditioning;
        EXPECT_LE(c.loopForceError, 1e-9) << m.name << " loop conditioning " << c.loopConditioning;
        worstUdot = std::max(worstUdot, c.udotError);
        worstLoop = std::max(worstLoop, c.loopForceError);
    }
    std::printf("%s: worst relative difference from Simbody over %zu models (%d with redundant loops): udot %.2e, "
                "loop forces %.2e\n", what, models.size(), redundantModels, worstUdot, worstLoop);
}

TEST(ForwardDynamics, MatchesSimbodyOnSmallRandomModels) {
    expectAgreement(test::makeRandomModels(100, false), "1-40 links, 0-4 loops", 31);
}

TEST(ForwardDynamics, MatchesSimbodyOnRandomModelsUpTo200LinksAnd10Loops) {
    expectAgreement(makeClosedChainModels(100), "2-200 links, 0-10 loops", 33);
}

TEST(ForwardDynamics, MatchesSimbodyWhenHungByALink) {
    expectAgreement(makeClosedChainModels(30), "hung by a middle link", 34, true);
}

// Featherstone's benchmark systems for divide-and-conquer dynamics (IJRR 1999): an unbranched chain and a
// binary tree of identical bodies, here of 127 ball-jointed links, with and without loops.
TEST(ForwardDynamics, MatchesSimbodyOnChainAndBinaryTree) {
    std::vector<test::NamedModel> models;
    for (auto topology : {RandomModelOptions::Topology::Chain, RandomModelOptions::Topology::BinaryTree}) {
        for (int loops : {0, 5}) {
            RandomModelOptions o;
            o.numLinks = 127;
            o.topology = topology;
            o.pinFraction = 0;
            o.numLoops = loops;
            o.numWires = 0;
            o.seed = 77;
            models.push_back({(topology == RandomModelOptions::Topology::Chain ? "chain127, loops " : "tree127, loops ") +
                                  std::to_string(loops),
                              generateRandomModel(o)});
        }
    }
    expectAgreement(models, "Featherstone chain and binary tree", 35);
}

// Custom joints (OpenSim's CustomJoint: 1-3 coordinates driving rotations and, through splines and
// polynomials, translations) absorbed as articulated bodies and, inside loops and in the balanced schedule,
// joined through the orthogonal complement of their motion subspace.
TEST(ForwardDynamics, MatchesSimbodyWithCustomJoints) {
    std::vector<test::NamedModel> models;
    for (int i = 0; i < 24; ++i) {
        RandomModelOptions o;
        o.seed = static_cast<unsigned>(4100 + i);
        o.numLinks = 3 + 3 * i;
        o.topology = i % 3 == 0 ? RandomModelOptions::Topology::Chain : RandomModelOptions::Topology::RandomTree;
        o.rootJoint = i % 2 ? JointType::Custom : JointType::Free;
        o.customJointFraction = 0.6;
        o.numLoops = i % 4;
        o.numWires = 2 * o.numLinks;
        models.push_back({test::describe(o), generateRandomModel(o)});
    }
    expectAgreement(models, "custom joints, serial schedule", 37);
    expectAgreement(models, "custom joints, balanced schedule", 38, false, AssemblySchedule::Kind::Balanced);
    expectAgreement(models, "custom joints, hung by a middle link", 39, true);
}


// The knee's slide coupled to its angle, and then the angle locked too (OpenSim's lock: Simbody's
// PrescribedMotion of a constant), which holds both. The same data evaluates twice, as in a simulation.
TEST(ForwardDynamics, MatchesSimbodyWithACouplerAndALock) {
    std::string locked = test::kCoupledKnee;
    locked.replace(locked.find("{name: knee_angle}"), 18, "{name: knee_angle, default: 0.3, locked: true}");
    std::mt19937 rng(40);
    for (const std::string& text : {std::string(test::kCoupledKnee), locked}) {
        const Model model = readModelText(text, "coupled_knee.yaml");
        for (AssemblySchedule::Kind kind : {AssemblySchedule::Kind::Serial, AssemblySchedule::Kind::Balanced}) {
            for (int hangLink : {-1, 1}) {
                for (int i = 0; i < 5; ++i) {
                    const Comparison c = compareWithSimbody(model, rng, hangLink, kind);
                    EXPECT_LE(c.udotError, 1e-9) << "hang " << hangLink;
                }
            }
        }
    }
}

// OpenSim's models as they stand: gait2392 (custom joints, moving and conditional path points, 92 muscles),
// Rajagopal 2015 (custom joints, 2 patellofemoral couplers, 21 locked coordinates), leg39 and the jumper (couplers), the double
// pendulum (point masses on pins). Against
// Simbody with OpenSim's FunctionBased mobilizers, except on Rajagopal's knees, where one coordinate drives
// three rotations and FunctionBased's Hdot is off (docs/opensim-joints.md): there against Simbody with
// sinew's custom mobilizer, whose H and Hdot tests/core/test_custom_joint.cpp checks by finite differences,
// and FunctionBased's departure is shown.
TEST(ForwardDynamics, MatchesSimbodyOnOpenSimModels) {
    const std::filesystem::path models = std::filesystem::path(SINEW_SHARED_DIR) / "data/opensim-models/Models";
    if (!std::filesystem::exists(models)) GTEST_SKIP() << models << " is absent (it ships with ../shared only)";
    std::mt19937 rng(41);
    for (const char* file : {"Gait2392_Simbody/gait2392_thelen2003muscle.osim", "Rajagopal_OpenSense/Rajagopal2015_opensense.osim",
                             "Leg39/leg39.osim", "Jumper/DynamicJumperModel.osim", "DoublePendulum/double_pendulum.osim"}) {
        const bool rajagopal = std::string(file).find("Rajagopal") != std::string::npos;
        const Model model = loadModel((models / file).string(), {});
        double worstSinew = 0, worstFunctionBased = 0;
        const bool pointMasses = std::string(file).find("Pendulum") != std::string::npos;  // serial only
        for (int i = 0; i < 10; ++i) {
            const auto kind = i % 2 && !pointMasses ? AssemblySchedule::Kind::Balanced : AssemblySchedule::Kind::Serial;
            worstSinew = std::max(worstSinew, compareWithSimbody(model, rng, -1, kind, SimbodyMobilizer::Sinew).udotError);
            worstFunctionBased = std::max(worstFunctionBased, compareWithSimbody(model, rng, -1, kind).udotError);
        }
        std::printf("%s (%d links, %d dof, %d couplers, %d wires): worst relative udot difference from Simbody %.2e "
                    "(sinew's mobilizer), %.2e (FunctionBased)\n", file, model.getNumLinks(), model.getNumU(),
                    model.getNumCouplers(), model.getNumWires(), worstSinew, worstFunctionBased);
        EXPECT_LE(worstSinew, 1e-9) << file;
        if (rajagopal) EXPECT_GT(worstFunctionBased, 1e-7) << file << ": FunctionBased's Hdot now exact here? update the docs";
        else EXPECT_LE(worstFunctionBased, 1e-9) << file;
    }
}

// Force elements against Simbody's own (Force::TwoPointLinearSpring, Force::LinearBushing, HuntCrossleyForce
// on a GeneralContactSubsystem; the knee limit is OpenSim's formula in both engines): udot at states with
// the heel 0-4 mm into the floor and random speeds (friction, damping and the bushing's rates all at work),
// and the elements' potential energy against Simbody's (gravity off there).
void expectForceElementsMatchSimbody(const Model& model, const std::string& sphere, int heightQ, const char* what) {
    SimbodyModel withGravity(model);
    SimbodyModelOptions noGravity;
    noGravity.gravity = false;
    SimbodyModel withoutGravity(model, noGravity);
    std::mt19937 rng(51);
    std::uniform_real_distribution<double> speed(-0.5, 0.5);
    const int nu = model.getNumU();
    double worstUdot = 0, worstEnergy = 0;
    int touching = 0;
    for (int trial = 0; trial < 20; ++trial) {
        const Eigen::VectorXd q = test::placeSphereInFloor(model, sphere, heightQ, 0.001 * (trial % 5));
        Eigen::VectorXd u(nu);
        for (int i = 0; i < nu; ++i) u[i] = speed(rng);
        SimTK::State state = withGravity.makeState(q, u, SimTK::Stage::Position);
        withGravity.getSystem().realize(state, SimTK::Stage::Acceleration);
        const Eigen::VectorXd udotSimbody = toEigen(state.getUDot());
        const SinewResult fd = evaluateSinew(model, q, u, Eigen::VectorXd::Zero(nu), 0, AssemblySchedule::Kind::Serial, 1, -1);
        worstUdot = std::max(worstUdot, (fd.udot - udotSimbody).lpNorm<Eigen::Infinity>() /
                                            std::max(1.0, udotSimbody.lpNorm<Eigen::Infinity>()));
        SimTK::State bare = withoutGravity.makeState(q, u, SimTK::Stage::Position);
        withoutGravity.getSystem().realize(bare, SimTK::Stage::Dynamics);
        Data data(model);
        calcPositionKinematics(model, data, q);
        const double energy = calcForceElementPotentialEnergy(model, data);
        const double energySimbody = withoutGravity.getSystem().calcPotentialEnergy(bare);
        worstEnergy = std::max(worstEnergy, std::fabs(energy - energySimbody) / std::max(1.0, std::fabs(energySimbody)));
        touching += trial % 5 != 0;
    }
    std::printf("%s: force elements, worst relative udot difference from Simbody %.2e, potential energy %.2e "
                "(%d of 20 states touching)\n", what, worstUdot, worstEnergy, touching);
    EXPECT_LE(worstUdot, 1e-9) << what;
    EXPECT_LE(worstEnergy, 1e-9) << what;
}

TEST(ForwardDynamics, ForceElementsMatchSimbodysOwn) {
    const Model model = test::makeForceElementModel();
    expectForceElementsMatchSimbody(model, "heel", model.getJoint(model.findLinkIndex("block")).qStart + 5, "block and leg");
}

// OpenSim's bouncing block as it stands: a free block, a two-link leg, a knee CoordinateLimitForce, a
// PointToPointSpring, a BushingForce on an offset frame and a HuntCrossleyForce between the heel and a platform.
TEST(ForwardDynamics, OpenSimsBouncingBlockMatchesSimbody) {
    const std::filesystem::path file =
        std::filesystem::path(SINEW_SHARED_DIR) / "data/opensim-models/Models/BouncingBlock/bouncing_block.osim";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " is absent (it ships with ../shared only)";
    const Model model = loadModel(file.string(), {});
    const ForceElements& e = model.getForceElements();
    EXPECT_EQ(e.coordinateLimits.size(), 1u);
    EXPECT_EQ(e.springs.size(), 1u);
    EXPECT_EQ(e.bushings.size(), 1u);
    EXPECT_EQ(e.huntCrossley.size(), 1u);
    expectForceElementsMatchSimbody(model, "heel", model.findCoordinateIndex("yTranslation"), "bouncing_block.osim");
}

// A point mass on a ball joint: nothing resists its spin about the line to the joint centre, so the mass
// matrix is singular there; the error names the joint and its link instead of returning infinities.
TEST(ForwardDynamics, RefusesASingularMassMatrixNamingTheJoint) {
    const Model model = readModelText(R"(sinew_model: 1
name: point_mass
links:
  - {name: bob, mass: 1, com: [0, -0.5, 0], inertia: [0, 0, 0, 0, 0, 0]}
joints:
  - {name: swivel, type: ball, parent: ground, child: bob}
)", "point_mass.yaml");
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    calcVelocityKinematics(model, data, Eigen::VectorXd::Zero(model.getNumU()));
    // The serial schedule finds it evaluating; the balanced one, which inverts each body's inertia, at once.
    for (AssemblySchedule::Kind kind : {AssemblySchedule::Kind::Serial, AssemblySchedule::Kind::Balanced}) {
        EXPECT_TRUE(test::throwsErrorAt(
            [&] {
                const AssemblySchedule schedule(model, kind);
                ForwardDynamicsData fd(model, schedule);
                calcForwardDynamics(model, schedule, data, Eigen::VectorXd::Zero(model.getNumU()),
                                    std::vector<SpatialVector>(1, SpatialVector::Zero()), fd);
            },
            "model 'point_mass'", {"link 'bob'", "point mass"}, ""));
    }
    EXPECT_EQ(AssemblySchedule(model).getKind(), AssemblySchedule::Kind::Serial);
}

// A wrist as OpenSim models often build one: a massless intermediate body between two pins (flexion, then
// deviation), the hand beyond it. Non-singular, since the hand's inertia resists both pins: it agrees with
// Simbody. Without the hand, the massless link ends the chain and the error names its joint.
TEST(ForwardDynamics, MasslessIntermediateBodyMatchesSimbodyAndAMasslessEndIsNamed) {
    const std::string wrist = R"(sinew_model: 1
name: wrist
links:
  - {name: forearm, mass: 1.2, com: [0, -0.12, 0], inertia: [0.006, 0.001, 0.006, 0, 0, 0]}
  - {name: lunate, mass: 0, inertia: [0, 0, 0, 0, 0, 0]}
  - {name: hand, mass: 0.45, com: [0.01, -0.07, 0.005], inertia: [0.0009, 0.0003, 0.0008, 0, 0, 0]}
joints:
  - {name: elbow, type: pin, parent: ground, child: forearm, axis: [0, 0, 1]}
  - {name: flexion, type: pin, parent: forearm, child: lunate, parent_point: [0, -0.25, 0], axis: [0, 0, 1]}
  - {name: deviation, type: pin, parent: lunate, child: hand, axis: [1, 0, 0]}
)";
    const Model model = readModelText(wrist, "wrist.yaml");
    std::mt19937 rng(42);
    for (int i = 0; i < 10; ++i) EXPECT_LE(compareWithSimbody(model, rng).udotError, 1e-9);
    const std::string withoutHand = wrist.substr(0, wrist.find("  - {name: hand")) +
                                    wrist.substr(wrist.find("joints:"), wrist.find("  - {name: deviation") - wrist.find("joints:"));
    const Model bare = readModelText(withoutHand, "wrist.yaml");
    Data data(bare);
    calcPositionKinematics(bare, data, bare.getDefaultQ());
    calcVelocityKinematics(bare, data, Eigen::VectorXd::Zero(bare.getNumU()));
    const AssemblySchedule schedule(bare);
    ForwardDynamicsData fd(bare, schedule);
    EXPECT_TRUE(test::throwsErrorAt(
        [&] {
            calcForwardDynamics(bare, schedule, data, Eigen::VectorXd::Zero(bare.getNumU()),
                                std::vector<SpatialVector>(2, SpatialVector::Zero()), fd);
        },
        "model 'wrist'", {"singular", "joint 'flexion'", "link 'lunate'"}, withoutHand));
}

TEST(ForwardDynamics, MatchesSimbodyOnArm26) {
    std::mt19937 rng(32);
    EXPECT_LE(compareWithSimbody(test::loadArm26().model, rng).udotError, 1e-9);
}

// The balanced schedule (O(log N) levels), on one thread or two, against the serial one: same answer to
// roundoff on the same state.
TEST(ForwardDynamics, BalancedScheduleOnThreadsMatchesSerial) {
    std::mt19937 rng(36);
    double worst = 0;
    for (const test::NamedModel& m : makeClosedChainModels(40)) {
        const Model& model = m.model;
        const Eigen::VectorXd q = generateRandomCoordinates(model, rng);
        const Eigen::VectorXd u = generateRandomSpeeds(model, rng);
        const Eigen::VectorXd tau = generateRandomSpeeds(model, rng, 5.0);
        const SinewResult serial = evaluateSinew(model, q, u, tau, 0, AssemblySchedule::Kind::Serial, 1, -1);
        // At this unassembled pose, redundant closures can be inconsistent, and their least-squares answer
        // then depends on the order in which they are closed.
        if (serial.redundantConstraints > 0) continue;
        const double scale = std::max(serial.udot.lpNorm<Eigen::Infinity>(), 1.0);
        for (int threads : {1, 2}) {
            const SinewResult balanced = evaluateSinew(model, q, u, tau, 0, AssemblySchedule::Kind::Balanced, threads, -1);
            const double difference = (balanced.udot - serial.udot).lpNorm<Eigen::Infinity>() / scale;
            EXPECT_LE(difference, 1e-12) << m.name << " threads " << threads;
            worst = std::max(worst, difference);
            if (model.getNumLinks() >= 100) {
                EXPECT_LT(balanced.levels, serial.levels / 4) << m.name;
            }
        }
    }
    std::printf("balanced vs serial schedule: worst relative udot difference %.2e\n", worst);
}

}  // namespace
}  // namespace sinew

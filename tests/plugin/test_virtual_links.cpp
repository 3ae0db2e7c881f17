// Virtual links in both engines: Simbody's (no body for them; VirtualLinkWireForce puts them in equilibrium
// from Simbody's own kinematics of the bones) against sinew's (its kinematics, the same equilibrium solver,
// assembly-disassembly dynamics): udot at random states, whole trajectories, energy with conservative wires,
// and `sinew simulate` on a model file with virtual links.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <unistd.h>

#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/plugin/simbody_simulation.hpp"
#include "sinew/plugin/simbody_model.hpp"
#include "support/forked_model.hpp"
#include "support/test_models.hpp"
#include "support/trajectory_recording.hpp"

namespace sinew {
namespace {

// udot (nu; the virtual links' entries 0) by sinew's engine at bone state (q, u), the virtual links
// warm-started from the model's default pose, as Simbody's force element is.
Eigen::VectorXd calcSinewUdot(const Model& model, Eigen::VectorXd q, Eigen::VectorXd u, double time,
                              VirtualLinkEquilibriumStatus& status) {
    VirtualLinkEquilibriumData eq(model);
    for (int v : eq.links) {
        const Joint& joint = model.getJoint(v);
        q.segment<7>(joint.qStart) = model.getDefaultQ().segment<7>(joint.qStart);
        u.segment<6>(joint.uStart).setZero();
    }
    Data data(model);
    calcPositionKinematics(model, data, q);
    calcVelocityKinematics(model, data, u);
    calcWirePaths(model, data);
    calcWireSpeeds(model, data);
    status = calcVirtualLinkEquilibrium(model, data, time, eq);
    Eigen::VectorXd tensions(model.getNumWires());
    calcWireTensions(model, data, time, tensions);
    calcWireLinkForces(model, data, tensions);
    const AssemblySchedule schedule(model, AssemblySchedule::Kind::Serial);
    ForwardDynamicsData fd(model, schedule);
    calcForwardDynamics(model, schedule, data, Eigen::VectorXd::Zero(model.getNumU()), data.F_G, fd);
    return fd.udot;
}

struct UdotComparison {
    double error = 0;  // max |udot_sinew - udot_Simbody| / max |udot_Simbody| over the bones' entries
    VirtualLinkEquilibriumStatus simbody, sinew;
};

// At an assembled state near the default pose with loop-consistent random speeds.
UdotComparison compareUdot(const Model& model, std::mt19937& rng) {
    const SimbodyModel simbody(model);
    const SimTK::MultibodySystem& system = simbody.getSystem();
    SimTK::State state = simbody.makeState(
        integrateCoordinates(model, model.getDefaultQ(), generateRandomSpeeds(model, rng), 0.1),
        generateRandomSpeeds(model, rng, 2.0), SimTK::Stage::Position);
    try {
        system.project(state, 1e-13);
    } catch (const std::exception&) {  // random loops that lock the mechanism: the default pose
        state = simbody.makeState(model.getDefaultQ(), generateRandomSpeeds(model, rng, 2.0), SimTK::Stage::Position);
    }
    system.realize(state, SimTK::Stage::Velocity);
    system.projectU(state, 1e-13);
    system.realize(state, SimTK::Stage::Acceleration);
    const Eigen::VectorXd udotSimbody = toEigen(state.getUDot());
    UdotComparison c;
    c.simbody = simbody.getVirtualLinkWireForce()->getEquilibrium().status;

    Eigen::VectorXd q, u;
    simbody.calcCoordinates(state, q, u);
    const Eigen::VectorXd udot = calcSinewUdot(model, q, u, state.getTime(), c.sinew);
    const Eigen::Index nu = udotSimbody.size();
    EXPECT_EQ(udot.size(), model.getNumU());
    EXPECT_TRUE(udot.tail(model.getNumU() - nu).isZero(0));
    c.error = (udot.head(nu) - udotSimbody).lpNorm<Eigen::Infinity>() /
              std::max(udotSimbody.lpNorm<Eigen::Infinity>(), 1e-300);
    return c;
}

// generateRandomModel's forks (two heads into a virtual link, a tail out, with and without loops): their
// branches' rest lengths are near their default lengths, so many virtual links find a pose where every
// branch is slack, or one on the edge of it.
TEST(VirtualLinks, UdotMatchesSimbodyOnRandomModels) {
    std::mt19937 rng(41);
    double worst = 0;
    int count = 0, links = 0, slack = 0, stalled = 0;
    for (int loops : {0, 2}) {
        for (unsigned seed = 1; seed <= 15; ++seed) {
            RandomModelOptions o;
            o.numLinks = 3 + static_cast<int>(seed) % 12;
            o.numLoops = loops;
            o.numWires = 2 * o.numLinks;
            o.numVirtualLinks = 1 + static_cast<int>(seed) % 3;
            o.topology = seed % 2 ? RandomModelOptions::Topology::RandomTree : RandomModelOptions::Topology::Chain;
            o.seed = 500 + seed;
            const UdotComparison c = compareUdot(generateRandomModel(o), rng);
            EXPECT_LE(c.error, 1e-9) << test::describe(o);
            worst = std::max(worst, c.error);
            ++count;
            links += o.numVirtualLinks;
            slack += c.sinew.slackLinks;
            stalled += !c.sinew.converged || !c.simbody.converged;
        }
    }
    std::printf("udot, sinew vs Simbody, %d random models with %d virtual links (%d slack; at %d states a solve "
                "stalled where a damped wire goes taut, at the same pose in both engines; 0 or 2 loops): worst relative difference %.2e\n",
                count, links, slack, stalled, worst);
}

// The shipped whole-body model (51 links, 10 virtual links, 4 loops, 990 wires, MuJoCo wraps) at random states
// near the neutral pose. Random speeds stretch some damped fork wires as they go taut, where no exact
// equilibrium exists; both engines then stop at the same pose, so udot still agrees.
TEST(VirtualLinks, UdotMatchesSimbodyOnTheWholeBodyModel) {
    const Model model = readModelFile(SINEW_SOURCE_DIR "/models/whole_body/whole_body.yaml");
    std::mt19937 rng(47);
    double worst = 0;
    int stalled = 0;
    for (int k = 0; k < 4; ++k) {
        const UdotComparison c = compareUdot(model, rng);
        EXPECT_LE(c.error, 1e-9);
        worst = std::max(worst, c.error);
        stalled += !c.sinew.converged || !c.simbody.converged;
    }
    std::printf("udot, sinew vs Simbody, whole-body model at 4 states (%d with a stalled solve): worst relative "
                "difference %.2e\n", stalled, worst);
}

// Forks that stay pulled (support/forked_model.hpp): 3 virtual links, with and without a loop.
TEST(VirtualLinks, UdotMatchesSimbodyOnTautForks) {
    std::mt19937 rng(43);
    double worst = 0;
    int count = 0;
    for (bool loop : {false, true}) {
        for (unsigned seed = 1; seed <= 10; ++seed) {
            test::ForkedModelOptions o;
            o.numLinks = 5 + static_cast<int>(seed) % 4;
            o.numForks = 3;
            o.loop = loop;
            o.rootJoint = seed % 2 ? JointType::Free : JointType::Ball;
            o.seed = seed;
            const UdotComparison c = compareUdot(test::makeForkedModel(o), rng);
            EXPECT_LE(c.error, 1e-9) << "seed " << seed << " loop " << loop;
            EXPECT_TRUE(c.simbody.converged && c.sinew.converged) << "seed " << seed << " loop " << loop;
            EXPECT_EQ(c.sinew.slackLinks, 0) << "seed " << seed << " loop " << loop;
            worst = std::max(worst, c.error);
            ++count;
        }
    }
    std::printf("udot, sinew vs Simbody, %d chains with 3 taut forks (with and without a loop): worst relative "
                "difference %.2e\n", count, worst);
}

// A chain of 4 links hanging from a weld with two forks of soft springs pulling it sideways: it swings by
// ~0.9 rad with every wire taut throughout (no slack-taut switch, no jump), so its trajectory is smooth and
// the engines can agree closely.
Model makeSwingingModel(double damping) {
    test::ForkedModelOptions o;
    o.numLinks = 4;
    o.rootJoint = JointType::Weld;
    o.numForks = 2;
    o.jointWires = false;
    o.forkStiffness = 200;
    o.damping = damping;
    o.seed = 1;
    return test::makeForkedModel(o);
}

// 1 s from rest with both engines at accuracy 1e-10: every frame's q, the virtual links' poses included.
TEST(VirtualLinks, OneSecondTrajectoriesAgree) {
    const Model model = makeSwingingModel(2.0);
    ForwardSimulationOptions options;
    options.duration = 1.0;
    options.accuracy = 1e-10;
    const Trajectory sinew = record(simulateForwardSinew, model, options);
    const Trajectory simbody = record(simulateForward, model, options);
    ASSERT_EQ(sinew.frames.size(), 101u);
    ASSERT_EQ(simbody.frames.size(), 101u);
    double dq = 0, dqVirtual = 0, travel = 0, dTension = 0, tension = 0;
    for (std::size_t i = 0; i < sinew.frames.size(); ++i) {
        const Eigen::VectorXd diff = sinew.frames[i].q - simbody.frames[i].q;
        for (int l = 0; l < model.getNumLinks(); ++l) {
            const Joint& joint = model.getJoint(l);
            const double d = diff.segment(joint.qStart, joint.nq).lpNorm<Eigen::Infinity>();
            double& worst = model.getLink(l).isVirtual ? dqVirtual : dq;
            worst = std::max(worst, d);
        }
        travel = std::max(travel, (simbody.frames[i].q - simbody.frames.front().q).lpNorm<Eigen::Infinity>());
        dTension = std::max(dTension, (sinew.frames[i].tensions - simbody.frames[i].tensions).lpNorm<Eigen::Infinity>());
        tension = std::max(tension, simbody.frames[i].tensions.lpNorm<Eigen::Infinity>());
    }
    std::printf("swinging chain with 2 virtual links, 1 s: max |q_sinew - q_simbody| bones %.2e, virtual links %.2e "
                "(travel %.2f); tensions %.2e of %.1f N; steps sinew %d, Simbody %d; equilibrium residual sinew %.1e N, "
                "Simbody %.1e N\n", dq, dqVirtual, travel, dTension, tension, sinew.summary.steps, simbody.summary.steps,
                sinew.summary.maxVirtualLinkResidual, simbody.summary.maxVirtualLinkResidual);
    EXPECT_EQ(sinew.summary.wireSwitches, 0);
    EXPECT_GT(travel, 0.05);
    EXPECT_LE(dq, 1e-8);
    EXPECT_LE(dqVirtual, 1e-8);
    EXPECT_LE(dTension, 1e-8 * tension);
}

// Conservative wires: a quasi-static virtual link stores no energy of its own beyond its wires' (it sits at
// their potential's minimum, so moving it does no work), and the total energy is conserved by both engines.
TEST(VirtualLinks, EnergyIsConservedWithConservativeWires) {
    const Model model = makeSwingingModel(0.0);
    ForwardSimulationOptions options;
    options.duration = 1.0;
    options.accuracy = 1e-10;
    for (const bool useSinew : {true, false}) {
        const Trajectory t = record(useSinew ? simulateForwardSinew : simulateForward, model, options);
        std::printf("%s engine, conservative wires through 2 virtual links, 1 s: energy drift %.2e J of peak "
                    "kinetic energy %.3f J\n", useSinew ? "sinew" : "Simbody", t.summary.maxEnergyDrift,
                    t.summary.peakKineticEnergy);
        EXPECT_GT(t.summary.peakKineticEnergy, 0.01);
        EXPECT_LE(t.summary.maxEnergyDrift, 1e-8 * t.summary.peakKineticEnergy) << (useSinew ? "sinew" : "Simbody");
    }
}

// `sinew simulate` with either engine on a model file with virtual links; the sinew executable is built next
// to this test's.
TEST(VirtualLinks, CommandLineSimulatesAModelWithVirtualLinks) {
    const std::filesystem::path cli = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "sinew";
    ASSERT_TRUE(std::filesystem::exists(cli)) << cli << " is missing: build the sinew_cli target";
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("sinew_virtual_links_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const Model model = makeSwingingModel(2.0);
    writeModelFile(model, (dir / "forked.yaml").string());
    for (const char* engine : {"sinew", "simbody"}) {
        const std::filesystem::path out = dir / engine, log = dir / (std::string(engine) + ".log");
        const std::string command = cli.string() + " simulate " + (dir / "forked.yaml").string() + " --engine " +
                                    engine + " --duration 0.1 -o " + out.string() + " > " + log.string() + " 2>&1";
        EXPECT_EQ(std::system(command.c_str()), 0) << command;
        std::stringstream text;
        text << std::ifstream(log).rdbuf();
        EXPECT_NE(text.str().find("11 frames"), std::string::npos) << text.str();
        EXPECT_FALSE(std::filesystem::is_empty(out)) << out;
    }
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace sinew

// Forward simulation through Simbody with sinew's wires: energy conservation with conservative wires,
// the hang-by weld, and clear refusals.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <regex>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/simbody/forward_simulation.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

struct EnergyRecord {
    double initial = 0, maxDrift = 0, peakKinetic = 0;
    int frames = 0;
};

// Relative drift: max |E(t) - E(0)| over 1 s divided by the peak kinetic energy (the energy that moves
// between kinetic, gravitational and elastic forms; E itself depends on the arbitrary gravity datum).
EnergyRecord simulateEnergy(const Model& model, const Eigen::VectorXd& u0, const std::string& hangBy) {
    ForwardSimulationOptions options;
    options.duration = 1.0;
    options.reportInterval = 0.01;
    options.accuracy = 1e-10;
    options.hangBy = hangBy;
    options.initialSpeeds = u0;
    EnergyRecord record;
    simulateForward(model, options, [&](const SimulationFrame& frame) {
        const double energy = frame.kineticEnergy + frame.potentialEnergy;
        if (record.frames++ == 0) record.initial = energy;
        record.maxDrift = std::max(record.maxDrift, std::abs(energy - record.initial));
        record.peakKinetic = std::max(record.peakKinetic, frame.kineticEnergy);
        EXPECT_TRUE(frame.tensions.allFinite());
        EXPECT_GE(frame.tensions.minCoeff(), 0.0);
    });
    return record;
}

TEST(ForwardSimulation, ConservesEnergyWithUndampedWiresAndLoops) {
    std::mt19937 rng(21);
    for (int i = 0; i < 6; ++i) {
        RandomModelOptions o;
        o.seed = static_cast<unsigned>(300 + i);
        o.numLinks = 3 + 2 * i;
        o.topology = i % 2 ? RandomModelOptions::Topology::Chain : RandomModelOptions::Topology::RandomTree;
        o.rootJoint = i % 3 == 0 ? JointType::Free : JointType::Ball;
        o.numLoops = i % 3;
        o.numWires = 3 * o.numLinks;
        o.damping = 0;
        const Model model = generateRandomModel(o);
        const EnergyRecord r = simulateEnergy(model, generateRandomSpeeds(model, rng, 1.0), "");
        ASSERT_EQ(r.frames, 101);
        ASSERT_GT(r.peakKinetic, 1e-3) << test::describe(o);
        std::printf("%s: relative energy drift %.2e over 1 s\n", test::describe(o).c_str(), r.maxDrift / r.peakKinetic);
        EXPECT_LE(r.maxDrift / r.peakKinetic, 1e-4) << test::describe(o) << " drift " << r.maxDrift << " J";
    }
}

TEST(ForwardSimulation, ConservesEnergyOnUndampedArm26) {
    test::NamedModel arm = test::loadArm26();
    std::string text = writeModelText(arm.model);
    text = std::regex_replace(text, std::regex("damping: [0-9.eE+-]+"), "damping: 0");
    const Model undamped = readModelText(text, "arm26-undamped");
    const EnergyRecord r = simulateEnergy(undamped, Eigen::VectorXd(), "base");
    ASSERT_GT(r.peakKinetic, 0.1);
    std::printf("arm26 undamped: relative energy drift %.2e over 1 s\n", r.maxDrift / r.peakKinetic);
    EXPECT_LE(r.maxDrift / r.peakKinetic, 1e-4) << "drift " << r.maxDrift << " J";
}

TEST(ForwardSimulation, DampedWiresDissipate) {
    const test::NamedModel arm = test::loadArm26();
    const EnergyRecord r = simulateEnergy(arm.model, Eigen::VectorXd(), "base");
    EXPECT_GT(r.maxDrift / r.peakKinetic, 1e-2);
}

// Both engines: the hung link stays where it was while the rest of the body swings.
TEST(ForwardSimulation, HangByHoldsTheLinkAtItsInitialPose) {
    RandomModelOptions o;
    o.numLinks = 8;
    o.numLoops = 1;
    o.seed = 77;
    const Model model = generateRandomModel(o);
    ForwardSimulationOptions options;
    options.duration = 0.3;
    options.hangBy = model.getLink(3).name;
    options.accuracy = 1e-8;
    for (auto simulate : {&simulateForward, &simulateForwardSinew}) {
        Data start(model), now(model);
        calcPositionKinematics(model, start, model.getDefaultQ());
        double worstOffset = 0, worstTravel = 0;
        simulate(model, options, [&](const SimulationFrame& frame) {
            calcPositionKinematics(model, now, frame.q);
            worstOffset = std::max(worstOffset, (now.p_GB[3] - start.p_GB[3]).norm());
            worstTravel = std::max(worstTravel, (now.p_GB[7] - start.p_GB[7]).norm());
        });
        EXPECT_LE(worstOffset, 1e-6) << (simulate == &simulateForward ? "simbody" : "sinew");
        EXPECT_GT(worstTravel, 1e-3) << "the rest of the body should swing";
    }
}

TEST(ForwardSimulation, RefusesUnknownHangLinkAndVirtualLinks) {
    RandomModelOptions o;
    o.numLinks = 3;
    ForwardSimulationOptions options;
    options.hangBy = "no_such_link";
    auto ignore = [](const SimulationFrame&) {};
    EXPECT_THROW(
        {
            try {
                simulateForward(generateRandomModel(o), options, ignore);
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find("no link 'no_such_link'"), std::string::npos) << e.what();
                throw;
            }
        },
        Error);
    o.numVirtualLinks = 1;
    options.hangBy.clear();
    EXPECT_THROW(simulateForward(generateRandomModel(o), options, ignore), Error);
}

}  // namespace
}  // namespace sinew

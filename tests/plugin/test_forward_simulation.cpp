// Forward simulation with both engines (Simbody with sinew's wires, and sinew's own): energy conservation
// with conservative wires, the hang-by weld, and clear refusals.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <utility>
#include <random>
#include <regex>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/plugin/simbody_simulation.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

using Simulate = SimulationSummary (*)(const Model&, const ForwardSimulationOptions&,
                                      const std::function<void(const SimulationFrame&)>&);
const std::pair<const char*, Simulate> kEngines[] = {{"simbody", &simulateForward}, {"sinew", &simulateForwardSinew}};

// Relative drift: max |E(t) - E(0)| over 1 s divided by the peak kinetic energy (the energy that moves
// between kinetic, gravitational and elastic forms; E itself depends on the arbitrary gravity datum).
double simulateEnergyDrift(Simulate simulate, const Model& model, const Eigen::VectorXd& u0, const std::string& hangBy,
                           SimulationSummary& summary) {
    ForwardSimulationOptions options;
    options.accuracy = 1e-10;
    options.hangBy = hangBy;
    options.initialSpeeds = u0;
    summary = simulate(model, options, [&](const SimulationFrame& frame) {
        EXPECT_TRUE(frame.tensions.allFinite());
        EXPECT_GE(frame.tensions.minCoeff(), 0.0);
    });
    EXPECT_EQ(summary.frames, 101);
    return summary.maxEnergyDrift / summary.peakKineticEnergy;
}

// Both engines. Odd cases hang by a middle link and start at rest; even ones fly free with random speeds,
// projected onto the loop constraints.
TEST(ForwardSimulation, ConservesEnergyWithUndampedWiresAndLoops) {
    for (const auto& [engine, simulate] : kEngines) {
        std::mt19937 rng(21);
        for (int i = 0; i < 6; ++i) {
            RandomModelOptions o;
            o.seed = static_cast<unsigned>(300 + i);
            o.numLinks = 3 + 2 * i;
            o.topology = i % 2 ? RandomModelOptions::Topology::Chain : RandomModelOptions::Topology::RandomTree;
            o.rootJoint = i % 3 == 0 ? JointType::Free : JointType::Ball;
            o.numLoops = 1 + i % 2;
            o.numWires = 3 * o.numLinks;
            o.damping = 0;
            const Model model = generateRandomModel(o);
            const std::string hangBy = i % 2 ? model.getLink(o.numLinks / 2).name : "";
            SimulationSummary s;
            const double drift = simulateEnergyDrift(simulate, model, i % 2 ? Eigen::VectorXd() : generateRandomSpeeds(model, rng, 1.0),
                                                     hangBy, s);
            ASSERT_GT(s.peakKineticEnergy, 1e-3) << test::describe(o);
            std::printf("%s, %s%s: relative energy drift %.2e over 1 s, constraint violation %.1e m, %d steps\n", engine,
                        test::describe(o).c_str(), hangBy.empty() ? "" : (" hung by " + hangBy).c_str(), drift,
                        s.maxConstraintViolation, s.steps);
            EXPECT_LE(drift, 1e-4) << engine << " " << test::describe(o);
            EXPECT_LE(s.maxConstraintViolation, 1e-7) << engine << " " << test::describe(o);
        }
    }
}

TEST(ForwardSimulation, ConservesEnergyOnUndampedArm26) {
    test::NamedModel arm = test::loadArm26();
    std::string text = writeModelText(arm.model);
    text = std::regex_replace(text, std::regex("damping: [0-9.eE+-]+"), "damping: 0");
    const Model undamped = readModelText(text, "arm26-undamped");
    for (const auto& [engine, simulate] : kEngines) {
        SimulationSummary s;
        const double drift = simulateEnergyDrift(simulate, undamped, Eigen::VectorXd(), "base", s);
        ASSERT_GT(s.peakKineticEnergy, 0.1);
        std::printf("%s, arm26 undamped: relative energy drift %.2e over 1 s\n", engine, drift);
        EXPECT_LE(drift, 1e-4) << engine;
    }
}

// OpenSim's own models as they stand (no damping in either: Thelen muscles' passive fibres are elastic), hung
// by the pelvis and started with random speeds: gait2392 (custom joints, moving and conditional path points,
// 92 muscles) and Rajagopal 2015 (custom joints whose one coordinate drives three rotations, two couplers).
// Both engines at accuracy 1e-8.
TEST(ForwardSimulation, ConservesEnergyOnOpenSimModels) {
    const std::filesystem::path models = std::filesystem::path(SINEW_SHARED_DIR) / "data/opensim-models/Models";
    if (!std::filesystem::exists(models)) GTEST_SKIP() << models << " is absent (it ships with ../shared only)";
    for (const char* file : {"Gait2392_Simbody/gait2392_thelen2003muscle.osim", "Rajagopal_OpenSense/Rajagopal2015_opensense.osim"}) {
        const Model model = loadModel((models / file).string(), {});
        std::mt19937 rng(22);
        const Eigen::VectorXd u0 = generateRandomSpeeds(model, rng, 1.0);
        for (const auto& [engine, simulate] : kEngines) {
            ForwardSimulationOptions options;
            options.accuracy = 1e-8;
            options.hangBy = "pelvis";
            options.initialSpeeds = u0;
            const SimulationSummary s = simulate(model, options, [](const SimulationFrame&) {});
            const double drift = s.maxEnergyDrift / s.peakKineticEnergy;
            ASSERT_GT(s.peakKineticEnergy, 1.0) << file;
            std::printf("%s, %s: relative energy drift %.2e over 1 s (peak kinetic energy %.0f J), constraint violation "
                        "%.1e, %d steps\n", engine, file, drift, s.peakKineticEnergy, s.maxConstraintViolation, s.steps);
            EXPECT_LE(drift, 1e-5) << engine << " " << file;
            EXPECT_LE(s.maxConstraintViolation, 1e-7) << engine << " " << file;
        }
    }
}

TEST(ForwardSimulation, DampedWiresDissipate) {
    const test::NamedModel arm = test::loadArm26();
    for (const auto& [engine, simulate] : kEngines) {
        SimulationSummary s;
        EXPECT_GT(simulateEnergyDrift(simulate, arm.model, Eigen::VectorXd(), "base", s), 1e-2) << engine;
    }
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
    for (const auto& [engine, simulate] : kEngines) {
        Data start(model), now(model);
        calcPositionKinematics(model, start, model.getDefaultQ());
        double worstOffset = 0, worstTravel = 0;
        simulate(model, options, [&](const SimulationFrame& frame) {
            calcPositionKinematics(model, now, frame.q);
            worstOffset = std::max(worstOffset, (now.p_GB[3] - start.p_GB[3]).norm());
            worstTravel = std::max(worstTravel, (now.p_GB[7] - start.p_GB[7]).norm());
        });
        EXPECT_LE(worstOffset, 1e-6) << engine;
        EXPECT_GT(worstTravel, 1e-3) << "the rest of the body should swing";
    }
}

TEST(ForwardSimulation, RefusesUnknownOrVirtualHangLink) {
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
    options.hangBy = "virtual0";
    EXPECT_THROW(simulateForward(generateRandomModel(o), options, ignore), Error);
}

}  // namespace
}  // namespace sinew

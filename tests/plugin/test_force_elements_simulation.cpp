// Force elements in motion, both engines: the block-and-leg model (tests/support/force_element_model.hpp)
// dropped 2 cm onto the floor with every damping and friction off conserves its energy in each engine, and
// the two engines (sinew's elements; Simbody's own spring, bushing and Hunt-Crossley contact) follow the
// same trajectory through the bounce.
#include <gtest/gtest.h>

#include <regex>

#include "sinew/core/forward_simulation.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/plugin/simbody_simulation.hpp"
#include "support/force_element_model.hpp"

namespace sinew {
namespace {

TEST(ForceElementsSimulation, BothEnginesBounceAlikeAndConserveEnergyWithoutDamping) {
    std::string text = test::kForceElementModelText;
    text = std::regex_replace(text, std::regex("initial_position: \\[0, 1.1, 0\\]"), "initial_position: [0, 1.07, 0]");
    text = std::regex_replace(text, std::regex("(dissipation|static_friction|dynamic_friction|viscous_friction): [0-9.e]+"),
                              "$1: 0");
    text = std::regex_replace(text, std::regex("damping: \\[[0-9., ]+\\]"), "damping: [0, 0, 0]");
    text = std::regex_replace(text, std::regex("damping: 1,"), "damping: 0,");
    text = std::regex_replace(text, std::regex("stiffness: [12]e7"), "stiffness: 1e6");
    const Model model = readModelText(text, "undamped_elements.yaml");
    ForwardSimulationOptions options;
    options.duration = 0.3;
    options.accuracy = 1e-9;
    std::vector<Eigen::VectorXd> trajectories[2];
    double minHeight[2] = {1e9, 1e9};
    int engine = 0;
    const int block = model.getJoint(model.findLinkIndex("block")).qStart + 5;
    for (auto simulate : {&simulateForward, &simulateForwardSinew}) {
        const SimulationSummary summary = simulate(model, options, [&](const SimulationFrame& frame) {
            trajectories[engine].push_back(frame.q);
            minHeight[engine] = std::min(minHeight[engine], frame.q[block]);
        });
        EXPECT_GT(summary.peakKineticEnergy, 1.0) << engine;
        EXPECT_LE(summary.maxEnergyDrift / summary.peakKineticEnergy, 1e-6) << engine;
        std::printf("engine %d: %d steps, energy drift %.2e of the peak kinetic energy %.3g J\n", engine, summary.steps,
                    summary.maxEnergyDrift / summary.peakKineticEnergy, summary.peakKineticEnergy);
        ++engine;
    }
    // The heel reached the floor: the block came down more than the 2 cm gap.
    EXPECT_LT(minHeight[0], 1.07 - 0.02);
    ASSERT_EQ(trajectories[0].size(), trajectories[1].size());
    double worst = 0;
    for (std::size_t k = 0; k < trajectories[0].size(); ++k)
        worst = std::max(worst, (trajectories[0][k] - trajectories[1][k]).lpNorm<Eigen::Infinity>());
    std::printf("largest difference between the engines' trajectories: %.2e rad or m\n", worst);
    EXPECT_LE(worst, 1e-6) << "rad or m";
}

}  // namespace
}  // namespace sinew

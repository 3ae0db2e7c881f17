// sinew's own simulation engine (simulateForwardSinew) on its own: energy conservation with undamped wires and
// loops, fourth-order convergence of the fixed-step RK4, no heap allocation while stepping, and clear
// refusals. Its agreement with Simbody's engine is tests/plugin/test_forward_simulation_sinew.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/core/kinematics.hpp"
#include "support/allocation_counter.hpp"
#include "support/test_models.hpp"


namespace sinew {
namespace {

using Integrator = ForwardSimulationOptions::Integrator;

ForwardSimulationOptions makeOptions(double accuracy, const std::string& hangBy = "") {
    ForwardSimulationOptions options;
    options.duration = 1.0;
    options.reportInterval = 0.01;
    options.accuracy = accuracy;
    options.hangBy = hangBy;
    return options;
}

std::vector<SimulationFrame> simulate(const Model& model, const ForwardSimulationOptions& options,
                                      SimulationSummary* summary = nullptr) {
    std::vector<SimulationFrame> frames;
    const SimulationSummary s = simulateForwardSinew(model, options, [&](const SimulationFrame& f) { frames.push_back(f); });
    if (summary) *summary = s;
    return frames;
}

// Classic RK4 is fourth order: halving the step divides the error against a tight adaptive reference by ~16.
// A smooth problem (a pendulum chain under gravity, no wires: a wire going slack is a kink in the forces that
// costs any Runge-Kutta method its order).
TEST(ForwardSimulationSinew, FixedStepRungeKutta4ConvergesAtFourthOrder) {
    RandomModelOptions o;
    o.seed = 5;
    o.numLinks = 4;
    o.topology = RandomModelOptions::Topology::Chain;
    o.rootJoint = JointType::Ball;
    o.numWires = 0;
    const Model model = generateRandomModel(o);
    ForwardSimulationOptions options = makeOptions(1e-13);
    options.duration = 0.5;
    options.reportInterval = 0.05;
    const std::vector<SimulationFrame> reference = simulate(model, options);
    options.integrator = Integrator::RungeKutta4Fixed;
    std::vector<double> errors;
    for (const double step : {2.5e-3, 1.25e-3, 0.625e-3}) {  // 20, 40, 80 steps per report interval
        options.fixedStep = step;
        SimulationSummary s;
        const std::vector<SimulationFrame> frames = simulate(model, options, &s);
        ASSERT_EQ(frames.size(), reference.size());
        EXPECT_EQ(s.steps, static_cast<int>(std::lround(options.duration / step)));
        double error = 0;
        for (std::size_t i = 0; i < frames.size(); ++i)
            error = std::max(error, (frames[i].q - reference[i].q).lpNorm<Eigen::Infinity>());
        errors.push_back(error);
    }
    for (std::size_t k = 1; k < errors.size(); ++k) {
        const double ratio = errors[k - 1] / errors[k];
        std::printf("RK4 step %.3g s: max q error %.2e, ratio to the step twice as long %.1f\n", 2.5e-3 / (1 << k),
                    errors[k], ratio);
        EXPECT_GT(ratio, 16 / 1.3);
        EXPECT_LT(ratio, 16 * 1.3);
    }
    EXPECT_LT(errors.back(), 1e-6);
}

// Wires snapping slack and taut are kinks (jumps, with damping) in the forces; the adaptive integrator locates
// them and steps across, so its error stays of the order of its accuracy setting: 1e-10 against a 1e-13
// reference on a hang that throws the body about (the model of the Simbody comparison).
TEST(ForwardSimulationSinew, AdaptiveIntegratorConvergesAcrossWireSwitches) {
    RandomModelOptions o;
    o.numLinks = 8;
    o.numLoops = 2;
    o.seed = 2;
    const Model model = generateRandomModel(o);
    SimulationSummary s, reference;
    const std::vector<SimulationFrame> frames = simulate(model, makeOptions(1e-10, model.getLink(3).name), &s);
    const std::vector<SimulationFrame> exact = simulate(model, makeOptions(1e-13, model.getLink(3).name), &reference);
    ASSERT_EQ(frames.size(), exact.size());
    double error = 0;
    for (std::size_t i = 0; i < frames.size(); ++i)
        error = std::max(error, (frames[i].q - exact[i].q).lpNorm<Eigen::Infinity>());
    std::printf("accuracy 1e-10: max q error %.2e against 1e-13 (%d steps, %d wire switches; reference %d steps)\n", error,
                s.steps, s.wireSwitches, reference.steps);
    EXPECT_GT(s.wireSwitches, 10);
    EXPECT_LE(error, 1e-7);
}

// The house rule (no allocation inside the loop): nothing between two frames but the integration itself.
TEST(ForwardSimulationSinew, AllocatesNothingWhileStepping) {
    if (!test::isCountingAllocations()) GTEST_SKIP() << "allocations are not counted under AddressSanitizer";
    RandomModelOptions o;
    o.numLinks = 8;
    o.numLoops = 2;
    o.seed = 7;
    const Model model = generateRandomModel(o);
    for (const Integrator integrator : {Integrator::Adaptive, Integrator::RungeKutta4Fixed}) {
        ForwardSimulationOptions options = makeOptions(1e-8, model.getLink(3).name);
        options.duration = 0.1;
        options.integrator = integrator;
        long long atFirstFrame = -1, atLastFrame = -1;
        const SimulationSummary s = simulateForwardSinew(model, options, [&](const SimulationFrame& frame) {
            (frame.time == 0 ? atFirstFrame : atLastFrame) = test::getAllocationCount();
        });
        EXPECT_GT(s.steps, 10);
        if (integrator == Integrator::Adaptive) {
            EXPECT_GT(s.wireSwitches, 0) << "the switch location path is not exercised";
        }
        EXPECT_EQ(atLastFrame - atFirstFrame, 0) << toString(integrator);
    }
}

TEST(ForwardSimulationSinew, ProjectsInitialSpeedsOntoTheConstraints) {
    RandomModelOptions o;
    o.numLinks = 6;
    o.numLoops = 2;
    o.seed = 11;
    const Model model = generateRandomModel(o);
    std::mt19937 rng(3);
    ForwardSimulationOptions options = makeOptions(1e-10, model.getLink(2).name);
    options.duration = 0.01;
    options.initialSpeeds = generateRandomSpeeds(model, rng, 1.0);
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    bool first = true;
    simulateForwardSinew(model, options, [&](const SimulationFrame& frame) {
        if (!first) return;
        first = false;
        calcVelocityKinematics(model, data, frame.u);
        EXPECT_LE(data.w_GB[2].norm() + data.v_GB[2].norm(), 1e-12) << "the hung link moves";
        for (const Loop& loop : model.getLoops()) {
            auto velocity = [&](int link, const Eigen::Vector3d& p_B) {
                const std::size_t b = static_cast<std::size_t>(link);
                return Eigen::Vector3d(data.v_GB[b] + data.w_GB[b].cross(data.R_GB[b] * p_B));
            };
            EXPECT_LE((velocity(loop.linkA, loop.p_A) - velocity(loop.linkB, loop.p_B)).norm(), 1e-12) << loop.name;
        }
        EXPECT_GT(frame.u.norm(), 0.1) << "projection should keep the compatible part of the speeds";
    });
}

TEST(ForwardSimulationSinew, RefusesUnknownOrVirtualHangLinkAndBadOptions) {
    RandomModelOptions o;
    o.numLinks = 3;
    const Model model = generateRandomModel(o);
    auto ignore = [](const SimulationFrame&) {};
    ForwardSimulationOptions options;
    options.hangBy = "no_such_link";
    try {
        simulateForwardSinew(model, options, ignore);
        ADD_FAILURE() << "no error for an unknown hang link";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no link 'no_such_link'"), std::string::npos) << e.what();
    }
    options.hangBy.clear();
    options.integrator = Integrator::RungeKutta4Fixed;
    options.fixedStep = 0;
    EXPECT_THROW(simulateForwardSinew(model, options, ignore), Error);
    options = ForwardSimulationOptions();
    options.initialSpeeds = Eigen::VectorXd::Zero(model.getNumU() + 1);
    EXPECT_THROW(simulateForwardSinew(model, options, ignore), Error);
    o.numVirtualLinks = 1;
    options = ForwardSimulationOptions();
    options.hangBy = "virtual0";
    try {
        simulateForwardSinew(generateRandomModel(o), options, ignore);
        ADD_FAILURE() << "no error for hanging by a virtual link";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'virtual0' is a virtual link"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sinew

// Coupled coordinates and Simbody: OpenSim's inverse dynamics ignores constraints
// (SimbodyMatterSubsystem::calcResidualForceIgnoringConstraints), so the dependent coordinate of a coupler
// gets a generalized force of its own; sinew's inverse dynamics of a coupled model, along a motion that
// satisfies the coupler, is checked against that Simbody call. Forward simulation enforces the coupler in
// both engines, which follow the same motion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/plugin/simbody_simulation.hpp"
#include "sinew/plugin/simbody_model.hpp"
#include "support/coupled_knee.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

using test::kCoupledKnee;

TEST(CoordinateCouplerSimbody, InverseDynamicsGivesTheDependentCoordinateItsOwnForceAsOpenSim) {
    const Model model = readModelText(kCoupledKnee, "coupled_knee.yaml");
    ASSERT_EQ(model.getNumCouplers(), 1);
    const int hip = model.findCoordinateIndex("hip"), knee = model.findCoordinateIndex("knee_angle"),
              tx = model.findCoordinateIndex("knee_tx");
    const SimbodyModel simbody(model, {"", true, false});
    const SimTK::MultibodySystem& system = simbody.getSystem();
    Data data(model);
    Eigen::VectorXd tau(model.getNumU());
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    double worst = 0, dependentForce = 0;
    for (double t : {0.0, 0.3, 0.7, 1.1}) {
        // hip(t), knee(t) and the coupled knee_tx(t) with its rate and acceleration by the chain rule.
        Eigen::VectorXd q(3), u(3), udot(3);
        q[hip] = 0.4 * std::sin(2 * t);
        u[hip] = 0.8 * std::cos(2 * t);
        udot[hip] = -1.6 * std::sin(2 * t);
        q[knee] = -0.8 + 0.6 * std::sin(3 * t);
        u[knee] = 1.8 * std::cos(3 * t);
        udot[knee] = -5.4 * std::sin(3 * t);
        applyCoordinateCouplers(model, q);
        EXPECT_NEAR(q[tx], 2 * (0.01 * q[knee] * q[knee] - 0.02 * q[knee]), 1e-16);
        u[tx] = 2 * (0.02 * q[knee] - 0.02) * u[knee];
        udot[tx] = 2 * (0.02 * u[knee] * u[knee] + (0.02 * q[knee] - 0.02) * udot[knee]);
        calcInverseDynamics(model, data, q, u, udot, noLoads, tau);

        SimTK::State state = simbody.makeState(q, u);
        system.realize(state, SimTK::Stage::Dynamics);  // gravity, as a force element
        SimTK::Vector residual;
        simbody.getMatter().calcResidualForceIgnoringConstraints(
            state, system.getMobilityForces(state, SimTK::Stage::Dynamics),
            system.getRigidBodyForces(state, SimTK::Stage::Dynamics), toSimTK(udot), residual);
        const Eigen::VectorXd reference = toEigen(residual);
        worst = std::max(worst, (tau - reference).lpNorm<Eigen::Infinity>() / std::max(1.0, reference.lpNorm<Eigen::Infinity>()));
        dependentForce = std::max(dependentForce, std::abs(tau[tx]));
    }
    EXPECT_LT(worst, 1e-10);
    // The slide carries the shank's weight and inertia along x: a force of its own, not folded into the knee.
    EXPECT_GT(dependentForce, 0.1) << "N";
}

// Forward simulation enforces the coupler in both engines (Simbody's Constraint::CoordinateCoupler; sinew's
// multipliers): the same trajectory over 1 s, the dependent coordinate on the coupler, energy conserved.
TEST(CoordinateCouplerSimbody, BothEnginesSimulateTheSameCoupledMotion) {
    const Model model = readModelText(kCoupledKnee, "coupled_knee.yaml");
    const CoordinateCoupler& coupler = model.getCouplers().front();
    ForwardSimulationOptions options;
    options.accuracy = 1e-10;
    options.initialSpeeds = Eigen::Vector3d(1.0, 0.5, 0.0);  // projected onto the coupler by both engines
    std::vector<Eigen::VectorXd> trajectories[2];
    int engine = 0;
    for (auto simulate : {&simulateForward, &simulateForwardSinew}) {
        double gap = 0;
        const SimulationSummary summary = simulate(model, options, [&](const SimulationFrame& frame) {
            trajectories[engine].push_back(frame.q);
            gap = std::max(gap, std::abs(frame.q[coupler.dependentQ] -
                                         coupler.scaleFactor * coupler.function.calcValue(frame.q[coupler.independentQ])));
        });
        ASSERT_GT(summary.peakKineticEnergy, 0.1);
        EXPECT_LE(gap, 1e-8) << engine;
        EXPECT_LE(summary.maxEnergyDrift / summary.peakKineticEnergy, 1e-7) << engine;
        ++engine;
    }
    ASSERT_EQ(trajectories[0].size(), trajectories[1].size());
    double worst = 0;
    for (std::size_t k = 0; k < trajectories[0].size(); ++k)
        worst = std::max(worst, (trajectories[0][k] - trajectories[1][k]).lpNorm<Eigen::Infinity>());
    EXPECT_LE(worst, 1e-7) << "rad or m";
}

}  // namespace
}  // namespace sinew

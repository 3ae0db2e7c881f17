// sinew's assembly-disassembly forward dynamics against Simbody's (realize(Acceleration) with the same loop
// constraints, gravity, wires and generalized forces), on assembled states with non-zero velocities.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/simbody/simbody_model.hpp"
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

Comparison compareWithSimbody(const Model& model, std::mt19937& rng) {
    SimbodyModel simbody(model);
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
    Data data(model);
    calcPositionKinematics(model, data, q);
    calcVelocityKinematics(model, data, u);
    calcWirePaths(model, data);
    calcWireSpeeds(model, data);
    Eigen::VectorXd tensions(model.getNumWires());
    calcWireTensions(model, data, state.getTime(), tensions);
    calcWireLinkForces(model, data, tensions);
    const AssemblySchedule schedule(model);
    ForwardDynamicsData fd(model, schedule);
    calcForwardDynamics(model, schedule, data, tau, data.F_G, fd);

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
        worst = std::max(worst, (reaction_G - fd.loopForce[static_cast<std::size_t>(k)]).lpNorm<Eigen::Infinity>());
    }
    result.redundantConstraints = fd.redundantConstraints;
    result.loopConditioning = fd.loopConditioning;
    // Relative to the problem's force scale: the largest of the loop forces, wire tensions and total weight.
    double weight = 0;
    for (const Link& link : model.getLinks()) weight += link.mass * model.getGravity().norm();
    const double forceScale = std::max({largest, tensions.size() ? tensions.maxCoeff() : 0.0, weight});
    result.loopForceError = largest > 0 && fd.redundantConstraints == 0 ? worst / forceScale : 0;
    return result;
}

TEST(ForwardDynamics, MatchesSimbodyOnRandomModelsWithLoops) {
    std::mt19937 rng(31);
    double worstUdot = 0, worstLoop = 0;
    int redundantModels = 0;
    for (const test::NamedModel& m : test::makeRandomModels(100, false)) {
        const Comparison c = compareWithSimbody(m.model, rng);
        redundantModels += c.redundantConstraints > 0;
        // 1e-9, widened for a nearly redundant loop as its conditioning costs digits (in both solvers).
        const double tolerance = 1e-9 * std::max(1.0, 1e-6 / c.loopConditioning);
        EXPECT_LE(c.udotError, tolerance) << m.name << " loop conditioning " << c.loopConditioning;
        EXPECT_LE(c.loopForceError, tolerance) << m.name << " loop conditioning " << c.loopConditioning;
        worstUdot = std::max(worstUdot, c.udotError);
        worstLoop = std::max(worstLoop, c.loopForceError);
    }
    std::printf("worst relative difference from Simbody over 100 models (%d with redundant loops): udot %.2e, "
                "loop forces %.2e\n", redundantModels, worstUdot, worstLoop);
}

TEST(ForwardDynamics, MatchesSimbodyOnArm26) {
    std::mt19937 rng(32);
    EXPECT_LE(compareWithSimbody(test::loadArm26().model, rng).udotError, 1e-9);
}

}  // namespace
}  // namespace sinew

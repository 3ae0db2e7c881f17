// sinew's core wire geometry against Simbody's: the wire Force elements' lengths, speeds and body forces (core's
// paths on Simbody's body poses), mapped by Simbody's own system Jacobian, must agree with the core's J, J u
// and -J^T f. (Against a polyline from Simbody's station kinematics alone: test_wire_paths.cpp.)
#include <gtest/gtest.h>

#include <random>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/plugin/simbody_model.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

struct CoreEvaluation {
    Eigen::VectorXd lengths, speeds, tensions, tau;
    Eigen::MatrixXd J;
};

CoreEvaluation evaluateCore(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
    Data data(model);
    calcPositionKinematics(model, data, q);
    calcVelocityKinematics(model, data, u);
    calcWirePaths(model, data);
    calcWireSpeeds(model, data);
    CoreEvaluation result;
    result.J.resize(model.getNumWires(), model.getNumU());
    calcWireJacobian(model, data, result.J);
    result.lengths = data.wireLength;
    result.speeds = result.J * u;
    result.tensions.resize(model.getNumWires());
    calcWireTensions(model, data, 0.0, result.tensions);
    result.tau = -result.J.transpose() * result.tensions;
    return result;
}

// Generalized forces Simbody produces from the wire Force elements alone (no gravity): body forces mapped
// through Simbody's own system Jacobian.
Eigen::VectorXd calcSimbodyWireGeneralizedForces(const SimbodyModel& simbody, const SimTK::State& state) {
    const SimTK::SimbodyMatterSubsystem& matter = simbody.getMatter();
    Eigen::VectorXd total = Eigen::VectorXd::Zero(state.getNU());
    for (int w = 0; w < simbody.getModel().getNumWires(); ++w) {
        // calcForceContribution overwrites its outputs, so each wire is mapped and summed on its own.
        SimTK::Vector_<SimTK::SpatialVec> bodyForces;
        SimTK::Vector_<SimTK::Vec3> particleForces;
        SimTK::Vector mobilityForces;
        simbody.getWireForceElement(w).calcForceContribution(state, bodyForces, particleForces, mobilityForces);
        SimTK::Vector tau;
        matter.multiplyBySystemJacobianTranspose(state, bodyForces, tau);
        total += toEigen(tau + mobilityForces);
    }
    return total;
}

// Relative to the reference's largest entry; a reference that is zero to roundoff (a one-link model's wires
// cannot change length) is compared absolutely.
double relativeDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& reference) {
    return (a - reference).lpNorm<Eigen::Infinity>() / std::max(reference.lpNorm<Eigen::Infinity>(), 1e-3);
}

void expectAgreementWithSimbody(const test::NamedModel& m, std::mt19937& rng) {
    const Model& model = m.model;
    SimbodyModelOptions options;
    options.gravity = false;
    const SimbodyModel simbody(model, options);
    int tautWires = 0;
    for (int trial = 0; trial < 3; ++trial) {
        // Poses near the default one keep most wires taut (they are built taut there); the last is anywhere.
        const Eigen::VectorXd q = trial < 2 ? integrateCoordinates(model, model.getDefaultQ(), generateRandomSpeeds(model, rng), 0.3)
                                            : generateRandomCoordinates(model, rng);
        const Eigen::VectorXd u = generateRandomSpeeds(model, rng, 2.0);
        const CoreEvaluation core = evaluateCore(model, q, u);
        const SimTK::State state = simbody.makeState(q, u);
        Eigen::VectorXd lengths(model.getNumWires()), speeds(model.getNumWires()), tensions(model.getNumWires());
        for (int w = 0; w < model.getNumWires(); ++w) {
            lengths[w] = simbody.getWireForce(w).calcLength(state);
            speeds[w] = simbody.getWireForce(w).calcLengtheningSpeed(state);
            tensions[w] = simbody.getWireForce(w).calcTension(state);
        }
        EXPECT_LE(relativeDifference(core.lengths, lengths), 1e-12) << m.name;
        EXPECT_LE(relativeDifference(core.speeds, speeds), 1e-10) << m.name << ": Simbody speed vs J u";
        EXPECT_LE(relativeDifference(core.tensions, tensions), 1e-10) << m.name;
        tautWires += static_cast<int>((core.tensions.array() > 0).count());
        EXPECT_LE(relativeDifference(core.tau, calcSimbodyWireGeneralizedForces(simbody, state)), 1e-10)
            << m.name << ": -J^T f vs Simbody's generalized wire forces";
    }
    EXPECT_GT(tautWires, 0) << m.name << ": no taut wire, the force comparison was empty";
}

// (Wires through virtual links act through VirtualLinkWireForce, checked in test_virtual_links.cpp.)
TEST(SimbodyWireForce, AgreesWithCoreOnRandomModelsWithLoops) {
    std::mt19937 rng(5);
    for (const test::NamedModel& m : test::makeRandomModels(30, false)) expectAgreementWithSimbody(m, rng);
}

TEST(SimbodyWireForce, AgreesWithCoreOnArm26) {
    std::mt19937 rng(6);
    expectAgreementWithSimbody(test::loadArm26(), rng);
}

TEST(SimbodyModel, MobilizedBodyPosesMatchCoreKinematics) {
    std::mt19937 rng(8);
    for (const test::NamedModel& m : test::makeRandomModels(12, true)) {
        const SimbodyModel simbody(m.model);
        const Eigen::VectorXd q = generateRandomCoordinates(m.model, rng);
        const SimTK::State state = simbody.makeState(q, Eigen::VectorXd::Zero(m.model.getNumU()), SimTK::Stage::Position);
        Data data(m.model);
        calcPositionKinematics(m.model, data, q);
        for (int i = 0; i < m.model.getNumLinks(); ++i) {
            if (m.model.getLink(i).isVirtual) continue;  // not a Simbody body: its pose is solved
            const SimTK::Transform& X_GB = simbody.getMobilizedBody(i).getBodyTransform(state);
            const std::size_t b = static_cast<std::size_t>(i);
            for (int r = 0; r < 3; ++r) {
                EXPECT_NEAR(X_GB.p()[r], data.p_GB[b][r], 1e-12) << m.name << " link " << i;
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(X_GB.R()[r][c], data.R_GB[b](r, c), 1e-12) << m.name;
            }
        }
    }
}

}  // namespace
}  // namespace sinew

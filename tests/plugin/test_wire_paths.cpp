// The Simbody plugin's wires run sinew's core path code on Simbody's kinematics (SimbodyWirePaths). Checked
// against what does not share that code: plain polylines against a via-point element computed from Simbody's
// own station kinematics (support/polyline_wire_force.hpp); wires with wraps, conditional and moving points
// against finite differences of their lengths in Simbody (speeds, and generalized forces = -f dL/du along
// random directions); Simbody's udot with these wires against sinew's own engine; and the shared
// evaluation against fresh systems (a state's numbers never depend on the states evaluated before it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <random>

#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/osim_model_converter.hpp"
#include "sinew/plugin/simbody_model.hpp"
#include "support/allocation_counter.hpp"
#include "support/polyline_wire_force.hpp"
#include "support/test_models.hpp"
#include "support/wrap_test_model.hpp"

namespace sinew {
namespace {

// OpenSim's arm26 (../shared, developer data), custom joints: TRIlong over two cylinders and an ellipsoid,
// BIClong over an ellipsoid, the triceps and BRA over the elbow's cylinder. Absent without the shared data.
std::optional<test::NamedModel> importArm26() {
    const std::filesystem::path path = std::filesystem::path(SINEW_SHARED_DIR) / "data/opensim/arm26/arm26.osim";
    if (!std::filesystem::exists(path)) return std::nullopt;
    return test::NamedModel{"arm26.osim", convertOsimModel(readOsimModel(path.string())).model};
}

// The models with path features: the wrap arm (every feature, one wire each) and arm26.osim when present.
std::vector<test::NamedModel> makePathFeatureModels() {
    std::vector<test::NamedModel> models{{"wrap_arm", test::loadWrapArm()}};
    if (std::optional<test::NamedModel> arm26 = importArm26()) models.push_back(std::move(*arm26));
    return models;
}

// A pose with the wires' paths engaged: the wrap arm's shoulder turned and elbow bent; arm26's coordinates
// anywhere in their ranges.
Eigen::VectorXd randomPose(const test::NamedModel& m, std::mt19937& rng) {
    if (m.name == "wrap_arm") return test::randomWrapArmPose(m.model, rng);
    Eigen::VectorXd q = m.model.getDefaultQ();
    for (std::size_t i = 0; i < m.model.getCoordinates().size(); ++i) {
        const Coordinate& c = m.model.getCoordinates()[i];
        q[static_cast<Eigen::Index>(i)] = std::uniform_real_distribution<double>(c.rangeMin, c.rangeMax)(rng);
    }
    return q;
}

// Generalized forces (Simbody's nu) of one force element alone: body forces mapped through Simbody's own
// system Jacobian, plus its mobility forces.
Eigen::VectorXd calcElementGeneralizedForces(const SimbodyModel& simbody, const SimTK::Force& element,
                                             const SimTK::State& state) {
    SimTK::Vector_<SimTK::SpatialVec> bodyForces;
    SimTK::Vector_<SimTK::Vec3> particleForces;
    SimTK::Vector mobilityForces, tau;
    element.calcForceContribution(state, bodyForces, particleForces, mobilityForces);
    simbody.getMatter().multiplyBySystemJacobianTranspose(state, bodyForces, tau);
    return toEigen(tau + mobilityForces);
}

// Relative to the reference's largest entry; a reference that is zero to roundoff is compared absolutely.
double relativeDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& reference) {
    return (a - reference).lpNorm<Eigen::Infinity>() / std::max(reference.lpNorm<Eigen::Infinity>(), 1e-3);
}

void expectPolylinesMatchReference(const test::NamedModel& m, std::mt19937& rng) {
    SimbodyModelOptions options;
    options.gravity = false;
    const SimbodyModel simbody(m.model, options);
    const test::PolylineReferenceSystem reference(m.model, options);
    const int numWires = m.model.getNumWires();
    int tautWires = 0;
    for (int trial = 0; trial < 3; ++trial) {
        // Near the default pose most wires are taut (they are built taut there); the last pose is anywhere.
        const Eigen::VectorXd q =
            trial < 2 ? integrateCoordinates(m.model, m.model.getDefaultQ(), generateRandomSpeeds(m.model, rng), 0.3)
                      : generateRandomCoordinates(m.model, rng);
        const Eigen::VectorXd u = generateRandomSpeeds(m.model, rng, 2.0);
        const SimTK::State state = simbody.makeState(q, u);
        const SimTK::State referenceState = reference.getSimbodyModel().makeState(q, u);
        Eigen::VectorXd lengths(numWires), speeds(numWires), tensions(numWires);
        Eigen::VectorXd referenceLengths(numWires), referenceSpeeds(numWires), referenceTensions(numWires);
        for (int w = 0; w < numWires; ++w) {
            lengths[w] = simbody.getWireForce(w).calcLength(state);
            speeds[w] = simbody.getWireForce(w).calcLengtheningSpeed(state);
            tensions[w] = simbody.getWireForce(w).calcTension(state);
            referenceLengths[w] = reference.getWire(w).calcLength(referenceState);
            referenceSpeeds[w] = reference.getWire(w).calcLengtheningSpeed(referenceState);
            referenceTensions[w] = reference.getWire(w).calcTension(referenceState);
            EXPECT_LE(relativeDifference(calcElementGeneralizedForces(simbody, simbody.getWireForceElement(w), state),
                                         calcElementGeneralizedForces(reference.getSimbodyModel(),
                                                                      reference.getWireForceElement(w), referenceState)),
                      1e-10)
                << m.name << " wire " << w;
        }
        EXPECT_LE(relativeDifference(lengths, referenceLengths), 1e-12) << m.name;
        EXPECT_LE(relativeDifference(speeds, referenceSpeeds), 1e-10) << m.name;
        EXPECT_LE(relativeDifference(tensions, referenceTensions), 1e-10) << m.name;
        tautWires += static_cast<int>((referenceTensions.array() > 0).count());
    }
    EXPECT_GT(tautWires, 0) << m.name << ": no taut wire, the force comparison was empty";
}

TEST(SimbodyWirePaths, PolylinesMatchSimbodysOwnStationKinematics) {
    std::mt19937 rng(11);
    for (const test::NamedModel& m : test::makeRandomModels(30, false)) expectPolylinesMatchReference(m, rng);
    expectPolylinesMatchReference(test::loadArm26(), rng);
}

// Each wire's length along q(t) = q exp(u t) by central differences in Simbody, at two steps: where they
// disagree the path switches within the step (a conditional point, a wrap engaging), and the wire is not
// compared there. Speed must equal dL/dt, and the element's generalized forces dotted with u must equal
// -f dL/dt: the moving points' push on their coordinates and the ellipsoid's gradient included. A wire over
// an ellipsoid has a numerical dL/du (docs/wire-paths.md), good to 1e-6 as core's tests hold it; the others
// are exact.
TEST(SimbodyWirePaths, PathFeaturesMatchFiniteDifferencesOfTheirLength) {
    std::mt19937 rng(12);
    for (const test::NamedModel& m : makePathFeatureModels()) {
        SimbodyModelOptions options;
        options.gravity = false;
        const SimbodyModel simbody(m.model, options);
        auto lengthAt = [&](const Eigen::VectorXd& q, int w) {
            return simbody.getWireForce(w).calcLength(
                simbody.makeState(q, Eigen::VectorXd::Zero(m.model.getNumU()), SimTK::Stage::Position));
        };
        double worst[2] = {0, 0};  // m/s, [exact dL/du, numerical]
        int compared = 0, switching = 0;
        for (int trial = 0; trial < 40; ++trial) {
            const Eigen::VectorXd q = randomPose(m, rng), u = generateRandomSpeeds(m.model, rng, 1.0);
            const SimTK::State state = simbody.makeState(q, u);
            for (int w = 0; w < m.model.getNumWires(); ++w) {
                auto dLdt = [&](double h) {
                    return (lengthAt(integrateCoordinates(m.model, q, u, h), w) -
                            lengthAt(integrateCoordinates(m.model, q, u, -h), w)) / (2 * h);
                };
                const double coarse = dLdt(1e-5), fine = dLdt(1e-6);
                if (std::abs(coarse - fine) > 1e-6 * std::max(1.0, std::abs(fine))) {
                    ++switching;
                    continue;
                }
                ++compared;
                const WireForce& wire = simbody.getWireForce(w);
                const double tension = wire.calcTension(state);
                const double power = calcElementGeneralizedForces(simbody, simbody.getWireForceElement(w), state).dot(u);
                const bool numerical = isLengthDifferentiatedNumerically(m.model, w);
                const double tolerance = numerical ? 1e-6 : 1e-8;
                double& worstOfKind = worst[numerical ? 1 : 0];
                worstOfKind = std::max({worstOfKind, std::abs(wire.calcLengtheningSpeed(state) - fine),
                                        std::abs(power + tension * fine) / std::max(tension, 1.0)});
                EXPECT_NEAR(wire.calcLengtheningSpeed(state), fine, tolerance) << m.name << " " << wire.getName();
                EXPECT_NEAR(power, -tension * fine, tolerance * std::max(tension, 1.0)) << m.name << " " << wire.getName();
            }
        }
        std::printf("%s: %d wire states against dL/dt by central differences (%d skipped at a path switch): speed and "
                    "generalized forces . u / f within %.1e m/s (wires over an ellipsoid: %.1e m/s)\n",
                    m.name.c_str(), compared, switching, worst[0], worst[1]);
        EXPECT_LE(switching, compared / 20) << m.name;
    }
}

// sinew's own engine at (q, u), as its forward simulation evaluates it: core kinematics, paths, tensions,
// link forces and the coordinate forces of moving points and ellipsoid-wrapped wires, then the
// assembly-disassembly forward dynamics.
Eigen::VectorXd calcSinewUdot(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u, double time) {
    Data data(model);
    calcPositionKinematics(model, data, q);
    calcVelocityKinematics(model, data, u);
    calcWirePaths(model, data);
    calcWireSpeeds(model, data);
    Eigen::VectorXd tensions(model.getNumWires());
    calcWireTensions(model, data, time, tensions);
    calcWireLinkForces(model, data, tensions);
    Eigen::VectorXd tau = Eigen::VectorXd::Zero(model.getNumU());
    addWireCoordinateForces(model, data, tensions, tau);
    const AssemblySchedule schedule(model);
    ForwardDynamicsData fd(model, schedule);
    calcForwardDynamics(model, schedule, data, tau, data.F_G, fd);
    return fd.udot;
}

// Simbody's udot at an assembled state near (q, u) (projected onto the loops), against sinew's engine's at
// that state, relative to the problem's acceleration scale: the larger of Simbody's udot and the udot the
// same forces give without the loops (a locked mechanism has udot ~ 0), as tests/plugin/test_forward_dynamics.cpp.
double expectUdotMatchesSinew(const test::NamedModel& m, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                              double tolerance = 1e-9) {
    const SimbodyModel simbody(m.model);
    const SimTK::MultibodySystem& system = simbody.getSystem();
    SimTK::State state = simbody.makeState(q, u, SimTK::Stage::Position);
    if (m.model.getNumLoops() > 0) {
        try {
            system.project(state, 1e-13);
        } catch (const std::exception&) {  // random loops that lock the mechanism: the default pose
            state = simbody.makeState(m.model.getDefaultQ(), u, SimTK::Stage::Position);
        }
        system.realize(state, SimTK::Stage::Velocity);
        system.projectU(state, 1e-13);
    }
    system.realize(state, SimTK::Stage::Acceleration);
    const Eigen::VectorXd simbodyUdot = toEigen(state.getUDot());
    SimTK::Vector udotFree;
    SimTK::Vector_<SimTK::SpatialVec> bodyAccelerations;
    simbody.getMatter().calcAccelerationIgnoringConstraints(
        state, system.getMobilityForces(state, SimTK::Stage::Dynamics),
        system.getRigidBodyForces(state, SimTK::Stage::Dynamics), udotFree, bodyAccelerations);
    const double scale =
        std::max({simbodyUdot.lpNorm<Eigen::Infinity>(), toEigen(udotFree).lpNorm<Eigen::Infinity>(), 1e-300});
    const Eigen::VectorXd sinewUdot =
        calcSinewUdot(m.model, toEigen(state.getQ()), toEigen(state.getU()), state.getTime());
    const double difference = (sinewUdot - simbodyUdot).lpNorm<Eigen::Infinity>() / scale;
    EXPECT_LE(difference, tolerance) << m.name;
    return difference;
}

TEST(SimbodyWirePaths, UdotMatchesSinewsEngineOnRandomModels) {
    std::mt19937 rng(13);
    double worst = 0;
    for (const test::NamedModel& m : test::makeRandomModels(30, false))
        worst = std::max(worst, expectUdotMatchesSinew(m, integrateCoordinates(m.model, m.model.getDefaultQ(),
                                                                              generateRandomSpeeds(m.model, rng), 0.2),
                                                       generateRandomSpeeds(m.model, rng, 2.0)));
    std::printf("udot, Simbody with the plugin's wires vs sinew's engine, 30 random models: worst relative "
                "difference %.2e\n", worst);
}

// A wire over an ellipsoid has dL/du by central differences with a step of 1e-6 (docs/wire-paths.md),
// whose roundoff (about 1.4e-11 m/rad, an ulp of its length over the step) the two engines' kinematics
// draw differently: with it, udot agrees to that, 1e-8 of the acceleration scale, and to 1e-9 without.
Model removeWire(const char* yaml, const std::string& wire) {
    std::string text = yaml;
    const std::size_t start = text.find("  - name: " + wire + "\n");
    const std::size_t end = text.find("  - name: ", start + 1);
    text.erase(start, end == std::string::npos ? std::string::npos : end - start);
    return readModelText(text, "without_" + wire + ".yaml");
}

TEST(SimbodyWirePaths, UdotMatchesSinewsEngineWithPathFeatures) {
    std::mt19937 rng(14);
    const test::NamedModel arms[] = {{"wrap_arm without its ellipsoid", removeWire(test::kWrapArmYaml, "over_ellipsoid")},
                                     {"wrap_arm", test::loadWrapArm()}};
    for (const test::NamedModel& m : arms) {
        const double tolerance = m.name == "wrap_arm" ? 1e-8 : 1e-9;
        double worst = 0;
        for (int trial = 0; trial < 30; ++trial)
            worst = std::max(worst, expectUdotMatchesSinew(m, test::randomWrapArmPose(m.model, rng),
                                                           generateRandomSpeeds(m.model, rng, 2.0), tolerance));
        std::printf("udot, Simbody with the plugin's wires vs sinew's engine, %s at 30 states: worst relative "
                    "difference %.2e\n", m.name.c_str(), worst);
    }
}

// arm26's custom joints are outside sinew's forward dynamics: there sinew's inverse dynamics at Simbody's
// udot must give back the wires' generalized forces (calcWireGeneralizedForces), relative to the larger of
// them and the gravity torques (the scale of both sides).
TEST(SimbodyWirePaths, Arm26UdotGivesBackItsWireForcesInSinewsInverseDynamics) {
    const std::optional<test::NamedModel> arm26 = importArm26();
    if (!arm26) GTEST_SKIP() << "../shared/data/opensim/arm26 is absent";
    const Model& model = arm26->model;
    const SimbodyModel simbody(model);
    std::mt19937 rng(17);
    Data data(model);
    Eigen::VectorXd tensions(model.getNumWires()), wireTau(model.getNumU()), tau(model.getNumU()),
        gravityTau(model.getNumU());
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    double worst = 0;
    for (int trial = 0; trial < 30; ++trial) {
        const Eigen::VectorXd q = randomPose(*arm26, rng), u = generateRandomSpeeds(model, rng, 2.0);
        SimTK::State state = simbody.makeState(q, u, SimTK::Stage::Acceleration);
        const Eigen::VectorXd udot = toEigen(state.getUDot());
        calcPositionKinematics(model, data, q);
        calcVelocityKinematics(model, data, u);
        calcWirePaths(model, data);
        calcWireSpeeds(model, data);
        calcWireTensions(model, data, 0.0, tensions);
        calcWireGeneralizedForces(model, data, tensions, wireTau);
        calcInverseDynamics(model, data, q, u, udot, noLoads, tau);
        calcInverseDynamics(model, data, q, Eigen::VectorXd::Zero(model.getNumU()),
                            Eigen::VectorXd::Zero(model.getNumU()), noLoads, gravityTau);
        const double scale = std::max(wireTau.lpNorm<Eigen::Infinity>(), gravityTau.lpNorm<Eigen::Infinity>());
        const double difference = (tau - wireTau).lpNorm<Eigen::Infinity>() / scale;
        EXPECT_LE(difference, 1e-8) << "trial " << trial;
        worst = std::max(worst, difference);
    }
    std::printf("arm26.osim: sinew's inverse dynamics at Simbody's udot vs the wires' generalized forces, 30 states: "
                "worst relative difference %.2e\n", worst);
}

// One system evaluates states in turn, state copies and states changed in place; each state's lengths,
// tensions and forces must be those a fresh system computes for it alone, to the last bit.
TEST(SimbodyWirePaths, AStatesNumbersDoNotDependOnTheStatesBefore) {
    const Model model = test::loadWrapArm();
    std::mt19937 rng(15);
    // (A copy of a realized State must be realized again in Simbody 3.7: its copied position cache is out
    // of date with respect to q. So the states are made in place, and the copy below is re-realized.)
    std::vector<SimTK::State> states;
    states.reserve(3);
    std::vector<Eigen::VectorXd> qs, us;
    const SimbodyModel shared(model);
    for (int i = 0; i < 3; ++i) {
        qs.push_back(test::randomWrapArmPose(model, rng));
        us.push_back(generateRandomSpeeds(model, rng, 2.0));
        states.push_back(shared.makeState(qs.back(), us.back()));
    }
    auto expectFresh = [&](const SimTK::State& state, const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
        const SimbodyModel fresh(model);
        const SimTK::State freshState = fresh.makeState(q, u);
        EXPECT_EQ(shared.calcWireTensions(state), fresh.calcWireTensions(freshState));
        for (int w = 0; w < model.getNumWires(); ++w) {
            EXPECT_EQ(shared.getWireForce(w).calcLength(state), fresh.getWireForce(w).calcLength(freshState));
            EXPECT_EQ(shared.getWireForce(w).calcLengtheningSpeed(state),
                      fresh.getWireForce(w).calcLengtheningSpeed(freshState));
            EXPECT_EQ(calcElementGeneralizedForces(shared, shared.getWireForceElement(w), state),
                      calcElementGeneralizedForces(fresh, fresh.getWireForceElement(w), freshState));
        }
    };
    for (int i : {0, 1, 0, 2, 2, 1}) expectFresh(states[static_cast<std::size_t>(i)], qs[static_cast<std::size_t>(i)],
                                                 us[static_cast<std::size_t>(i)]);
    // A copy, realized again, is evaluated again, to the same numbers.
    SimTK::State copy = states[0];
    copy.invalidateAllCacheAtOrAbove(SimTK::Stage::Position);
    shared.getSystem().realize(copy, SimTK::Stage::Velocity);
    expectFresh(copy, qs[0], us[0]);
    // Changed in place: Simbody invalidates the state's cache entries.
    states[1].updQ() = toSimTK(qs[2]);
    shared.getSystem().realize(states[1], SimTK::Stage::Velocity);
    expectFresh(states[1], qs[2], us[1]);
    states[1].updU() = toSimTK(us[0]);
    shared.getSystem().realize(states[1], SimTK::Stage::Velocity);
    expectFresh(states[1], qs[2], us[0]);
}

// The house rule, for the plugin's part of a force evaluation: the shared evaluation at a new state and
// every wire's force allocate nothing.
TEST(SimbodyWirePaths, EvaluationAllocatesNothing) {
    if (!test::isCountingAllocations()) GTEST_SKIP() << "allocations are not counted under AddressSanitizer";
    std::mt19937 rng(16);
    const test::NamedModel models[] = {{"wrap_arm", test::loadWrapArm()}, test::makeRandomModels(3, false)[2]};
    for (const test::NamedModel& m : models) {
        const SimbodyModel simbody(m.model);
        SimTK::State state = simbody.makeState(m.model.getDefaultQ(), Eigen::VectorXd::Zero(m.model.getNumU()));
        SimTK::Vector_<SimTK::SpatialVec> bodyForces(simbody.getMatter().getNumBodies(),
                                                    SimTK::SpatialVec(SimTK::Vec3(0)));
        SimTK::Vector_<SimTK::Vec3> particleForces;
        SimTK::Vector mobilityForces(state.getNU(), 0.0);
        for (int trial = 0; trial < 3; ++trial) {
            state.updQ() = toSimTK(m.name == "wrap_arm" ? test::randomWrapArmPose(m.model, rng)
                                                        : generateRandomCoordinates(m.model, rng));
            state.updU() = toSimTK(generateRandomSpeeds(m.model, rng));
            simbody.getSystem().realize(state, SimTK::Stage::Velocity);
            const long long before = test::getAllocationCount();
            simbody.getWirePaths()->realizeTensions(state);
            for (int w = 0; w < m.model.getNumWires(); ++w)
                simbody.getWireForce(w).calcForce(state, bodyForces, particleForces, mobilityForces);
            EXPECT_EQ(test::getAllocationCount() - before, 0) << m.name;
        }
    }
}

}  // namespace
}  // namespace sinew

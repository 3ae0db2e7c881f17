// The Millard 2012 muscle law and its quintic Bézier curves, against what defines them independently of the
// code: the knots OpenSim's curve factory places (value and slope there), central differences of the value,
// Simpson's rule for the integral, the fibre geometry of a fixed-width pennation model by hand, and the
// parameter refusals OpenSim's factory makes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sinew/core/error.hpp"
#include "sinew/core/force_law_registry.hpp"
#include "sinew/core/millard_muscle.hpp"

namespace sinew {
namespace {

MillardMuscleParameters makeParameters() {
    MillardMuscleParameters p;
    p.maxIsometricForce = 800;
    p.optimalFiberLength = 0.08;
    p.tendonSlackLength = 0.25;
    p.pennationAngleAtOptimal = 0.3;
    p.maxContractionVelocity = 10;
    return p;
}

double integrateBySimpson(const SmoothSegmentedCurve& curve, double a, double b) {
    const int n = 20000;
    const double h = (b - a) / n;
    double sum = curve.calcValue(a) + curve.calcValue(b);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * curve.calcValue(a + i * h);
    return sum * h / 3;
}

// Value and slope at the knots the factory defines (SmoothSegmentedFunctionFactory, OpenSim's defaults).
TEST(MillardMuscle, CurvesPassThroughOpenSimsKnotsWithTheirSlopes) {
    const MillardMuscle muscle(makeParameters());
    const SmoothSegmentedCurve& fal = muscle.getActiveForceLengthCurve();
    const SmoothSegmentedCurve& fv = muscle.getForceVelocityCurve();
    const SmoothSegmentedCurve& fpe = muscle.getPassiveForceLengthCurve();
    const double lMin = 0.47 - 0.0259;
    EXPECT_NEAR(fal.calcValue(lMin), 0.1, 1e-14);
    EXPECT_NEAR(fal.calcValue(1.0), 1.0, 1e-14);
    EXPECT_NEAR(fal.calcSlope(1.0), 0.0, 1e-12);
    EXPECT_NEAR(fal.calcValue(1.8123), 0.1, 1e-14);
    EXPECT_NEAR(fal.calcValue(0.2), 0.1, 1e-14);  // beyond the ends: the minimum, flat
    EXPECT_NEAR(fal.calcValue(2.5), 0.1, 1e-14);
    // The shallow ascent's knot: x = 0.73 + 0.5 (0.95 - 0.73), y = 1 - 0.5 * 0.8616 * (0.95 - 0.73).
    EXPECT_NEAR(fal.calcValue(0.84), 1 - 0.5 * 0.8616 * 0.22, 1e-12);
    EXPECT_NEAR(fal.calcSlope(0.84), 0.8616, 1e-10);

    EXPECT_NEAR(fv.calcValue(-1), 0, 1e-14);
    EXPECT_NEAR(fv.calcValue(-0.9), 0.5 * 0.25 * 0.1, 1e-12);
    EXPECT_NEAR(fv.calcSlope(-0.9), 0.25, 1e-10);
    EXPECT_NEAR(fv.calcValue(0), 1, 1e-12);
    EXPECT_NEAR(fv.calcSlope(0), 5, 1e-9);
    EXPECT_NEAR(fv.calcValue(0.9), 1.4 - 0.5 * 0.15 * 0.1, 1e-12);
    EXPECT_NEAR(fv.calcValue(1), 1.4, 1e-14);
    EXPECT_NEAR(fv.calcValue(-3), 0, 1e-14);
    EXPECT_NEAR(fv.calcValue(4), 1.4, 1e-14);

    EXPECT_NEAR(fpe.calcValue(1.0), 0, 1e-14);
    EXPECT_NEAR(fpe.calcValue(0.6), 0, 1e-14);
    EXPECT_NEAR(fpe.calcValue(1.7), 1, 1e-14);
    EXPECT_NEAR(fpe.calcSlope(1.7), 2 / 0.7, 1e-9);
    EXPECT_NEAR(fpe.calcValue(1.8), 1 + 0.1 * 2 / 0.7, 1e-12);  // linear beyond one max isometric force
    // The toe's knot: x = 1 + min(0.1 / k_iso, 0.07), y = k_low * half of that.
    const double toe = std::min(0.1 * 0.7 / 2, 0.07);
    EXPECT_NEAR(fpe.calcValue(1 + toe), 0.2 * 0.5 * toe, 1e-12);
    EXPECT_NEAR(fpe.calcSlope(1 + toe), 0.2, 1e-9);
}

TEST(MillardMuscle, CurvesAreSmoothAndTheirSlopesAndIntegralsAgreeWithNumerics) {
    const MillardMuscle muscle(makeParameters());
    for (const SmoothSegmentedCurve* curve : {&muscle.getActiveForceLengthCurve(), &muscle.getForceVelocityCurve(),
                                              &muscle.getPassiveForceLengthCurve()}) {
        const double a = curve->getFirstX() - 0.2, b = curve->getLastX() + 0.2;
        double worstSlope = 0, previous = curve->calcValue(a);
        for (int i = 1; i <= 4000; ++i) {
            const double x = a + (b - a) * i / 4000.0, h = 1e-6;
            const double fd = (curve->calcValue(x + h) - curve->calcValue(x - h)) / (2 * h);
            worstSlope = std::max(worstSlope, std::fabs(fd - curve->calcSlope(x)));
            // No jump anywhere: a step of 1/4000 of the range moves the value by at most slope × step.
            const double value = curve->calcValue(x);
            EXPECT_LE(std::fabs(value - previous), 6.0 * (b - a) / 4000.0) << curve->getName() << " x=" << x;
            previous = value;
        }
        EXPECT_LT(worstSlope, 1e-7) << curve->getName();
        for (double x : {a, curve->getFirstX() + 0.01, 0.5 * (curve->getFirstX() + curve->getLastX()), b}) {
            const double simpson = integrateBySimpson(*curve, curve->getFirstX(), x);
            EXPECT_NEAR(curve->calcIntegral(x), simpson, 1e-9) << curve->getName() << " x=" << x;
        }
    }
    // The force-velocity and passive curves never fall.
    for (double x = -1.5; x < 1.5; x += 1e-3)
        EXPECT_GE(muscle.getForceVelocityCurve().calcSlope(x), -1e-12) << x;
    for (double x = 0.5; x < 2.0; x += 1e-3)
        EXPECT_GE(muscle.getPassiveForceLengthCurve().calcSlope(x), -1e-12) << x;
}

TEST(MillardMuscle, TensionIsTheFibreForceAlongTheTendonAndEnergyIsThePassiveWork) {
    MillardMuscleParameters p = makeParameters();
    p.activation = 0.6;
    const MillardMuscle muscle(p);
    const double height = p.optimalFiberLength * std::sin(p.pennationAngleAtOptimal);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> length(0.28, 0.45), speed(-1.5, 1.5);
    for (int i = 0; i < 200; ++i) {
        const double l = length(rng), v = speed(rng);
        // Fixed width by hand: the fibre is the hypotenuse over the length along the tendon.
        const double along = l - p.tendonSlackLength, fiber = std::hypot(height, along), cosine = along / fiber;
        const double lN = fiber / p.optimalFiberLength, vN = v * cosine / (p.optimalFiberLength * 10);
        const double fal = muscle.getActiveForceLengthCurve().calcValue(lN);
        const double fv = muscle.getForceVelocityCurve().calcValue(vN);
        const double fpe = muscle.getPassiveForceLengthCurve().calcValue(lN);
        const double expected = std::max(0.0, 800 * (0.6 * fal * fv + fpe + 0.1 * vN) * cosine);
        ASSERT_NEAR(muscle.calcTension({l, v, 0}), expected, 1e-9 * 800) << "l=" << l << " v=" << v;
        ASSERT_NEAR(muscle.calcActiveForceMultiplier({l, v, 0}), fal * fv * cosine, 1e-12);
    }
    // The passive tension (no activation, no damping) is the energy's derivative.
    p.activation = 0;
    p.fiberDamping = 0;
    const MillardMuscle passive(p);
    for (double l : {0.30, 0.33, 0.36, 0.4, 0.45}) {
        const double h = 1e-6;
        const double dEdl = (passive.calcPotentialEnergy(l + h) - passive.calcPotentialEnergy(l - h)) / (2 * h);
        EXPECT_NEAR(dEdl, passive.calcTension({l, 0, 0}), 1e-6 * (1 + passive.calcTension({l, 0, 0}))) << l;
    }
    EXPECT_GT(passive.calcTension({0.42, 0, 0}), 0);
}

TEST(MillardMuscle, AFibreAtItsMinimumLengthCarriesNoActiveForce) {
    const MillardMuscle muscle(makeParameters());
    // Minimum: the active curve's left end (0.4441 l_opt) or the fibre at the maximum pennation acos(0.1).
    const double height = 0.08 * std::sin(0.3);
    EXPECT_NEAR(muscle.getMinimumFiberLength(), std::max(0.4441 * 0.08, height / std::sin(std::acos(0.1))), 1e-15);
    const WireState tooShort{0.25 + 0.2 * 0.08, -0.3, 0};
    const MuscleFiberState fiber = muscle.calcFiber(tooShort.length, tooShort.speed, 1);
    EXPECT_TRUE(fiber.atMinimumLength);
    EXPECT_DOUBLE_EQ(fiber.normalizedLength * 0.08, muscle.getMinimumFiberLength());
    EXPECT_EQ(fiber.normalizedVelocity, 0);  // a clamped fibre does not shorten
    EXPECT_EQ(muscle.calcActiveForceMultiplier(tooShort), 0);
}

TEST(MillardMuscle, RefusesWhatOpenSimsCurveFactoryRefuses) {
    auto expectError = [](std::map<std::string, std::vector<double>> extra, const std::string& text) {
        std::map<std::string, std::vector<double>> values{
            {"max_isometric_force", {500}}, {"optimal_fiber_length", {0.1}}, {"tendon_slack_length", {0.2}}};
        for (auto& [name, value] : extra) values[name] = value;
        try {
            ForceLawRegistry::global().create("millard2012_muscle", ForceLawParameters(values));
            ADD_FAILURE() << "no error; expected one mentioning '" << text << "'";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
        }
    };
    expectError({{"max_eccentric_velocity_force_multiplier", {0.9}}}, "max_eccentric_velocity_force_multiplier");
    expectError({{"isometric_slope", {0.5}}}, "isometric_slope");
    expectError({{"transition_norm_fiber_length", {1.2}}}, "transition_norm_fiber_length");
    expectError({{"shallow_ascending_slope", {5}}}, "shallow_ascending_slope");
    expectError({{"stiffness_at_low_force", {0.3}}}, "all together");
    expectError({{"strain_at_one_norm_force", {-0.1}}}, "strain_at_one_norm_force");
    expectError({{"max_isometric_force", {-1}}}, "max_isometric_force");
    expectError({{"maximum_pennation_angle", {2}}}, "maximum_pennation_angle");
    // A complete passive triple is taken as given.
    const auto law = ForceLawRegistry::global().create(
        "millard2012_muscle",
        ForceLawParameters({{"max_isometric_force", {500}}, {"optimal_fiber_length", {0.1}}, {"tendon_slack_length", {0.2}},
                            {"stiffness_at_low_force", {0.3}}, {"stiffness_at_one_norm_force", {4}}, {"curviness", {0.5}}}));
    const auto& muscle = dynamic_cast<const MillardMuscle&>(*law);
    EXPECT_NEAR(muscle.getPassiveForceLengthCurve().calcSlope(1.7), 4, 1e-9);
}

}  // namespace
}  // namespace sinew

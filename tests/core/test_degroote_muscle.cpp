// The DeGrooteFregly2016 muscle law against its definition (De Groote et al. 2016 as OpenSim codes it): the
// curves' anchor points (force-velocity through (-1, 0) and (0, 1), passive zero at 0.2 and one at 1 + e0,
// active peak 1 at the optimal length), the tension by hand on a fixed-width pennated fibre, the energy's
// derivative against the passive tension, and the refused parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sinew/core/degroote_muscle.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/force_law_registry.hpp"

namespace sinew {
namespace {

DeGrooteMuscleParameters makeParameters() {
    DeGrooteMuscleParameters p;
    p.maxIsometricForce = 900;
    p.optimalFiberLength = 0.09;
    p.tendonSlackLength = 0.3;
    p.pennationAngleAtOptimal = 0.25;
    p.activation = 0.4;
    p.fiberDamping = 0.05;
    return p;
}

TEST(DeGrooteMuscle, CurvesPassThroughTheirAnchors) {
    const DeGrooteMuscle muscle(makeParameters());
    EXPECT_NEAR(DeGrooteMuscle::calcForceVelocity(-1), 0, 1e-12);
    EXPECT_NEAR(DeGrooteMuscle::calcForceVelocity(0), 1, 1e-12);
    EXPECT_NEAR(muscle.calcPassiveForce(0.2), 0, 1e-15);
    EXPECT_NEAR(muscle.calcPassiveForce(1.6), 1, 1e-14);
    // The active curve peaks at 1 near the optimal length (OpenSim's modified b11).
    double peak = 0, where = 0;
    for (double l = 0.5; l < 1.5; l += 1e-4)
        if (muscle.calcActiveForceLength(l) > peak) peak = muscle.calcActiveForceLength(l), where = l;
    EXPECT_NEAR(peak, 1, 2e-3);
    EXPECT_NEAR(where, 1, 2e-2);
    // A width scale s stretches the curve about 1: f_s(l) = f(1 + (l - 1) / s).
    DeGrooteMuscleParameters wide = makeParameters();
    wide.activeForceWidthScale = 1.5;
    const DeGrooteMuscle scaled(wide);
    for (double l : {0.5, 0.8, 1.0, 1.3})
        EXPECT_NEAR(scaled.calcActiveForceLength(l), muscle.calcActiveForceLength(1 + (l - 1) / 1.5), 1e-15);
    for (double v = -1; v < 1; v += 0.01)
        EXPECT_GT(DeGrooteMuscle::calcForceVelocity(v + 0.01), DeGrooteMuscle::calcForceVelocity(v)) << v;
}

TEST(DeGrooteMuscle, TensionIsTheFibreForceAlongTheTendonAndEnergyIsThePassiveWork) {
    const DeGrooteMuscleParameters p = makeParameters();
    const DeGrooteMuscle muscle(p);
    const double height = 0.09 * std::sin(0.25);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> length(0.34, 0.46), speed(-0.8, 0.8);
    for (int i = 0; i < 100; ++i) {
        const double l = length(rng), v = speed(rng);
        const double along = l - 0.3, fiber = std::hypot(height, along), cosine = along / fiber;
        const double lN = fiber / 0.09, vN = v * cosine / (10 * 0.09);
        const double fiberForce = 0.4 * muscle.calcActiveForceLength(lN) * DeGrooteMuscle::calcForceVelocity(vN) +
                                  muscle.calcPassiveForce(lN) + 0.05 * vN;
        EXPECT_NEAR(muscle.calcTension({l, v, 0}), std::max(0.0, 900 * fiberForce * cosine), 1e-9);
        EXPECT_NEAR(muscle.calcActiveForceMultiplier({l, v, 0}),
                    muscle.calcActiveForceLength(lN) * DeGrooteMuscle::calcForceVelocity(vN) * cosine, 1e-14);
    }
    DeGrooteMuscleParameters passive = p;
    passive.activation = 0;
    passive.fiberDamping = 0;
    const DeGrooteMuscle spring(passive);
    for (double l : {0.36, 0.40, 0.44, 0.5}) {
        const double h = 1e-6;
        const double dEdl = (spring.calcPotentialEnergy(l + h) - spring.calcPotentialEnergy(l - h)) / (2 * h);
        EXPECT_NEAR(dEdl, spring.calcTension({l, 0, 0}), 1e-6 * (1 + spring.calcTension({l, 0, 0}))) << l;
    }
}

TEST(DeGrooteMuscle, RefusesOutOfRangeParameters) {
    const auto expectError = [](const std::string& name, double value) {
        std::map<std::string, std::vector<double>> values{
            {"max_isometric_force", {500}}, {"optimal_fiber_length", {0.1}}, {"tendon_slack_length", {0.2}}};
        values[name] = {value};
        try {
            ForceLawRegistry::global().create("degroote_fregly2016_muscle", ForceLawParameters(values));
            ADD_FAILURE() << name << " = " << value << " accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    };
    expectError("active_force_width_scale", 0.5);
    expectError("fiber_damping", -1);
    expectError("passive_fiber_strain_at_one_norm_force", 0);
    expectError("ignore_passive_fiber_force", 2);
    expectError("optimal_fiber_length", 0);
}

}  // namespace
}  // namespace sinew

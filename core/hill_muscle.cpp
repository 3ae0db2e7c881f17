#include "sinew/core/hill_muscle.hpp"

#include <cmath>
#include <string>

#include "sinew/core/error.hpp"

namespace sinew {

void readMuscleParameters(const ForceLawParameters& parameters, MuscleParameters& muscle) {
    muscle.maxIsometricForce = parameters.getScalar("max_isometric_force");
    muscle.optimalFiberLength = parameters.getScalar("optimal_fiber_length");
    muscle.tendonSlackLength = parameters.getScalar("tendon_slack_length");
    muscle.pennationAngleAtOptimal = parameters.getScalarOr("pennation_angle_at_optimal", muscle.pennationAngleAtOptimal);
    muscle.maxContractionVelocity = parameters.getScalarOr("max_contraction_velocity", muscle.maxContractionVelocity);
    muscle.activation = parameters.getScalarOr("activation", muscle.activation);
}

void checkMuscleParameters(const char* law, const MuscleParameters& muscle) {
    const auto fail = [&](const std::string& what) { throw Error(std::string(law) + ": parameter " + what); };
    const auto requirePositive = [&](const char* name, double value) {
        if (!std::isfinite(value) || !(value > 0))
            fail(std::string("'") + name + "' must be a finite number > 0, got " + std::to_string(value));
    };
    requirePositive("max_isometric_force", muscle.maxIsometricForce);
    requirePositive("optimal_fiber_length", muscle.optimalFiberLength);
    requirePositive("max_contraction_velocity", muscle.maxContractionVelocity);
    if (!std::isfinite(muscle.tendonSlackLength) || muscle.tendonSlackLength < 0)
        fail("'tendon_slack_length' must be a finite number >= 0");
    if (!(muscle.pennationAngleAtOptimal >= 0 && muscle.pennationAngleAtOptimal < M_PI / 2))
        fail("'pennation_angle_at_optimal' must lie in [0, pi/2) rad");
    if (!(muscle.activation >= 0 && muscle.activation <= 1)) fail("'activation' must lie in [0, 1]");
}

MuscleFiberState calcFixedWidthFiber(const MuscleParameters& muscle, double length, double speed) {
    MuscleFiberState fiber;
    const double height = muscle.optimalFiberLength * std::sin(muscle.pennationAngleAtOptimal);
    const double alongTendon = std::fmax(length - muscle.tendonSlackLength, 1e-9 * muscle.optimalFiberLength);
    const double fiberLength = std::hypot(height, alongTendon);
    fiber.cosPennation = alongTendon / fiberLength;
    fiber.normalizedLength = fiberLength / muscle.optimalFiberLength;
    fiber.normalizedVelocity = speed * fiber.cosPennation / (muscle.maxContractionVelocity * muscle.optimalFiberLength);
    return fiber;
}

double HillMuscle::doCalcTension(const WireState& state) const {
    const MuscleFiberState fiber = calcFiber(state.length, state.speed, muscle_.activation);
    const double active = muscle_.activation * fiber.activeForceLength * fiber.forceVelocity;
    return muscle_.maxIsometricForce * (active + fiber.passiveForce + fiberDamping_ * fiber.normalizedVelocity) *
           fiber.cosPennation;
}

double HillMuscle::calcActiveForceMultiplier(const WireState& state) const {
    const MuscleFiberState fiber = calcFiber(state.length, state.speed, 1.0);
    return fiber.atMinimumLength ? 0 : fiber.activeForceLength * fiber.forceVelocity * fiber.cosPennation;
}

}  // namespace sinew

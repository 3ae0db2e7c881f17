#include "sinew/core/degroote_muscle.hpp"

#include <cmath>
#include <string>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// DeGrooteFregly2016Muscle.h's constants (b11 as OpenSim modified it so that the curve peaks at 1).
constexpr double kActive[3][4] = {{0.8150671134243542, 1.055033428970575, 0.162384573599574, 0.063303448465465},
                                  {0.433004984392647, 0.716775413397760, -0.029947116970696, 0.200356847296188},
                                  {0.1, 1.0, 0.353553390593274, 0.0}};
constexpr double kPassiveShape = 4.0;
constexpr double kMinNormFiberLength = 0.2;
constexpr double kD1 = -0.3211346127989808, kD2 = -8.149, kD3 = -0.374, kD4 = 0.8825327733249912;

}  // namespace

DeGrooteMuscle::DeGrooteMuscle(const DeGrooteMuscleParameters& parameters)
    : HillMuscle(parameters, parameters.fiberDamping), parameters_(parameters) {
    checkMuscleParameters("degroote_fregly2016_muscle", parameters);
    const auto fail = [](const std::string& what) { throw Error("degroote_fregly2016_muscle: parameter " + what); };
    if (!(parameters.activeForceWidthScale >= 1) || !std::isfinite(parameters.activeForceWidthScale))
        fail("'active_force_width_scale' must be finite and >= 1");
    if (!(parameters.fiberDamping >= 0) || !std::isfinite(parameters.fiberDamping))
        fail("'fiber_damping' must be finite and >= 0");
    if (!(parameters.passiveFiberStrainAtOneNormForce > 0) || !std::isfinite(parameters.passiveFiberStrainAtOneNormForce))
        fail("'passive_fiber_strain_at_one_norm_force' must be finite and > 0");
}

std::shared_ptr<const ForceLaw> DeGrooteMuscle::create(const ForceLawParameters& parameters) {
    DeGrooteMuscleParameters p;
    readMuscleParameters(parameters, p);
    p.activeForceWidthScale = parameters.getScalarOr("active_force_width_scale", p.activeForceWidthScale);
    p.fiberDamping = parameters.getScalarOr("fiber_damping", p.fiberDamping);
    p.passiveFiberStrainAtOneNormForce =
        parameters.getScalarOr("passive_fiber_strain_at_one_norm_force", p.passiveFiberStrainAtOneNormForce);
    const double ignore = parameters.getScalarOr("ignore_passive_fiber_force", 0);
    if (ignore != 0 && ignore != 1)
        throw Error("degroote_fregly2016_muscle: parameter 'ignore_passive_fiber_force' must be 0 or 1");
    p.ignorePassiveFiberForce = ignore == 1;
    return std::make_shared<DeGrooteMuscle>(p);
}

double DeGrooteMuscle::calcActiveForceLength(double normalizedLength) const {
    const double x = (normalizedLength - 1) / parameters_.activeForceWidthScale + 1;
    double sum = 0;
    for (const auto& b : kActive) {
        const double width = b[2] + b[3] * x;
        sum += b[0] * std::exp(-0.5 * (x - b[1]) * (x - b[1]) / (width * width));
    }
    return sum;
}

double DeGrooteMuscle::calcForceVelocity(double normalizedVelocity) {
    const double v = kD2 * normalizedVelocity + kD3;
    return kD1 * std::log(v + std::sqrt(v * v + 1)) + kD4;
}

// Zero at 0.2 optimal lengths, one at 1 + strain; negative below 0.2 (where a rigid-tendon wire is slack).
double DeGrooteMuscle::calcPassiveForce(double normalizedLength) const {
    if (parameters_.ignorePassiveFiberForce) return 0;
    const double e0 = parameters_.passiveFiberStrainAtOneNormForce;
    const double offset = std::exp(kPassiveShape * (kMinNormFiberLength - 1) / e0);
    return (std::exp(kPassiveShape * (normalizedLength - 1) / e0) - offset) / (std::exp(kPassiveShape) - offset);
}

// The force per activation is along the tendon, as for the other laws (OpenSim's
// DeGrooteFregly2016Muscle::calcInextensibleTendonActiveFiberForce returns it along the fibre,
// docs/force-laws.md).
MuscleFiberState DeGrooteMuscle::calcFiber(double length, double speed, double /*activation*/) const {
    MuscleFiberState fiber = calcFixedWidthFiber(parameters_, length, speed);
    fiber.activeForceLength = calcActiveForceLength(fiber.normalizedLength);
    fiber.forceVelocity = calcForceVelocity(fiber.normalizedVelocity);
    fiber.passiveForce = calcPassiveForce(fiber.normalizedLength);
    return fiber;
}

// The passive curve's closed-form integral from 0.2 optimal lengths (its zero), times F0 l_opt.
double DeGrooteMuscle::doCalcPotentialEnergy(double length) const {
    if (parameters_.ignorePassiveFiberForce) return 0;
    const double lN = calcFiber(length, 0, 0).normalizedLength;
    const double e0 = parameters_.passiveFiberStrainAtOneNormForce;
    const double offset = std::exp(kPassiveShape * (kMinNormFiberLength - 1) / e0);
    const double integral = (e0 / kPassiveShape * (std::exp(kPassiveShape * (lN - 1) / e0) - offset) -
                             offset * (lN - kMinNormFiberLength)) /
                            (std::exp(kPassiveShape) - offset);
    return parameters_.maxIsometricForce * parameters_.optimalFiberLength * integral;
}

}  // namespace sinew

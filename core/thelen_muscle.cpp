#include "sinew/core/thelen_muscle.hpp"

#include <cmath>
#include <string>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

void requirePositive(const char* name, double value) {
    if (!std::isfinite(value) || !(value > 0))
        throw Error(std::string("parameter '") + name + "' must be a finite number > 0, got " + std::to_string(value));
}

// Thelen's passive curve, continued linearly beyond one max isometric force (at strain fmaxMuscleStrain)
// so a wire stretched far by a bad pose stays finite; returns the force multiplier and, in `energy`, its
// integral over normalized length from 1.
double calcPassiveForce(const ThelenMuscleParameters& p, double normalizedLength, double& energy) {
    energy = 0;
    const double strain = normalizedLength - 1;
    if (strain <= 0) return 0;
    const double e0 = p.fmaxMuscleStrain, k = p.kShapePassive, denominator = std::expm1(k);
    const double exponentialPart = std::fmin(strain, e0);
    double force = std::expm1(k * exponentialPart / e0) / denominator;
    energy = (e0 / k * std::expm1(k * exponentialPart / e0) - exponentialPart) / denominator;
    if (strain > e0) {
        const double slope = k / e0 * std::exp(k) / denominator, beyond = strain - e0;
        energy += force * beyond + 0.5 * slope * beyond * beyond;
        force += slope * beyond;
    }
    return force;
}

}  // namespace

ThelenMuscle::ThelenMuscle(const ThelenMuscleParameters& parameters) : HillMuscle(parameters, 0), parameters_(parameters) {
    checkMuscleParameters("thelen2003_muscle", parameters);
    requirePositive("fmax_muscle_strain", parameters.fmaxMuscleStrain);
    requirePositive("kshape_active", parameters.kShapeActive);
    requirePositive("kshape_passive", parameters.kShapePassive);
    requirePositive("af", parameters.af);
    if (!(parameters.flen > 1)) throw Error("parameter 'flen' must be > 1");
}

std::shared_ptr<const ForceLaw> ThelenMuscle::create(const ForceLawParameters& parameters) {
    ThelenMuscleParameters p;
    readMuscleParameters(parameters, p);
    p.fmaxMuscleStrain = parameters.getScalarOr("fmax_muscle_strain", p.fmaxMuscleStrain);
    p.kShapeActive = parameters.getScalarOr("kshape_active", p.kShapeActive);
    p.kShapePassive = parameters.getScalarOr("kshape_passive", p.kShapePassive);
    p.af = parameters.getScalarOr("af", p.af);
    p.flen = parameters.getScalarOr("flen", p.flen);
    return std::make_shared<ThelenMuscle>(p);
}

MuscleFiberState ThelenMuscle::calcFiber(double length, double speed, double activation) const {
    const ThelenMuscleParameters& p = parameters_;
    MuscleFiberState fiber = calcFixedWidthFiber(p, length, speed);
    const double stretch = fiber.normalizedLength - 1;
    fiber.activeForceLength = std::exp(-stretch * stretch / p.kShapeActive);
    double energy = 0;
    fiber.passiveForce = calcPassiveForce(p, fiber.normalizedLength, energy);
    // Thelen (2003) eq. 6 solved for the force: the velocity scale is (0.25 + 0.75 a) v_max.
    const double v = fiber.normalizedVelocity / (0.25 + 0.75 * activation);
    if (v <= 0) {
        fiber.forceVelocity = std::fmax(0.0, (1 + v) / (1 - v / p.af));
    } else {
        const double k = (2 + 2 / p.af) / (p.flen - 1);
        fiber.forceVelocity = (1 + v * k * p.flen) / (1 + v * k);
    }
    return fiber;
}

// Along a rigid tendon d(fibre length)/d(length) = cos(pennation), so the passive tension's work is the
// passive fibre force's work along the fibre.
double ThelenMuscle::doCalcPotentialEnergy(double length) const {
    const MuscleFiberState fiber = calcFiber(length, 0, parameters_.activation);
    double energy = 0;
    calcPassiveForce(parameters_, fiber.normalizedLength, energy);
    return parameters_.maxIsometricForce * parameters_.optimalFiberLength * energy;
}

}  // namespace sinew

#include "sinew/core/millard_muscle.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// SimTK::SignificantReal and sqrt(SimTK::Eps): OpenSim's thresholds, kept so the same parameters give the
// same minimum lengths and the same refusals.
constexpr double kSignificantReal = 1.8189894035458565e-14;
constexpr double kRootEps = 1.4901161193847656e-08;

void require(bool condition, const std::string& what) {
    if (!condition) throw Error("millard2012_muscle: " + what);
}

// SmoothSegmentedFunctionFactory::createFiberActiveForceLengthCurve with OpenSim's curviness 1: a rising
// shoulder from the minimum active length, a shallow ascent to the transition length, the plateau at 1,
// and the descending limb to the maximum active length.
SmoothSegmentedCurve makeActiveForceLengthCurve(const MillardMuscleParameters& p) {
    const double x0 = p.minNormActiveFiberLength, x1 = p.transitionNormFiberLength, x2 = 1,
                 x3 = p.maxNormActiveFiberLength, low = p.minimumActiveForce, slope = p.shallowAscendingSlope;
    require(x0 >= 0 && x1 > x0 + kRootEps && x2 > x1 + kRootEps && x3 > x2 + kRootEps,
            "the active force-length curve needs 0 <= min_norm_active_fiber_length < transition_norm_fiber_length "
            "< 1 < max_norm_active_fiber_length");
    require(low >= 0, "the active force-length curve's minimum_value must be >= 0");
    require(slope >= 0 && slope < (1 - low) / (x2 - x1),
            "shallow_ascending_slope must lie in [0, " + std::to_string((1 - low) / (x2 - x1)) + ")");
    const double halfWidth = 0.05 * x2, shoulder = x2 - halfWidth;
    const double y1 = 1 - slope * (shoulder - x1);
    const double rise = 1.25 * y1 / (x1 - x0);
    const double descentStart = x2 + halfWidth, descentSlope = -1 / ((x3 - halfWidth) - descentStart);
    const std::vector<CurveKnot> knots{{x0, low, 0},
                                       {x0 + 0.5 * (x1 - x0), 0.5 * y1, rise},
                                       {x1 + 0.5 * (shoulder - x1), y1 + 0.5 * (1 - y1), slope},
                                       {x2, 1, 0},
                                       {descentStart + 0.5 * (x3 - descentStart), 0.5, descentSlope},
                                       {x3, low, 0}};
    return SmoothSegmentedCurve("active force-length", knots, std::vector<double>(5, 1.0));
}

// createFiberForceVelocityCurve: 0 at the max shortening speed (-1), 1 isometric, the eccentric multiplier
// at the max lengthening speed (+1), each half with its curviness.
SmoothSegmentedCurve makeForceVelocityCurve(const MillardMuscleParameters& p) {
    const double fmax = p.maxEccentricVelocityForceMultiplier;
    require(fmax > 1, "max_eccentric_velocity_force_multiplier must be > 1");
    require(p.concentricSlopeAtVmax >= 0 && p.concentricSlopeAtVmax < 1, "concentric_slope_at_vmax must lie in [0, 1)");
    require(p.concentricSlopeNearVmax > p.concentricSlopeAtVmax && p.concentricSlopeNearVmax <= 1,
            "concentric_slope_near_vmax must lie in (concentric_slope_at_vmax, 1]");
    require(p.isometricSlope > 1, "isometric_slope must be > 1");
    require(p.eccentricSlopeAtVmax >= 0 && p.eccentricSlopeAtVmax < fmax - 1,
            "eccentric_slope_at_vmax must lie in [0, max_eccentric_velocity_force_multiplier - 1)");
    require(p.eccentricSlopeNearVmax >= p.eccentricSlopeAtVmax && p.eccentricSlopeNearVmax < fmax - 1,
            "eccentric_slope_near_vmax must lie in [eccentric_slope_at_vmax, max_eccentric_velocity_force_multiplier - 1)");
    const double nearShortening = 0.05 * (p.concentricSlopeNearVmax + p.concentricSlopeAtVmax);
    const double nearLengthening = fmax - 0.05 * (p.eccentricSlopeNearVmax + p.eccentricSlopeAtVmax);
    const std::vector<CurveKnot> knots{{-1, 0, p.concentricSlopeAtVmax},
                                       {-0.9, nearShortening, p.concentricSlopeNearVmax},
                                       {0, 1, p.isometricSlope},
                                       {0.9, nearLengthening, p.eccentricSlopeNearVmax},
                                       {1, fmax, p.eccentricSlopeAtVmax}};
    return SmoothSegmentedCurve("force-velocity", knots,
                                {p.concentricCurviness, p.concentricCurviness, p.eccentricCurviness, p.eccentricCurviness});
}

// createFiberForceLengthCurve: 0 up to 1 + strain_at_zero_force, a toe of low stiffness, 1 at
// 1 + strain_at_one_norm_force with the stiffness there.
SmoothSegmentedCurve makePassiveForceLengthCurve(const MillardMuscleParameters& p) {
    const double e0 = p.strainAtZeroForce, e1 = p.strainAtOneNormForce;
    const double kLow = p.passiveStiffnessAtLowForce, kIso = p.passiveStiffnessAtOneNormForce;
    require(e1 > e0, "strain_at_one_norm_force must exceed strain_at_zero_force");
    require(kIso > 1 / (e1 - e0), "stiffness_at_one_norm_force must exceed 1 / (strain range) = " +
                                      std::to_string(1 / (e1 - e0)));
    require(kLow > 0 && kLow < 1 / (e1 - e0),
            "stiffness_at_low_force must lie in (0, " + std::to_string(1 / (e1 - e0)) + ")");
    const double xZero = 1 + e0, xIso = 1 + e1;
    const double toe = std::min(0.1 / kIso, 0.1 * (xIso - xZero));
    const double xLow = xZero + toe;
    const std::vector<CurveKnot> knots{{xZero, 0, 0}, {xLow, kLow * 0.5 * toe, kLow}, {xIso, 1, kIso}};
    return SmoothSegmentedCurve("passive force-length", knots, {p.passiveCurviness, p.passiveCurviness});
}

}  // namespace

MillardMuscle::MillardMuscle(const MillardMuscleParameters& parameters)
    : HillMuscle(parameters, parameters.fiberDamping),
      parameters_(parameters),
      activeForceLength_(makeActiveForceLengthCurve(parameters)),
      forceVelocity_(makeForceVelocityCurve(parameters)),
      passiveForceLength_(makePassiveForceLengthCurve(parameters)) {
    const MillardMuscleParameters& p = parameters_;
    checkMuscleParameters("millard2012_muscle", p);
    require(p.maximumPennationAngle >= 0 && p.maximumPennationAngle <= M_PI / 2,
            "parameter 'maximum_pennation_angle' must lie in [0, pi/2] rad");
    require(std::isfinite(p.fiberDamping) && p.fiberDamping >= 0, "parameter 'fiber_damping' must be >= 0");
    height_ = p.optimalFiberLength * std::sin(p.pennationAngleAtOptimal);
    // MuscleFixedWidthPennationModel's shortest fibre (at the maximum pennation), then Millard's bound.
    pennatedMinimumFiberLength_ = p.maximumPennationAngle > kSignificantReal
                                      ? height_ / std::sin(p.maximumPennationAngle)
                                      : 0.01 * p.optimalFiberLength;
    minimumFiberLength_ = std::max(kSignificantReal, std::max(p.minNormActiveFiberLength * p.optimalFiberLength,
                                                              pennatedMinimumFiberLength_));
}

std::shared_ptr<const ForceLaw> MillardMuscle::create(const ForceLawParameters& parameters) {
    MillardMuscleParameters p;
    readMuscleParameters(parameters, p);
    const auto read = [&](const char* name, double& value) { value = parameters.getScalarOr(name, value); };
    read("fiber_damping", p.fiberDamping);
    read("maximum_pennation_angle", p.maximumPennationAngle);
    read("min_norm_active_fiber_length", p.minNormActiveFiberLength);
    read("transition_norm_fiber_length", p.transitionNormFiberLength);
    read("max_norm_active_fiber_length", p.maxNormActiveFiberLength);
    read("shallow_ascending_slope", p.shallowAscendingSlope);
    read("minimum_value", p.minimumActiveForce);
    read("concentric_slope_at_vmax", p.concentricSlopeAtVmax);
    read("concentric_slope_near_vmax", p.concentricSlopeNearVmax);
    read("isometric_slope", p.isometricSlope);
    read("eccentric_slope_at_vmax", p.eccentricSlopeAtVmax);
    read("eccentric_slope_near_vmax", p.eccentricSlopeNearVmax);
    read("max_eccentric_velocity_force_multiplier", p.maxEccentricVelocityForceMultiplier);
    read("concentric_curviness", p.concentricCurviness);
    read("eccentric_curviness", p.eccentricCurviness);
    read("strain_at_zero_force", p.strainAtZeroForce);
    read("strain_at_one_norm_force", p.strainAtOneNormForce);
    // OpenSim's FiberForceLengthCurve: its three shape parameters all given, or all fitted.
    const int given = parameters.has("stiffness_at_low_force") + parameters.has("stiffness_at_one_norm_force") +
                      parameters.has("curviness");
    if (given != 0 && given != 3)
        throw Error("millard2012_muscle: stiffness_at_low_force, stiffness_at_one_norm_force and curviness "
                    "(the passive fibre curve) must be given all together or not at all");
    p.passiveStiffnessAtOneNormForce = 2 / (p.strainAtOneNormForce - p.strainAtZeroForce);
    read("stiffness_at_low_force", p.passiveStiffnessAtLowForce);
    read("stiffness_at_one_norm_force", p.passiveStiffnessAtOneNormForce);
    read("curviness", p.passiveCurviness);
    return std::make_shared<MillardMuscle>(p);
}

// The pennation is the fibre's own in the force per activation too: OpenSim 4.4's static optimization takes it
// at the normalized length (docs/force-laws.md).
MuscleFiberState MillardMuscle::calcFiber(double length, double speed, double /*activation*/) const {
    const MillardMuscleParameters& p = parameters_;
    MuscleFiberState fiber;
    // MuscleFixedWidthPennationModel on a rigid tendon: constant height l_opt sin(alpha_opt), the pennation
    // bounded by the maximum angle; the fibre clamped at the minimum length, where it cannot shorten.
    const double alongTendon = length - p.tendonSlackLength;
    const double fiberLength = alongTendon >= pennatedMinimumFiberLength_ * std::cos(p.maximumPennationAngle)
                                   ? std::hypot(height_, alongTendon)
                                   : pennatedMinimumFiberLength_;
    fiber.atMinimumLength = fiberLength <= minimumFiberLength_;
    const double clamped = std::max(fiberLength, minimumFiberLength_);
    if (p.pennationAngleAtOptimal > 2.220446049250313e-16) {
        const double sinPennation = height_ / clamped;
        fiber.cosPennation = sinPennation < std::sin(p.maximumPennationAngle)
                                 ? std::sqrt(1 - sinPennation * sinPennation)
                                 : std::cos(p.maximumPennationAngle);
    }
    fiber.normalizedLength = clamped / p.optimalFiberLength;
    const double fiberSpeed = speed * fiber.cosPennation;
    const bool blocked = fiberLength < minimumFiberLength_ || (fiber.atMinimumLength && fiberSpeed <= 0);
    fiber.normalizedVelocity = blocked ? 0 : fiberSpeed / (p.optimalFiberLength * p.maxContractionVelocity);
    fiber.activeForceLength = activeForceLength_.calcValue(fiber.normalizedLength);
    fiber.forceVelocity = forceVelocity_.calcValue(fiber.normalizedVelocity);
    fiber.passiveForce = passiveForceLength_.calcValue(fiber.normalizedLength);
    return fiber;
}

// Along a rigid tendon d(fibre length)/d(length) = cos(pennation), so the passive elastic tension's work is
// the passive fibre force's work along the fibre (the clamped fibre's curve is zero: its minimum is below
// the slack length).
double MillardMuscle::doCalcPotentialEnergy(double length) const {
    const MuscleFiberState fiber = calcFiber(length, 0, 0);
    return parameters_.maxIsometricForce * parameters_.optimalFiberLength *
           passiveForceLength_.calcIntegral(fiber.normalizedLength);
}

}  // namespace sinew

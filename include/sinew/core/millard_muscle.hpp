#pragma once
// "millard2012_muscle": OpenSim's Millard2012EquilibriumMuscle on a rigid tendon (its
// ignore_tendon_compliance mode), with its own curves: the active force-length, force-velocity and passive
// fibre force-length curves built from the same parameters, defaults and quintic Bézier corners as OpenSim
// builds them (SmoothSegmentedFunctionFactory), a fixed-width pennation model bounded by the maximum
// pennation angle, and the fibre's damping (docs/force-laws.md, "Imported muscles").
#include <memory>

#include "sinew/core/force_law.hpp"
#include "sinew/core/hill_muscle.hpp"
#include "sinew/core/smooth_segmented_curve.hpp"

namespace sinew {

struct MillardMuscleParameters : MuscleParameters {
    double fiberDamping = 0.1;           // max isometric forces per normalized fibre velocity
    double maximumPennationAngle = 1.4706289056333368;  // rad, acos(0.1)
    // ActiveForceLengthCurve
    double minNormActiveFiberLength = 0.47 - 0.0259;
    double transitionNormFiberLength = 0.73;
    double maxNormActiveFiberLength = 1.8123;
    double shallowAscendingSlope = 0.8616;
    double minimumActiveForce = 0.1;     // the curve's minimum_value
    // ForceVelocityCurve
    double concentricSlopeAtVmax = 0;
    double concentricSlopeNearVmax = 0.25;
    double isometricSlope = 5;
    double eccentricSlopeAtVmax = 0;
    double eccentricSlopeNearVmax = 0.15;
    double maxEccentricVelocityForceMultiplier = 1.4;
    double concentricCurviness = 0.6;
    double eccentricCurviness = 0.9;
    // FiberForceLengthCurve; the last three are given all together or not at all (then 0.2, 2 / (strain
    // range) and 0.75, OpenSim's fit to its reference curve).
    double strainAtZeroForce = 0;
    double strainAtOneNormForce = 0.7;
    double passiveStiffnessAtLowForce = 0.2;
    double passiveStiffnessAtOneNormForce = 2 / 0.7;
    double passiveCurviness = 0.75;
};

class MillardMuscle final : public HillMuscle {
public:
    // Throws sinew::Error naming the parameter OpenSim's curve factory would refuse.
    explicit MillardMuscle(const MillardMuscleParameters& parameters);
    static std::shared_ptr<const ForceLaw> create(const ForceLawParameters& parameters);

    const MillardMuscleParameters& getParameters() const { return parameters_; }
    // The fibre clamped at the minimum fibre length (atMinimumLength there); fv does not depend on activation.
    MuscleFiberState calcFiber(double length, double speed, double activation) const override;
    // The minimum fibre length (m): the active force-length curve's left end or the maximum pennation's.
    double getMinimumFiberLength() const { return minimumFiberLength_; }
    const SmoothSegmentedCurve& getActiveForceLengthCurve() const { return activeForceLength_; }
    const SmoothSegmentedCurve& getForceVelocityCurve() const { return forceVelocity_; }
    const SmoothSegmentedCurve& getPassiveForceLengthCurve() const { return passiveForceLength_; }

protected:
    double doCalcPotentialEnergy(double length) const override;

private:
    MillardMuscleParameters parameters_;
    double height_ = 0;              // the fixed width: l_opt sin(alpha_opt), m
    double pennatedMinimumFiberLength_ = 0;  // m, the pennation model's shortest fibre
    double minimumFiberLength_ = 0;          // m
    SmoothSegmentedCurve activeForceLength_, forceVelocity_, passiveForceLength_;
};

}  // namespace sinew

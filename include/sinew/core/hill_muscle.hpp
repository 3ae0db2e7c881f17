#pragma once
// What the Hill-type muscle laws on a rigid tendon share (docs/force-laws.md, "Imported muscles"): the
// parameters they are given (OpenSim's Muscle properties and a constant activation), which each law's own
// parameters extend, the fibre's state they compute, and the base class that turns that state into the
// wire's tension and its force per unit activation.
#include "sinew/core/force_law.hpp"

namespace sinew {

struct MuscleParameters {
    double maxIsometricForce = 1000;     // N
    double optimalFiberLength = 0.1;     // m
    double tendonSlackLength = 0.2;      // m
    double pennationAngleAtOptimal = 0;  // rad
    double maxContractionVelocity = 10;  // optimal fibre lengths per second
    double activation = 0;               // 0..1, held constant (0: passive)
};

// The fibre at one muscle-tendon length and lengthening speed.
struct MuscleFiberState {
    double normalizedLength = 0;    // fibre length / optimal fibre length
    double normalizedVelocity = 0;  // fibre lengthening speed / (max contraction velocity × optimal length)
    double cosPennation = 1;
    double activeForceLength = 0;   // multipliers of max isometric force
    double forceVelocity = 1;
    double passiveForce = 0;
    // The path is too short for the fibre (Millard's clamp): no force per activation for the distributions.
    bool atMinimumLength = false;
};

// max_isometric_force, optimal_fiber_length, tendon_slack_length (required), pennation_angle_at_optimal,
// max_contraction_velocity, activation (optional) into `muscle`.
void readMuscleParameters(const ForceLawParameters& parameters, MuscleParameters& muscle);
// Throws sinew::Error naming `law` and the parameter out of its range.
void checkMuscleParameters(const char* law, const MuscleParameters& muscle);

// The fibre on a rigid tendon with constant thickness l_opt sin(alpha_opt) (Zajac 1989): its normalized
// length and velocity and cos(pennation) (the curves' values left for the law).
MuscleFiberState calcFixedWidthFiber(const MuscleParameters& muscle, double length, double speed);

// A muscle law: a fibre state per wire state; the tension F0 (a fl fv + fpe + damping v_N) cos(pennation),
// and, for the tension distributions, F0 and fl fv cos(pennation) at full activation (OpenSim's
// calcInextensibleTendonActiveFiberForce(s, 1) / F0).
class HillMuscle : public ForceLaw {
public:
    // The fibre at a muscle-tendon length (m) and lengthening speed (m/s), fv taken at `activation`.
    virtual MuscleFiberState calcFiber(double length, double speed, double activation) const = 0;

    std::optional<double> getMaxIsometricForce() const final { return muscle_.maxIsometricForce; }
    double calcActiveForceMultiplier(const WireState& state) const final;

protected:
    HillMuscle(const MuscleParameters& muscle, double fiberDamping) : muscle_(muscle), fiberDamping_(fiberDamping) {}
    double doCalcTension(const WireState& state) const final;

private:
    MuscleParameters muscle_;
    double fiberDamping_;  // max isometric forces per normalized fibre velocity
};

}  // namespace sinew

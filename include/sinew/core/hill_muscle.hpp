#pragma once
// What the Hill-type muscle laws on a rigid tendon share (docs/force-laws.md, "Imported muscles"): the
// parameters they are given (OpenSim's Muscle properties and a constant activation), which each law's own
// parameters extend, and the fibre's state they compute.
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
};

// max_isometric_force, optimal_fiber_length, tendon_slack_length (required), pennation_angle_at_optimal,
// max_contraction_velocity, activation (optional) into `muscle`.
void readMuscleParameters(const ForceLawParameters& parameters, MuscleParameters& muscle);
// Throws sinew::Error naming `law` and the parameter out of its range.
void checkMuscleParameters(const char* law, const MuscleParameters& muscle);

}  // namespace sinew

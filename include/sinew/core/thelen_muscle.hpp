#pragma once
// "thelen2003_muscle": a Hill-type muscle with the curves of Thelen (2003) as OpenSim's Thelen2003Muscle
// defines them, on a rigid tendon, so that the wire's tension is a function of its length, lengthening
// speed and a constant activation (docs/force-laws.md, "Imported muscles"). calcFiber is public: the
// tension distributions weigh activations with the same force-length and force-velocity factors.
#include <memory>

#include "sinew/core/force_law.hpp"
#include "sinew/core/hill_muscle.hpp"

namespace sinew {

struct ThelenMuscleParameters : MuscleParameters {
    double fmaxMuscleStrain = 0.6;      // passive strain at one max isometric force (OpenSim's FmaxMuscleStrain)
    double kShapeActive = 0.45;         // width of the Gaussian active force-length curve
    double kShapePassive = 4;           // exponential shape of the passive curve
    double af = 0.25;                   // force-velocity shape (Thelen's Af)
    double flen = 1.4;                  // lengthening force asymptote, in max isometric forces
};

class ThelenMuscle final : public HillMuscle {
public:
    explicit ThelenMuscle(const ThelenMuscleParameters& parameters);
    static std::shared_ptr<const ForceLaw> create(const ForceLawParameters& parameters);

    const ThelenMuscleParameters& getParameters() const { return parameters_; }
    // On a fixed-width fibre; fv at `activation` (Thelen's velocity scale grows with activation).
    MuscleFiberState calcFiber(double length, double speed, double activation) const override;

protected:
    double doCalcPotentialEnergy(double length) const override;

private:
    ThelenMuscleParameters parameters_;
};

}  // namespace sinew

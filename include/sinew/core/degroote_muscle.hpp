#pragma once
// "degroote_fregly2016_muscle": OpenSim's DeGrooteFregly2016Muscle on a rigid tendon, with its analytic
// curves (De Groote et al. 2016, as OpenSim codes them): the active force-length curve as three Gaussian-like
// terms (its width scalable), the passive curve exponential from 0.2 optimal lengths, the force-velocity
// curve a scaled asinh, a fixed-width pennation and linear fibre damping (docs/force-laws.md,
// "Imported muscles").
#include <memory>

#include "sinew/core/force_law.hpp"
#include "sinew/core/hill_muscle.hpp"

namespace sinew {

struct DeGrooteMuscleParameters : MuscleParameters {
    double activeForceWidthScale = 1;             // >= 1: widens the active force-length curve about 1
    double fiberDamping = 0;                      // max isometric forces per normalized fibre velocity
    double passiveFiberStrainAtOneNormForce = 0.6;
    bool ignorePassiveFiberForce = false;
};

class DeGrooteMuscle final : public HillMuscle {
public:
    // Throws sinew::Error naming the parameter out of its range.
    explicit DeGrooteMuscle(const DeGrooteMuscleParameters& parameters);
    static std::shared_ptr<const ForceLaw> create(const ForceLawParameters& parameters);

    const DeGrooteMuscleParameters& getParameters() const { return parameters_; }
    // On a fixed-width fibre; fv does not depend on activation.
    MuscleFiberState calcFiber(double length, double speed, double activation) const override;
    // The curves, of normalized fibre length or velocity.
    double calcActiveForceLength(double normalizedLength) const;
    static double calcForceVelocity(double normalizedVelocity);
    double calcPassiveForce(double normalizedLength) const;

protected:
    double doCalcPotentialEnergy(double length) const override;

private:
    DeGrooteMuscleParameters parameters_;
};

}  // namespace sinew

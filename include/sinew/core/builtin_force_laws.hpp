#pragma once
// The force laws sinew ships, registered in ForceLawRegistry::global() under the names below.
#include <vector>

#include "sinew/core/force_law.hpp"

namespace sinew {

// "prescribed_tension": a tension given as data, not computed from the wire's state. Either `tension`
// (constant, N) or `times` (s, strictly increasing) with `tensions` (N), interpolated linearly and held at
// the end values outside the series.
class PrescribedTension final : public ForceLaw {
public:
    PrescribedTension(std::vector<double> times, std::vector<double> tensions);
    static std::shared_ptr<const ForceLaw> create(const ForceLawParameters& parameters);

protected:
    double doCalcTension(const WireState& state) const override;

private:
    std::vector<double> times_;
    std::vector<double> tensions_;
};

// "spring_damper": passive wire, slack below its rest length. Tension = stiffness*(l - rest_length)
// + damping*dl/dt while l > rest_length, else 0, and never negative (a fast-shortening taut wire goes slack
// rather than push). Parameters: `stiffness` N/m >= 0, `damping` N*s/m >= 0, `rest_length` m > 0.
class SpringDamper final : public ForceLaw {
public:
    SpringDamper(double stiffness, double damping, double restLength);
    static std::shared_ptr<const ForceLaw> create(const ForceLawParameters& parameters);

    double getStiffness() const { return stiffness_; }
    double getDamping() const { return damping_; }
    double getRestLength() const { return restLength_; }

protected:
    double doCalcTension(const WireState& state) const override;
    double doCalcPotentialEnergy(double length) const override;

private:
    double stiffness_;
    double damping_;
    double restLength_;
};

}  // namespace sinew

#include "sinew/core/builtin_force_laws.hpp"

#include <algorithm>
#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

void requireFiniteAtLeast(const char* name, double value, double lowest) {
    if (!std::isfinite(value) || value < lowest)
        throw Error(std::string("parameter '") + name + "' must be a finite number >= " + std::to_string(lowest) +
                    ", got " + std::to_string(value));
}

}  // namespace

PrescribedTension::PrescribedTension(std::vector<double> times, std::vector<double> tensions)
    : times_(std::move(times)), tensions_(std::move(tensions)) {
    if (times_.empty() || times_.size() != tensions_.size())
        throw Error("parameters 'times' and 'tensions' need the same, non-zero number of values (got " +
                    std::to_string(times_.size()) + " and " + std::to_string(tensions_.size()) + ")");
    for (std::size_t i = 0; i < times_.size(); ++i) {
        requireFiniteAtLeast("tensions", tensions_[i], 0.0);
        if (!std::isfinite(times_[i]) || (i > 0 && !(times_[i] > times_[i - 1])))
            throw Error("parameter 'times' must be finite and strictly increasing (value " + std::to_string(i) + ")");
    }
}

std::shared_ptr<const ForceLaw> PrescribedTension::create(const ForceLawParameters& parameters) {
    if (parameters.has("tension")) {
        if (parameters.has("times") || parameters.has("tensions"))
            throw Error("give either 'tension' or 'times' with 'tensions', not both");
        return std::make_shared<PrescribedTension>(std::vector<double>{0.0},
                                                   std::vector<double>{parameters.getScalar("tension")});
    }
    return std::make_shared<PrescribedTension>(parameters.getVector("times"), parameters.getVector("tensions"));
}

double PrescribedTension::doCalcTension(const WireState& state) const {
    if (state.time <= times_.front()) return tensions_.front();
    if (state.time >= times_.back()) return tensions_.back();
    const auto upper = std::upper_bound(times_.begin(), times_.end(), state.time);
    const std::size_t i = static_cast<std::size_t>(upper - times_.begin());
    const double s = (state.time - times_[i - 1]) / (times_[i] - times_[i - 1]);
    return (1 - s) * tensions_[i - 1] + s * tensions_[i];
}

SpringDamper::SpringDamper(double stiffness, double damping, double restLength)
    : stiffness_(stiffness), damping_(damping), restLength_(restLength) {
    requireFiniteAtLeast("stiffness", stiffness, 0.0);
    requireFiniteAtLeast("damping", damping, 0.0);
    if (!std::isfinite(restLength) || !(restLength > 0))
        throw Error("parameter 'rest_length' must be a finite number > 0, got " + std::to_string(restLength));
}

std::shared_ptr<const ForceLaw> SpringDamper::create(const ForceLawParameters& parameters) {
    return std::make_shared<SpringDamper>(parameters.getScalar("stiffness"), parameters.getScalarOr("damping", 0.0),
                                          parameters.getScalar("rest_length"));
}

double SpringDamper::doCalcTension(const WireState& state) const {
    const double stretch = state.length - restLength_;
    if (stretch <= 0) return 0;
    return stiffness_ * stretch + damping_ * state.speed;
}

double SpringDamper::doCalcPotentialEnergy(double length) const {
    const double stretch = length - restLength_;
    return stretch > 0 ? 0.5 * stiffness_ * stretch * stretch : 0.0;
}

}  // namespace sinew

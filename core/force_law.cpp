#include "sinew/core/force_law.hpp"

#include <algorithm>
#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {

double ForceLawParameters::getScalar(const std::string& name) const {
    const std::vector<double>& v = getVector(name);
    if (v.size() != 1)
        throw Error("parameter '" + name + "' must be a single number, got " + std::to_string(v.size()) + " values");
    return v[0];
}

double ForceLawParameters::getScalarOr(const std::string& name, double fallback) const {
    return has(name) ? getScalar(name) : fallback;
}

const std::vector<double>& ForceLawParameters::getVector(const std::string& name) const {
    auto it = values_.find(name);
    if (it == values_.end()) throw Error("missing parameter '" + name + "'");
    if (std::find(read_.begin(), read_.end(), &it->first) == read_.end()) read_.push_back(&it->first);
    return it->second;
}

std::vector<std::string> ForceLawParameters::findUnread() const {
    std::vector<std::string> unread;
    for (const auto& [name, value] : values_)
        if (std::find(read_.begin(), read_.end(), &name) == read_.end()) unread.push_back(name);
    return unread;
}

ForceLawParameters& ForceLawParameters::operator=(const ForceLawParameters& other) {
    if (this != &other) {
        values_ = other.values_;
        copyReads(other);
    }
    return *this;
}

void ForceLawParameters::copyReads(const ForceLawParameters& other) {
    read_.clear();
    for (const std::string* name : other.read_) read_.push_back(&values_.find(*name)->first);
}

double ForceLaw::calcTension(const WireState& state) const {
    const double tension = doCalcTension(state);
    if (!std::isfinite(tension))
        throw Error("force law returned a non-finite tension at length " + std::to_string(state.length) +
                    " m, speed " + std::to_string(state.speed) + " m/s");
    return tension > 0 ? tension : 0.0;
}

double ForceLaw::calcPotentialEnergy(double length) const {
    const double energy = doCalcPotentialEnergy(length);
    if (!std::isfinite(energy))
        throw Error("force law returned a non-finite potential energy at length " + std::to_string(length) + " m");
    return energy;
}

}  // namespace sinew

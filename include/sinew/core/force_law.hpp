#pragma once
// A wire force law maps the wire's state (length, lengthening speed, time) to a tension >= 0.
// Geometry lives in the wire path; the law never sees links or points (docs/force-laws.md).
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sinew {

// What a force law may depend on, for one wire at one instant.
struct WireState {
    double length = 0;  // m, sum of segment lengths
    double speed = 0;   // m/s, d(length)/dt, positive when lengthening
    double time = 0;    // s
};

// Named numeric parameters of a force law, as written in a model file (a scalar is a 1-vector).
// Every parameter must be read by the law's factory; unread ones are reported (a typo must not pass).
class ForceLawParameters {
public:
    ForceLawParameters() = default;
    explicit ForceLawParameters(std::map<std::string, std::vector<double>> values) : values_(std::move(values)) {}
    // Copies take the values and what was read of them.
    ForceLawParameters(const ForceLawParameters& other) : values_(other.values_) { copyReads(other); }
    ForceLawParameters& operator=(const ForceLawParameters& other);
    ForceLawParameters(ForceLawParameters&&) = default;
    ForceLawParameters& operator=(ForceLawParameters&&) = default;

    void set(const std::string& name, std::vector<double> value) { values_[name] = std::move(value); }
    bool has(const std::string& name) const { return values_.count(name) != 0; }
    // Throws sinew::Error naming the parameter when it is missing or not a scalar.
    double getScalar(const std::string& name) const;
    double getScalarOr(const std::string& name, double fallback) const;
    const std::vector<double>& getVector(const std::string& name) const;
    // Names that were provided but never read by get*. Reading is tracked in the object, so one object is
    // read by one thread at a time (ForceLawRegistry::create gives each factory a copy of its own).
    std::vector<std::string> findUnread() const;
    const std::map<std::string, std::vector<double>>& getAll() const { return values_; }

private:
    void copyReads(const ForceLawParameters& other);

    std::map<std::string, std::vector<double>> values_;
    // The keys read: a map's keys stay where they are, and a list of a few pointers costs no allocation per read.
    mutable std::vector<const std::string*> read_;
};

// The extension point. Implement doCalcTension (and doCalcPotentialEnergy for conservative laws); callers
// use the non-virtual calc* methods, which enforce that a wire never pushes and never returns NaN.
class ForceLaw {
public:
    virtual ~ForceLaw() = default;

    // Tension in N, >= 0. A negative value from doCalcTension is a slack wire and becomes 0 (a wire cannot
    // push); a non-finite value throws sinew::Error.
    double calcTension(const WireState& state) const;
    // Energy stored in the conservative part of the law, J, at this length (0 for non-conservative laws);
    // a non-finite value throws sinew::Error.
    double calcPotentialEnergy(double length) const;

    // Laws driven by an activation (muscles) say how strong they are, for the tension distributions
    // (docs/tensions.md): the max isometric force, N, and the active force per unit activation at a wire
    // state as a multiple of it (OpenSim's fl × fv × cos(pennation) on a rigid tendon, fv at activation 1).
    // Laws without an activation have neither: nullopt, and multiplier 1.
    virtual std::optional<double> getMaxIsometricForce() const { return std::nullopt; }
    virtual double calcActiveForceMultiplier(const WireState& /*state*/) const { return 1; }

protected:
    virtual double doCalcTension(const WireState& state) const = 0;
    virtual double doCalcPotentialEnergy(double /*length*/) const { return 0; }
};

}  // namespace sinew

#pragma once
// Tension methods by name ("lp", "qp", "so", "ipopt"), as force laws are (force_law_registry.hpp): a method
// is the form of problem it solves and a factory for its solver, so a new objective is one new file that
// registers itself (docs/tensions.md, "Adding an objective").
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/tension_solver.hpp"

namespace sinew {

// The variables a method distributes, which decides the problem the builder makes for it
// (tension_problem.hpp).
enum class WireVariables {
    // Wire tensions, N, within [0, maxTension]: LP band rows and QP least-squares rows, equalities on the
    // virtual links' joints; extra column blocks with their own cost and weight.
    Tension,
    // Activations (OpenSim's static optimization): a wire's column per unit activation (its force per
    // activation times -J^T), every row exact, cost Σ |x|^p over every bounded variable (weights p).
    Activation
};

// What a method's solver is made with.
struct TensionMethodSettings {
    double activationExponent = 2;  // the cost exponent p (static optimization, Ipopt), >= 1
    ActiveSetOptions activeSet;     // the QP's (and static optimization's at p = 2)
};

using TensionSolverFactory = std::function<std::unique_ptr<TensionSolver>(const TensionMethodSettings&)>;

struct TensionMethod {
    WireVariables variables = WireVariables::Tension;
    TensionSolverFactory makeSolver;
};

class TensionMethodRegistry {
public:
    // The process-wide registry, with sinew's built-in methods already in it.
    static TensionMethodRegistry& global();

    // Throws sinew::Error when `name` is empty or already registered.
    void add(const std::string& name, TensionMethod method);
    bool contains(const std::string& name) const;
    std::vector<std::string> listNames() const;
    // Throws sinew::Error for an unknown name, listing the known ones.
    TensionMethod get(const std::string& name) const;

private:
    TensionMethodRegistry() = default;
    mutable std::mutex mutex_;
    std::map<std::string, TensionMethod> methods_;
};

// Registers a method at static-initialisation time, in a translation unit linked into the executable:
// `static sinew::TensionMethodRegistration reg{"name", {WireVariables::Tension, factory}};`
struct TensionMethodRegistration {
    TensionMethodRegistration(const std::string& name, TensionMethod method) {
        TensionMethodRegistry::global().add(name, std::move(method));
    }
};

}  // namespace sinew

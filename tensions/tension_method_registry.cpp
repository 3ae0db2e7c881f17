#include "sinew/tensions/tension_method_registry.hpp"

#include "sinew/core/error.hpp"
#include "sinew/tensions/ipopt_solver.hpp"
#include "sinew/tensions/lp_solver.hpp"
#include "sinew/tensions/static_optimization_solver.hpp"

namespace sinew {

TensionMethodRegistry& TensionMethodRegistry::global() {
    // Built-ins are added here rather than by static registration objects, which a static library drops.
    static TensionMethodRegistry* registry = [] {
        auto* r = new TensionMethodRegistry();
        r->add("lp", {WireVariables::Tension, [](const TensionMethodSettings&) { return std::make_unique<LpSolver>(); }});
        r->add("qp", {WireVariables::Tension, [](const TensionMethodSettings& settings) {
                          return std::make_unique<ActiveSetSolver>(settings.activeSet);
                      }});
        r->add("so", {WireVariables::Activation, [](const TensionMethodSettings& settings) {
                          return std::make_unique<StaticOptimizationSolver>(settings.activationExponent, settings.activeSet);
                      }});
        r->add("ipopt", {WireVariables::Tension, [](const TensionMethodSettings& settings) {
                             IpoptSolverOptions options;
                             options.exponent = settings.activationExponent;
                             return std::make_unique<IpoptSolver>(options);
                         }});
        return r;
    }();
    return *registry;
}

void TensionMethodRegistry::add(const std::string& name, TensionMethod method) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (name.empty()) throw Error("a tension method needs a non-empty name");
    if (!method.makeSolver) throw Error("tension method '" + name + "' has no solver factory");
    if (!methods_.emplace(name, std::move(method)).second)
        throw Error("tension method '" + name + "' is already registered");
}

bool TensionMethodRegistry::contains(const std::string& name) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return methods_.count(name) != 0;
}

std::vector<std::string> TensionMethodRegistry::listNames() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> names;
    for (const auto& entry : methods_) names.push_back(entry.first);
    return names;
}

TensionMethod TensionMethodRegistry::get(const std::string& name) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = methods_.find(name);
    if (it != methods_.end()) return it->second;
    std::string known;
    for (const auto& entry : methods_) known += (known.empty() ? "" : ", ") + entry.first;
    throw Error("unknown tension method '" + name + "' (known: " + known + ")");
}

}  // namespace sinew

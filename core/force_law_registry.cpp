#include "sinew/core/force_law_registry.hpp"

#include "sinew/core/builtin_force_laws.hpp"
#include "sinew/core/degroote_muscle.hpp"
#include "sinew/core/millard_muscle.hpp"
#include "sinew/core/thelen_muscle.hpp"
#include "sinew/core/error.hpp"

namespace sinew {

ForceLawRegistry& ForceLawRegistry::global() {
    // Built-ins are added here rather than by static registration objects, which a static library drops.
    static ForceLawRegistry* registry = [] {
        auto* r = new ForceLawRegistry();
        r->add("prescribed_tension", &PrescribedTension::create);
        r->add("spring_damper", &SpringDamper::create);
        r->add("degroote_fregly2016_muscle", &DeGrooteMuscle::create);
        r->add("millard2012_muscle", &MillardMuscle::create);
        r->add("thelen2003_muscle", &ThelenMuscle::create);
        return r;
    }();
    return *registry;
}

void ForceLawRegistry::add(const std::string& type, ForceLawFactory factory) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (type.empty()) throw Error("a force law type needs a non-empty name");
    if (!factories_.emplace(type, std::move(factory)).second)
        throw Error("force law type '" + type + "' is already registered");
}

bool ForceLawRegistry::contains(const std::string& type) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return factories_.count(type) != 0;
}

std::vector<std::string> ForceLawRegistry::listTypes() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> types;
    for (const auto& entry : factories_) types.push_back(entry.first);
    return types;
}

std::shared_ptr<const ForceLaw> ForceLawRegistry::create(const std::string& type,
                                                         const ForceLawParameters& parameters) const {
    ForceLawFactory factory;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = factories_.find(type);
        if (it == factories_.end()) {
            std::string known;
            for (const auto& entry : factories_) known += (known.empty() ? "" : ", ") + entry.first;
            throw Error("unknown force law type '" + type + "' (known: " + known + ")");
        }
        factory = it->second;
    }
    // A fresh copy tracks what this factory reads, whatever earlier reads of `parameters` marked; and
    // `parameters` is only read, so laws may be created from it on several threads at once.
    const ForceLawParameters tracked(parameters.getAll());
    std::shared_ptr<const ForceLaw> law;
    try {
        law = factory(tracked);
    } catch (const Error& e) {
        // A misspelt required parameter fails as "missing"; listing what was given shows the typo.
        std::string given;
        for (const auto& entry : parameters.getAll()) given += (given.empty() ? "" : ", ") + entry.first;
        throw Error("force law '" + type + "': " + e.what() + " (given: " + (given.empty() ? "none" : given) + ")");
    }
    const std::vector<std::string> unread = tracked.findUnread();
    if (!unread.empty()) {
        std::string names;
        for (const auto& name : unread) names += (names.empty() ? "'" : ", '") + name + "'";
        throw Error("force law '" + type + "' has no parameter " + names);
    }
    return law;
}

}  // namespace sinew

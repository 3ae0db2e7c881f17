#pragma once
// Force laws by name, so model files can name a law and researchers can add laws without touching sinew
// (docs/force-laws.md has a compiled example).
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "sinew/core/force_law.hpp"

namespace sinew {

// Builds a law from its parameters; throws sinew::Error naming a bad or missing parameter.
using ForceLawFactory = std::function<std::shared_ptr<const ForceLaw>(const ForceLawParameters&)>;

class ForceLawRegistry {
public:
    // The process-wide registry, with sinew's built-in laws already in it.
    static ForceLawRegistry& global();

    // Throws sinew::Error when `type` is already registered.
    void add(const std::string& type, ForceLawFactory factory);
    bool contains(const std::string& type) const;
    std::vector<std::string> listTypes() const;
    // Throws sinew::Error for an unknown type (listing the known ones), a factory error, or a parameter the
    // factory never read.
    std::shared_ptr<const ForceLaw> create(const std::string& type, const ForceLawParameters& parameters) const;

private:
    ForceLawRegistry() = default;
    mutable std::mutex mutex_;
    std::map<std::string, ForceLawFactory> factories_;
};

// Registers a law at static-initialisation time: `static sinew::ForceLawRegistration reg{"name", factory};`
// in the translation unit that defines it (one linked into the executable, not a static library).
struct ForceLawRegistration {
    ForceLawRegistration(const std::string& type, ForceLawFactory factory) {
        ForceLawRegistry::global().add(type, std::move(factory));
    }
};

}  // namespace sinew

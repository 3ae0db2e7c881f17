#include "sinew/core/coordinate_coupler.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

void applyCoordinateCouplers(const Model& model, Eigen::Ref<Eigen::VectorXd> q) {
    // The builder refuses chains, so no dependent coordinate is read after it is written.
    for (const CoordinateCoupler& c : model.getCouplers())
        q[c.dependentQ] = c.scaleFactor * c.function.calcValue(q[c.independentQ]);
}

void requireNoCouplers(const Model& model, const std::string& engine) {
    if (model.getNumCouplers() == 0) return;
    const CoordinateCoupler& c = model.getCouplers().front();
    const auto& coordinates = model.getCoordinates();
    throw Error("model '" + model.getName() + "': " + engine + " does not enforce coordinate couplers, and coupler '" +
                c.name + "' ties '" + coordinates[static_cast<std::size_t>(c.dependentQ)].name + "' to '" +
                coordinates[static_cast<std::size_t>(c.independentQ)].name + "' (" +
                std::to_string(model.getNumCouplers()) + " coupler(s) in all); simulate a model without couplers");
}

}  // namespace sinew

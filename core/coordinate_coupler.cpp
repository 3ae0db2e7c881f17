#include "sinew/core/coordinate_coupler.hpp"

namespace sinew {

void applyCoordinateCouplers(const Model& model, Eigen::Ref<Eigen::VectorXd> q) {
    // The builder refuses chains, so no dependent coordinate is read after it is written.
    for (const CoordinateCoupler& c : model.getCouplers())
        q[c.dependentQ] = c.scaleFactor * c.function.calcValue(q[c.independentQ]);
}

std::vector<CoordinateConstraint> getCoordinateConstraints(const Model& model) {
    std::vector<CoordinateConstraint> constraints;
    forEachCoordinateConstraint(model, [&](const CoordinateConstraint& c) { constraints.push_back(c); });
    return constraints;
}

double calcCoordinateConstraintSlope(const Model& model, const CoordinateConstraint& constraint, const Eigen::VectorXd& q) {
    if (constraint.coupler < 0) return 0;
    const CoordinateCoupler& c = model.getCouplers()[static_cast<std::size_t>(constraint.coupler)];
    return c.scaleFactor * c.function.calcDerivative(q[c.independentQ], 1);
}

double calcCoordinateConstraintGap(const Model& model, const CoordinateConstraint& constraint, const Eigen::VectorXd& q) {
    if (constraint.coupler < 0)
        return q[constraint.coordinate] - model.getCoordinates()[static_cast<std::size_t>(constraint.coordinate)].defaultValue;
    const CoordinateCoupler& c = model.getCouplers()[static_cast<std::size_t>(constraint.coupler)];
    return q[c.dependentQ] - c.scaleFactor * c.function.calcValue(q[c.independentQ]);
}

}  // namespace sinew

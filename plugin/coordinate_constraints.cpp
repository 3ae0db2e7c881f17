#include "sinew/plugin/coordinate_constraints.hpp"

#include <utility>

namespace sinew {
namespace {

// phi(x) = x_0 - s f(x_1) with x = (q_dep, q_ind); Simbody asks for derivatives up to second order.
class CouplerFunction : public SimTK::Function {
public:
    explicit CouplerFunction(const CoordinateCoupler& coupler) : function_(coupler.function), scale_(coupler.scaleFactor) {}
    SimTK::Real calcValue(const SimTK::Vector& x) const override { return x[0] - scale_ * function_.calcValue(x[1]); }
    // Only phi_0 = 1, phi_1 = -s f' and phi_11 = -s f'' are non-zero.
    SimTK::Real calcDerivative(const SimTK::Array_<int>& derivComponents, const SimTK::Vector& x) const override {
        if (derivComponents.size() == 1) return derivComponents[0] == 0 ? 1.0 : -scale_ * function_.calcDerivative(x[1], 1);
        for (int component : derivComponents)
            if (component == 0) return 0.0;
        return -scale_ * function_.calcDerivative(x[1], static_cast<int>(derivComponents.size()));
    }
    int getArgumentSize() const override { return 2; }
    int getMaxDerivativeOrder() const override { return 2; }
    SimTK::Function* clone() const override { return new CouplerFunction(*this); }

private:
    sinew::Function function_;
    double scale_;
};

// A coordinate's mobilized body and its index among that mobilizer's q.
std::pair<SimTK::MobilizedBodyIndex, SimTK::MobilizerQIndex> locateCoordinate(
    const Model& model, int q, const std::vector<SimTK::MobilizedBodyIndex>& mobilizedBodies) {
    const int link = model.getCoordinates()[static_cast<std::size_t>(q)].joint;
    return {mobilizedBodies[static_cast<std::size_t>(link)], SimTK::MobilizerQIndex(q - model.getJoint(link).qStart)};
}

}  // namespace

SimTK::ConstraintIndex addCouplerConstraint(SimTK::SimbodyMatterSubsystem& matter, const Model& model,
                                            const CoordinateCoupler& coupler,
                                            const std::vector<SimTK::MobilizedBodyIndex>& mobilizedBodies) {
    SimTK::Array_<SimTK::MobilizedBodyIndex> bodies;
    SimTK::Array_<SimTK::MobilizerQIndex> indices;
    for (int q : {coupler.dependentQ, coupler.independentQ}) {
        const auto [body, index] = locateCoordinate(model, q, mobilizedBodies);
        bodies.push_back(body);
        indices.push_back(index);
    }
    return SimTK::Constraint::CoordinateCoupler(matter, new CouplerFunction(coupler), bodies, indices).getConstraintIndex();
}

SimTK::ConstraintIndex addLockConstraint(SimTK::SimbodyMatterSubsystem& matter, const Model& model, int q,
                                         const std::vector<SimTK::MobilizedBodyIndex>& mobilizedBodies) {
    const auto [body, index] = locateCoordinate(model, q, mobilizedBodies);
    const double value = model.getCoordinates()[static_cast<std::size_t>(q)].defaultValue;
    return SimTK::Constraint::PrescribedMotion(matter, new SimTK::Function::Constant(value),  // takes ownership
                                               body, index)
        .getConstraintIndex();
}

}  // namespace sinew

#include "sinew/plugin/custom_mobilizer.hpp"

namespace sinew {

SimbodyFunction::SimbodyFunction(sinew::Function function, int argumentSize)
    : function_(std::move(function)), argumentSize_(argumentSize) {}

SimTK::Real SimbodyFunction::calcValue(const SimTK::Vector& x) const {
    return function_.calcValue(argumentSize_ > 0 ? x[0] : 0.0);
}

// derivComponents lists the argument differentiated for each order; with one argument only its length counts.
SimTK::Real SimbodyFunction::calcDerivative(const SimTK::Array_<int>& derivComponents, const SimTK::Vector& x) const {
    if (argumentSize_ == 0) return 0.0;
    return function_.calcDerivative(x[0], static_cast<int>(derivComponents.size()));
}

SimTK::MobilizedBodyIndex addCustomMobilizer(SimTK::MobilizedBody& parent, const SimTK::Transform& X_PF,
                                             const SimTK::Body& body, const SimTK::Transform& X_BM, const Joint& joint) {
    SimTK::Array_<const SimTK::Function*> functions;  // FunctionBased takes ownership
    SimTK::Array_<SimTK::Array_<int>> coordinateIndices;
    SimTK::Array_<SimTK::Vec3> axes;
    for (const TransformAxis& axis : joint.transformAxes) {
        const bool driven = axis.coordinate != kNoCoordinate;
        functions.push_back(new SimbodyFunction(axis.function, driven ? 1 : 0));
        coordinateIndices.push_back(driven ? SimTK::Array_<int>(1, axis.coordinate) : SimTK::Array_<int>());
        axes.push_back(SimTK::Vec3(axis.axis[0], axis.axis[1], axis.axis[2]));
    }
    return SimTK::MobilizedBody::FunctionBased(parent, X_PF, body, X_BM, joint.nu, functions, coordinateIndices, axes)
        .getMobilizedBodyIndex();
}

}  // namespace sinew

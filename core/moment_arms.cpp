#include "sinew/core/moment_arms.hpp"

#include "sinew/core/wire_jacobian.hpp"

namespace sinew {

void calcMomentArms(const Model& model, Data& data, Eigen::Ref<Eigen::MatrixXd> R) {
    // A unit tension's generalized force is -J^T 1 (docs/wire-jacobian.md), so each row is -J's.
    calcWireJacobian(model, data, R);
    R = -R;
    // Chain rule along each coupler. Dependent coordinates drive no coupler (the builder refuses chains),
    // so every dependent column is still the partial derivative when the first loop reads it, and every
    // independent column is complete when the second loop divides it.
    const auto& couplers = model.getCouplers();
    for (const CoordinateCoupler& c : couplers)
        R.col(c.independentU) += c.scaleFactor * c.function.calcDerivative(data.q[c.independentQ], 1) * R.col(c.dependentU);
    for (const CoordinateCoupler& c : couplers) {
        const double a = c.scaleFactor * c.function.calcDerivative(data.q[c.independentQ], 1);
        if (a == 0)
            R.col(c.dependentU).setZero();
        else
            R.col(c.dependentU) = R.col(c.independentU) / a;
    }
}

}  // namespace sinew

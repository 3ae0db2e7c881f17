#include "sinew/core/moment_arms.hpp"

#include "sinew/core/wire_jacobian.hpp"

namespace sinew {

void calcMomentArms(const Model& model, Data& data, Eigen::Ref<Eigen::MatrixXd> R) {
    // A unit tension's generalized force is -J^T 1 (docs/wire-jacobian.md), so each row is -J's.
    calcWireJacobian(model, data, R);
    R = -R;
}

}  // namespace sinew

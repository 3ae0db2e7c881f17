#include "sinew/core/coordinate_coupler.hpp"

namespace sinew {

void applyCoordinateCouplers(const Model& model, Eigen::Ref<Eigen::VectorXd> q) {
    // The builder refuses chains, so no dependent coordinate is read after it is written.
    for (const CoordinateCoupler& c : model.getCouplers())
        q[c.dependentQ] = c.scaleFactor * c.function.calcValue(q[c.independentQ]);
}

}  // namespace sinew

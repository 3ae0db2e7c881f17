#include "sinew/tools/force_element_loads.hpp"

#include "sinew/core/force_elements.hpp"
#include "sinew/core/kinematics.hpp"

namespace sinew {

ForceElementLoads::ForceElementLoads(const Model& model)
    : model_(model), direct_(model.getNumU()), fromLinks_(model.getNumU()) {}

// Inverse dynamics is linear in the applied forces, so the elements' share comes off afterwards.
void ForceElementLoads::subtractFrom(Data& data, Eigen::Ref<Eigen::VectorXd> tau) {
    if (model_.getForceElements().empty()) return;
    for (SpatialVector& F : data.scratchF_G) F.setZero();
    direct_.setZero();
    addForceElementForces(model_, data, data.scratchF_G, direct_);
    calcGeneralizedForcesFromLinkForces(model_, data, fromLinks_);
    tau -= direct_ + fromLinks_;
}

}  // namespace sinew

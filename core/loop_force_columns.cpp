#include "sinew/core/loop_force_columns.hpp"

#include <string>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"

namespace sinew {
namespace {

// Adds f_G acting at the point p_B of `link` to F (moment about the link's origin). Loop ends are never
// ground: the model builder refuses them.
void addPointForce(const Data& data, int link, const Eigen::Vector3d& p_B, const Eigen::Vector3d& f_G,
                   std::vector<SpatialVector>& F) {
    const std::size_t b = static_cast<std::size_t>(link);
    F[b].head<3>() += (data.R_GB[b] * p_B).cross(f_G);
    F[b].tail<3>() += f_G;
}

}  // namespace

void addLoopForce(const Model& model, const Data& data, int loopIndex, const Eigen::Vector3d& f_G,
                  std::vector<SpatialVector>& F) {
    const Loop& loop = model.getLoop(loopIndex);
    addPointForce(data, loop.linkB, loop.p_B, f_G, F);
    addPointForce(data, loop.linkA, loop.p_A, -f_G, F);
}

void calcLoopForceColumns(const Model& model, Data& data, int loopIndex, Eigen::Ref<Eigen::MatrixXd> columns) {
    if (loopIndex < 0 || loopIndex >= model.getNumLoops())
        throw Error("loop force columns of model '" + model.getName() + "': loop " + std::to_string(loopIndex) +
                    ", expected 0 to " + std::to_string(model.getNumLoops() - 1));
    if (columns.rows() != model.getNumU() || columns.cols() != 3)
        throw Error("loop force columns of model '" + model.getName() + "': the columns are " +
                    std::to_string(columns.rows()) + " x " + std::to_string(columns.cols()) + ", expected nu x 3 = " +
                    std::to_string(model.getNumU()) + " x 3");
    for (int c = 0; c < 3; ++c) {
        for (SpatialVector& F : data.scratchF_G) F.setZero();
        addLoopForce(model, data, loopIndex, Eigen::Vector3d::Unit(c), data.scratchF_G);
        calcGeneralizedForcesFromLinkForces(model, data, columns.col(c));
    }
}

}  // namespace sinew

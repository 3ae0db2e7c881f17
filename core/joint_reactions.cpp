#include "sinew/core/joint_reactions.hpp"

#include <string>

#include "sinew/core/error.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/loop_force_columns.hpp"

namespace sinew {

JointReactionsData::JointReactionsData(const Model& model)
    : F_GM(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero()),
      F_BM(F_GM),
      loopForce_G(static_cast<std::size_t>(model.getNumLoops()), Eigen::Vector3d::Zero()),
      loopForce_B(loopForce_G),
      residual(Eigen::VectorXd::Zero(model.getNumU())),
      linkForces_G(F_GM),
      loopColumns(Eigen::MatrixXd::Zero(model.getNumU(), 3 * model.getNumLoops())),
      loopForces(Eigen::VectorXd::Zero(3 * model.getNumLoops())),
      loopSolver(model.getNumU(), 3 * model.getNumLoops()) {
    // A loop that repeats a constraint the tree already has leaves a column direction at roundoff (about
    // 1e-16 of the largest); genuine ones of real models sit far above 1e-9, as in calcForwardDynamics.
    loopSolver.setThreshold(1e-9);
}

namespace {

void checkSizes(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u, const Eigen::VectorXd& udot,
                const Eigen::VectorXd& tau, const std::vector<SpatialVector>& linkForces) {
    auto require = [&](Eigen::Index got, int expected, const char* what) {
        if (got != expected)
            throw Error("joint reactions of model '" + model.getName() + "': " + what + " has " + std::to_string(got) +
                        " entries, expected " + std::to_string(expected));
    };
    require(q.size(), model.getNumQ(), "q");
    require(u.size(), model.getNumU(), "u");
    require(udot.size(), model.getNumU(), "udot");
    require(tau.size(), model.getNumU(), "the applied generalized forces");
    require(static_cast<Eigen::Index>(linkForces.size()), model.getNumLinks(), "the applied link forces");
}

}  // namespace

void calcJointReactions(const Model& model, Data& data, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                        const Eigen::VectorXd& udot, const Eigen::VectorXd& appliedGeneralizedForces,
                        const std::vector<SpatialVector>& appliedLinkForces, JointReactionsData& reactions) {
    checkSizes(model, q, u, udot, appliedGeneralizedForces, appliedLinkForces);
    reactions.linkForces_G = appliedLinkForces;
    if (model.getNumLoops() > 0) {
        // The loop forces make up what the tree's inverse dynamics needs beyond the applied generalized
        // forces (docs/joint-loads.md, eq. 3).
        calcInverseDynamics(model, data, q, u, udot, appliedLinkForces, reactions.residual);
        reactions.residual -= appliedGeneralizedForces;
        for (int k = 0; k < model.getNumLoops(); ++k)
            calcLoopForceColumns(model, data, k, reactions.loopColumns.middleCols<3>(3 * k));
        reactions.loopSolver.compute(reactions.loopColumns);
        reactions.loopForces = reactions.loopSolver.solve(reactions.residual);
        for (int k = 0; k < model.getNumLoops(); ++k) {
            const std::size_t l = static_cast<std::size_t>(k);
            reactions.loopForce_G[l] = reactions.loopForces.segment<3>(3 * k);
            const Eigen::Matrix3d& R_GB = data.R_GB[static_cast<std::size_t>(model.getLoop(k).linkB)];
            reactions.loopForce_B[l] = R_GB.transpose() * reactions.loopForce_G[l];
            addLoopForce(model, data, k, reactions.loopForce_G[l], reactions.linkForces_G);
        }
    }
    // With every external force in, the subtree net force (inertial less applied) that inverse dynamics
    // leaves in Data::scratchF_G, about each link's origin, is what the joint transmits (eq. 1).
    calcInverseDynamics(model, data, q, u, udot, reactions.linkForces_G, reactions.residual);
    reactions.residual -= appliedGeneralizedForces;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const std::size_t b = static_cast<std::size_t>(i);
        const SpatialVector F_GM = shiftForce(data.scratchF_G[b], data.p_GM[b] - data.p_GB[b]);
        reactions.F_GM[b] = F_GM;
        reactions.F_BM[b] << data.R_GB[b].transpose() * F_GM.head<3>(), data.R_GB[b].transpose() * F_GM.tail<3>();
    }
}

}  // namespace sinew

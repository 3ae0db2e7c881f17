#include "sinew/tensions/reserve_columns.hpp"

#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// A reserve's DOF or links must be the model's; a body actuator's axis must have a direction.
void checkReserve(const Model& model, const ReserveActuator& reserve) {
    const auto fail = [&](const std::string& what) { throw Error("tensions: reserve '" + reserve.name + "' " + what); };
    if (!reserve.body) {
        if (reserve.dof < 0 || reserve.dof >= model.getNumU())
            fail("acts on DOF " + std::to_string(reserve.dof) + ", expected 0 to " + std::to_string(model.getNumU() - 1));
        return;
    }
    const BodyActuator& body = *reserve.body;
    const bool pointForce = body.kind == BodyActuator::Kind::PointForce;
    for (const int link : {body.link, body.reactionLink})
        if (link < kGround || link >= model.getNumLinks())
            fail("acts on link " + std::to_string(link) + ", expected ground (-1) or 0 to " +
                 std::to_string(model.getNumLinks() - 1));
    if (pointForce && body.link == kGround) fail("pushes ground, which cannot move");
    if (!(body.axis.norm() > 0) || !body.axis.allFinite() || !body.point.allFinite())
        fail(std::string("has ") + (pointForce ? "direction" : "axis") + " (" + std::to_string(body.axis.x()) + ", " +
             std::to_string(body.axis.y()) + ", " + std::to_string(body.axis.z()) +
             ") or a point that is not finite; expected a finite, non-zero vector");
}

}  // namespace

void checkReserveLimits(const ReserveActuator& reserve) {
    if (!(reserve.optimalForce > 0) || !std::isfinite(reserve.optimalForce) || !(reserve.minControl <= reserve.maxControl))
        throw Error("static optimization: reserve '" + reserve.name + "' has optimal force " +
                    std::to_string(reserve.optimalForce) + " and control bounds [" + std::to_string(reserve.minControl) +
                    ", " + std::to_string(reserve.maxControl) + "], expected a finite optimal force > 0 and min <= max");
}

ReserveColumns::ReserveColumns(const Model& model, std::vector<ReserveActuator> reserves)
    : model_(model), reserves_(std::move(reserves)), column_(model.getNumU()) {
    for (const ReserveActuator& reserve : reserves_) {
        checkReserve(model, reserve);
        checkReserveLimits(reserve);
    }
}

void ReserveColumns::addPattern(int columnOffset, std::vector<Eigen::Triplet<double>>& entries) const {
    for (int r = 0; r < count(); ++r) {
        const ReserveActuator& reserve = reserves_[static_cast<std::size_t>(r)];
        if (!reserve.body) {
            entries.emplace_back(reserve.dof, columnOffset + r, 1.0);
            continue;
        }
        for (int i = 0; i < model_.getNumU(); ++i) entries.emplace_back(i, columnOffset + r, 1.0);
    }
}

// A DOF reserve's generalized force per unit control is its optimal force on its row; a body reserve's
// follows the configuration (J^T F).
void ReserveColumns::update(const Data& data, int columnOffset, Eigen::SparseMatrix<double>& A) {
    for (int r = 0; r < count(); ++r) {
        const ReserveActuator& reserve = reserves_[static_cast<std::size_t>(r)];
        double* value = A.valuePtr() + A.outerIndexPtr()[columnOffset + r];
        if (!reserve.body) {
            *value = reserve.optimalForce;
            continue;
        }
        calcBodyActuatorGeneralizedForce(model_, data, *reserve.body, column_);
        for (int i = 0; i < model_.getNumU(); ++i) value[i] = column_[i] * reserve.optimalForce;
    }
}

void ReserveColumns::setVariables(double /*wireWeight*/, Eigen::Ref<Eigen::VectorXd> lower,
                                  Eigen::Ref<Eigen::VectorXd> upper, Eigen::Ref<Eigen::VectorXd> cost,
                                  Eigen::Ref<Eigen::VectorXd> weight) const {
    for (int r = 0; r < count(); ++r) {
        lower[r] = reserves_[static_cast<std::size_t>(r)].minControl;
        upper[r] = reserves_[static_cast<std::size_t>(r)].maxControl;
    }
    cost.setOnes();
    weight.setOnes();
}

}  // namespace sinew

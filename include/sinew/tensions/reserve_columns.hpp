#pragma once
// Reserve actuators as a column block of the tension problem (problem_columns.hpp): OpenSim's
// CoordinateActuators on one DOF, and its PointActuators and TorqueActuators on links (residuals on a
// floating root), each variable the actuator's control c, its column the generalized force of c times its
// optimal force (e_dof F_r, or J^T F_r for a body actuator at the frame's configuration).
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sinew/core/body_actuator.hpp"
#include "sinew/core/model.hpp"
#include "sinew/tensions/problem_columns.hpp"

namespace sinew {

// A generalized force on one DOF (OpenSim's CoordinateActuator used as a reserve), or with `body` a force
// or torque on links (PointActuator, TorqueActuator: residuals on a floating root), whose generalized force
// per unit control depends on the state.
struct ReserveActuator {
    std::string name;
    int dof = 0;                // row (index into u); unused with `body`
    double optimalForce = 1;    // N m or N per unit control, > 0
    double minControl = -std::numeric_limits<double>::infinity();
    double maxControl = std::numeric_limits<double>::infinity();
    std::optional<BodyActuator> body = std::nullopt;
};

// Throws sinew::Error naming the reserve when its optimal force is not finite and > 0 or its control
// bounds are crossed.
void checkReserveLimits(const ReserveActuator& reserve);

class ReserveColumns final : public ProblemColumns {
public:
    // Throws sinew::Error naming the reserve whose DOF or links are not the model's, whose axis has no
    // direction, or whose limits are invalid.
    ReserveColumns(const Model& model, std::vector<ReserveActuator> reserves);

    int count() const override { return static_cast<int>(reserves_.size()); }
    // A DOF reserve reaches its row; a body reserve every row.
    void addPattern(int columnOffset, std::vector<Eigen::Triplet<double>>& entries) const override;
    void update(const Data& data, int columnOffset, Eigen::SparseMatrix<double>& A) override;
    // Bounds: the controls' limits. LP cost 1 and QP weight 1 per unit control: a reserve is the last resort
    // of the LP and the QP, whose wires cost about 1 per newton and weigh the tiny regulariser.
    void setVariables(double wireWeight, Eigen::Ref<Eigen::VectorXd> lower, Eigen::Ref<Eigen::VectorXd> upper,
                      Eigen::Ref<Eigen::VectorXd> cost, Eigen::Ref<Eigen::VectorXd> weight) const override;

    const std::vector<ReserveActuator>& getReserves() const { return reserves_; }

private:
    const Model& model_;
    std::vector<ReserveActuator> reserves_;
    Eigen::VectorXd column_;  // (nu) a body reserve's generalized force per unit force
};

}  // namespace sinew

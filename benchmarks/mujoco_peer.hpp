#pragma once
// MuJoCo (Debian's libmujoco 2.2.2) as a peer on sinew's own model: the model written as MJCF by sinew's
// writer (include/sinew/io/mjcf_model_writer.hpp), loaded by MuJoCo with its default options, and set to the
// benchmark's state through the writer's qpos and qvel maps. One evaluation is mj_forward: everything MuJoCo
// needs for qacc from qpos and qvel (kinematics, tendons, the mass matrix and its factors, passive forces,
// bias forces, the connect constraints' solver).
#include <Eigen/Core>
#include <memory>
#include <string>

#include "sinew/core/model.hpp"

struct mjModel_;
struct mjData_;

namespace sinew_benchmarks {

class MujocoPeer {
public:
    // Throws sinew::Error when the model cannot be written as MJCF, std::runtime_error with MuJoCo's message
    // when MuJoCo refuses it. `tau` (nu) goes in as qfrc_applied.
    MujocoPeer(const sinew::Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u, const Eigen::VectorXd& tau);
    ~MujocoPeer();
    MujocoPeer(const MujocoPeer&) = delete;
    MujocoPeer& operator=(const MujocoPeer&) = delete;

    void evaluate();  // mj_forward
    Eigen::VectorXd getUdot() const;  // qacc in sinew's speed coordinates
    // max |MuJoCo's tendon length - sinew's wire length| at the state, m.
    double calcTendonLengthDifference(const Eigen::VectorXd& wireLengths) const;
    int getNumConstraintRows() const;  // efc rows (3 per connect)

private:
    const sinew::Model& model_;
    Eigen::VectorXd q_;
    std::unique_ptr<mjModel_, void (*)(mjModel_*)> mujocoModel_;
    std::unique_ptr<mjData_, void (*)(mjData_*)> mujocoData_;
};

}  // namespace sinew_benchmarks

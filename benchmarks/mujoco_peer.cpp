#include "mujoco_peer.hpp"

#include <mujoco/mujoco.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>

#include "sinew/io/mjcf_model_writer.hpp"

namespace sinew_benchmarks {

MujocoPeer::MujocoPeer(const sinew::Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                       const Eigen::VectorXd& tau)
    : model_(model), q_(q), mujocoModel_(nullptr, mj_deleteModel), mujocoData_(nullptr, mj_deleteData) {
    // A name of its own: the model's name may hold anything.
    static int written = 0;
    const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                       ("sinew_benchmark_" + std::to_string(::getpid()) + "_" + std::to_string(written++) + ".xml");
    sinew::writeMjcfModel(model, file.string());
    char error[1000] = "";
    mujocoModel_.reset(mj_loadXML(file.string().c_str(), nullptr, error, sizeof error));
    std::filesystem::remove(file);
    if (!mujocoModel_) throw std::runtime_error("MuJoCo " + std::string(mj_versionString()) + " refuses the written model: " + error);
    mujocoData_.reset(mj_makeData(mujocoModel_.get()));
    Eigen::Map<Eigen::VectorXd>(mujocoData_->qpos, mujocoModel_->nq) = sinew::toMujocoQpos(model, q);
    Eigen::Map<Eigen::VectorXd>(mujocoData_->qvel, mujocoModel_->nv) = sinew::toMujocoVelocity(model, q, u);
    Eigen::Map<Eigen::VectorXd>(mujocoData_->qfrc_applied, mujocoModel_->nv) = sinew::toMujocoVelocity(model, q, tau);
}

MujocoPeer::~MujocoPeer() = default;

void MujocoPeer::evaluate() { mj_forward(mujocoModel_.get(), mujocoData_.get()); }

Eigen::VectorXd MujocoPeer::getUdot() const {
    return sinew::fromMujocoVelocity(model_, q_, Eigen::Map<const Eigen::VectorXd>(mujocoData_->qacc, mujocoModel_->nv));
}

double MujocoPeer::calcTendonLengthDifference(const Eigen::VectorXd& wireLengths) const {
    // The writer keeps the wires' order.
    if (mujocoModel_->ntendon == 0) return 0;
    return (Eigen::Map<const Eigen::VectorXd>(mujocoData_->ten_length, mujocoModel_->ntendon) - wireLengths).lpNorm<Eigen::Infinity>();
}

int MujocoPeer::getNumConstraintRows() const { return mujocoData_->nefc; }

}  // namespace sinew_benchmarks

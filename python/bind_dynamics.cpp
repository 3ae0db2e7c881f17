// Inverse dynamics per frame (core/inverse_dynamics.hpp) and per motion (tools/inverse_dynamics_tool.hpp), and
// sinew's O(N) closed-chain forward dynamics (core/forward_dynamics.hpp).
#include <limits>
#include <memory>

#include "bindings.hpp"
#include "sinew/core/assembly_schedule.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/tools/inverse_dynamics_tool.hpp"

namespace sinew::python {
namespace {

AssemblySchedule::Kind toScheduleKind(const std::string& kind) {
    if (kind == "automatic") return AssemblySchedule::Kind::Automatic;
    if (kind == "serial") return AssemblySchedule::Kind::Serial;
    if (kind == "balanced") return AssemblySchedule::Kind::Balanced;
    throw Error("schedule expects automatic, serial or balanced, got '" + kind + "'");
}

// One model's schedule and buffers, built once and reused by every call, as the C++ API intends.
class ForwardDynamics {
public:
    ForwardDynamics(std::shared_ptr<Model> model, const std::string& hangBy, const std::string& schedule, int threads)
        : model_(std::move(model)),
          schedule_(*model_, toScheduleKind(schedule), hangBy.empty() ? -1 : findLinkOrThrow(*model_, hangBy, "hang_by")),
          data_(*model_),
          fd_(*model_, schedule_),
          threads_(threads) {
        if (threads < 1) throw Error("threads expects at least 1, got " + std::to_string(threads));
    }

    Eigen::VectorXd calc(const Eigen::VectorXd& q, const Eigen::VectorXd& u, const Eigen::VectorXd& tau,
                         const std::optional<Eigen::MatrixXd>& linkForces) {
        const Model& model = *model_;
        checkSize(model, q, model.getNumQ(), "q");
        checkSize(model, u, model.getNumU(), "u");
        checkSize(model, tau, model.getNumU(), "tau");
        const std::vector<SpatialVector> forces = toLinkForces(model, linkForces);
        calcPositionKinematics(model, data_, q);
        calcVelocityKinematics(model, data_, u);
        calcForwardDynamics(model, schedule_, data_, tau, forces, fd_, threads_);
        return fd_.udot;
    }

    const ForwardDynamicsData& getOutputs() const { return fd_; }
    const AssemblySchedule& getSchedule() const { return schedule_; }

private:
    std::shared_ptr<const Model> model_;
    AssemblySchedule schedule_;
    Data data_;
    ForwardDynamicsData fd_;
    int threads_;
};

}  // namespace

void bindDynamics(py::module_& m) {
    m.def(
        "calc_inverse_dynamics",
        [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u, const Eigen::VectorXd& udot,
           const std::optional<Eigen::MatrixXd>& linkForces) {
            checkSize(model, q, model.getNumQ(), "q");
            checkSize(model, u, model.getNumU(), "u");
            checkSize(model, udot, model.getNumU(), "udot");
            Data data(model);
            Eigen::VectorXd tau(model.getNumU());
            calcInverseDynamics(model, data, q, u, udot, toLinkForces(model, linkForces), tau);
            return tau;
        },
        py::arg("model"), py::arg("q"), py::arg("u"), py::arg("udot"), py::arg("link_forces") = py::none(),
        "Generalized forces tau (nu) with M udot + C = tau + gravity + applied, loops ignored (recursive "
        "Newton-Euler). link_forces: numLinks x 6, [moment about the link origin; force], ground axes.");

    m.def(
        "run_inverse_dynamics",
        [](const Model& model, const StorageTable& coordinates, const ExternalLoads* loads, double lowpassCutoffHz,
           double startTime, double finalTime) {
            InverseDynamicsOptions options;
            options.lowpassCutoffHz = lowpassCutoffHz;
            options.startTime = startTime;
            options.finalTime = finalTime;
            py::gil_scoped_release release;
            return runInverseDynamics(model, coordinates, loads, options);
        },
        py::arg("model"), py::arg("coordinates"), py::arg("external_loads") = nullptr,
        py::arg("lowpass_cutoff_hz") = -1.0, py::arg("start_time") = -std::numeric_limits<double>::infinity(),
        py::arg("final_time") = std::numeric_limits<double>::infinity(),
        "OpenSim's inverse dynamics tool over a coordinates table (what `sinew inverse-dynamics` runs): a "
        "StorageTable of generalized forces named as OpenSim names them.");

    py::class_<ForwardDynamics>(m, "ForwardDynamics",
                                "sinew's assembly-disassembly forward dynamics for one model (docs/closed-chain.md). "
                                "hang_by welds a link to ground; virtual links get udot 0.")
        .def(py::init<std::shared_ptr<Model>, const std::string&, const std::string&, int>(), py::arg("model"),
             py::arg("hang_by") = "", py::arg("schedule") = "automatic", py::arg("threads") = 1)
        .def("calc", &ForwardDynamics::calc, py::arg("q"), py::arg("u"), py::arg("tau"),
             py::arg("link_forces") = py::none(),
             "udot (nu) for generalized forces tau (nu), gravity and link_forces (numLinks x 6, as in "
             "calc_inverse_dynamics); loops and the hang held at acceleration level.")
        .def_property_readonly("loop_forces",
                               [](const ForwardDynamics& f) {
                                   const std::vector<Eigen::Vector3d>& forces = f.getOutputs().loopForce;
                                   Eigen::MatrixXd out(static_cast<Eigen::Index>(forces.size()), 3);
                                   for (std::size_t k = 0; k < forces.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = forces[k].transpose();
                                   return out;
                               },
                               "N, force on each loop's link B at its loop point, ground axes (numLoops x 3), last call")
        .def_property_readonly("hang_force", [](const ForwardDynamics& f) { return SpatialVector(f.getOutputs().hangForce); })
        .def_property_readonly("redundant_constraints", [](const ForwardDynamics& f) { return f.getOutputs().redundantConstraints; })
        .def_property_readonly("loop_conditioning", [](const ForwardDynamics& f) { return f.getOutputs().loopConditioning; })
        .def_property_readonly("num_bodies", [](const ForwardDynamics& f) { return f.getSchedule().getNumBodies(); });
}

}  // namespace sinew::python

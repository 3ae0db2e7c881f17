// Forward simulation with either engine (core/simulation.hpp options and frames): sinew's own
// (core/forward_simulation.hpp) or Simbody's (plugin/simbody_simulation.hpp). This file includes Simbody
// and so must never see NDEBUG (plugin/ndebug_guard.hpp refuses it).
#include "bindings.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/plugin/simbody_simulation.hpp"

namespace sinew::python {
namespace {

// The frames as arrays, one row per reported time.
struct SimulationResult {
    Eigen::VectorXd time;              // s (frames)
    Eigen::MatrixXd q, u, tensions;    // frames x nq, nu, numWires
    Eigen::VectorXd kineticEnergy, potentialEnergy;  // J (frames)
    SimulationSummary summary;
};

SimulationResult simulate(const Model& model, const ForwardSimulationOptions& options, const std::string& engine) {
    if (engine != "sinew" && engine != "simbody")
        throw Error("engine expects sinew or simbody, got '" + engine + "'");
    std::vector<SimulationFrame> frames;
    const auto record = [&](const SimulationFrame& frame) { frames.push_back(frame); };
    SimulationResult result;
    result.summary = engine == "sinew" ? simulateForwardSinew(model, options, record) : simulateForward(model, options, record);
    const auto n = static_cast<Eigen::Index>(frames.size());
    result.time.resize(n);
    result.q.resize(n, model.getNumQ());
    result.u.resize(n, model.getNumU());
    result.tensions.resize(n, model.getNumWires());
    result.kineticEnergy.resize(n);
    result.potentialEnergy.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const SimulationFrame& frame = frames[static_cast<std::size_t>(i)];
        result.time[i] = frame.time;
        result.q.row(i) = frame.q.transpose();
        result.u.row(i) = frame.u.transpose();
        result.tensions.row(i) = frame.tensions.transpose();
        result.kineticEnergy[i] = frame.kineticEnergy;
        result.potentialEnergy[i] = frame.potentialEnergy;
    }
    return result;
}

}  // namespace

void bindSimulation(py::module_& m) {
    using Options = ForwardSimulationOptions;
    py::enum_<Options::Integrator>(m, "Integrator")
        .value("Adaptive", Options::Integrator::Adaptive)
        .value("RungeKutta4Fixed", Options::Integrator::RungeKutta4Fixed);
    py::class_<Options>(m, "ForwardSimulationOptions", "What `sinew simulate` is asked (core/simulation.hpp).")
        .def(py::init<>())
        .def_readwrite("hang_by", &Options::hangBy)
        .def_readwrite("duration", &Options::duration)
        .def_readwrite("report_interval", &Options::reportInterval)
        .def_readwrite("integrator", &Options::integrator)
        .def_readwrite("accuracy", &Options::accuracy)
        .def_readwrite("fixed_step", &Options::fixedStep)
        .def_readwrite("initial_speeds", &Options::initialSpeeds)
        .def_readwrite("max_steps", &Options::maxSteps)
        .def_readwrite("min_step", &Options::minStep);
    py::class_<SimulationSummary>(m, "SimulationSummary")
        .def_readonly("frames", &SimulationSummary::frames)
        .def_readonly("steps", &SimulationSummary::steps)
        .def_readonly("wire_switches", &SimulationSummary::wireSwitches)
        .def_readonly("wall_seconds", &SimulationSummary::wallSeconds)
        .def_readonly("initial_energy", &SimulationSummary::initialEnergy)
        .def_readonly("max_energy_drift", &SimulationSummary::maxEnergyDrift)
        .def_readonly("peak_kinetic_energy", &SimulationSummary::peakKineticEnergy)
        .def_readonly("max_constraint_violation", &SimulationSummary::maxConstraintViolation)
        .def_readonly("max_virtual_link_residual", &SimulationSummary::maxVirtualLinkResidual);
    py::class_<SimulationResult>(m, "SimulationResult", "One row per reported frame.")
        .def_readonly("time", &SimulationResult::time)
        .def_readonly("q", &SimulationResult::q)
        .def_readonly("u", &SimulationResult::u)
        .def_readonly("tensions", &SimulationResult::tensions)
        .def_readonly("kinetic_energy", &SimulationResult::kineticEnergy)
        .def_readonly("potential_energy", &SimulationResult::potentialEnergy)
        .def_readonly("summary", &SimulationResult::summary);
    m.def(
        "simulate",
        [](const Model& model, const Options& options, const std::string& engine) {
            py::gil_scoped_release release;
            return simulate(model, options, engine);
        },
        py::arg("model"), py::arg("options") = Options(), py::arg("engine") = "sinew",
        "Passive forward simulation from the default pose under gravity and the wires (what `sinew simulate` "
        "runs): engine 'sinew' (assembly-disassembly dynamics) or 'simbody'.");
}

}  // namespace sinew::python

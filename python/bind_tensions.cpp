// Wire tensions from motion: one frame (tools/tension_analysis.hpp TensionAnalysis::calcFrame) and a whole
// motion (tools/tension_motion.hpp runTensionAnalysis, what `sinew tensions` runs).
#include <limits>
#include <memory>

#include "bindings.hpp"
#include "sinew/tools/tension_analysis.hpp"
#include "sinew/tools/tension_motion.hpp"

namespace sinew::python {
namespace {

// TensionAnalysis keeps a reference to its model; this owner keeps the model alive with it.
class OwnedTensionAnalysis {
public:
    OwnedTensionAnalysis(std::shared_ptr<Model> model, TensionAnalysisOptions options)
        : model_(std::move(model)), analysis_(*model_, std::move(options)) {}

    TensionFrame calcFrame(const Eigen::VectorXd& q, const Eigen::VectorXd& u, const Eigen::VectorXd& udot,
                           const std::optional<Eigen::MatrixXd>& linkForces) {
        checkSize(*model_, q, model_->getNumQ(), "q");
        checkSize(*model_, u, model_->getNumU(), "u");
        checkSize(*model_, udot, model_->getNumU(), "udot");
        return analysis_.calcFrame(q, u, udot, toLinkForces(*model_, linkForces));
    }
    TensionAnalysis& get() { return analysis_; }

private:
    std::shared_ptr<Model> model_;
    TensionAnalysis analysis_;
};

void bindOptions(py::module_& m) {
    py::class_<WireProblemOptions>(m, "WireProblemOptions")
        .def(py::init<>())
        .def_readwrite("torque_tolerance", &WireProblemOptions::torqueTolerance, "LP band per row, N m or N")
        .def_readwrite("wire_cost", &WireProblemOptions::wireCost)
        .def_readwrite("regularization", &WireProblemOptions::regularization);
    py::class_<ReserveActuator>(m, "ReserveActuator", "A generalized force on one DOF (OpenSim's CoordinateActuator).")
        .def(py::init([](std::string name, int dof, double optimalForce, double minControl, double maxControl) {
                 ReserveActuator reserve;
                 reserve.name = std::move(name);
                 reserve.dof = dof;
                 reserve.optimalForce = optimalForce;
                 reserve.minControl = minControl;
                 reserve.maxControl = maxControl;
                 return reserve;
             }),
             py::arg("name"), py::arg("dof"), py::arg("optimal_force") = 1.0,
             py::arg("min_control") = -std::numeric_limits<double>::infinity(),
             py::arg("max_control") = std::numeric_limits<double>::infinity())
        .def_readwrite("name", &ReserveActuator::name)
        .def_readwrite("dof", &ReserveActuator::dof)
        .def_readwrite("optimal_force", &ReserveActuator::optimalForce)
        .def_readwrite("min_control", &ReserveActuator::minControl)
        .def_readwrite("max_control", &ReserveActuator::maxControl);
    py::class_<TensionAnalysisOptions>(m, "TensionAnalysisOptions", "tools/tension_analysis.hpp's options.")
        .def(py::init<>())
        .def_readwrite("method", &TensionAnalysisOptions::method, "lp, qp, so, ipopt or a registered method")
        .def_readwrite("problem", &TensionAnalysisOptions::problem)
        .def_readwrite("max_tension", &TensionAnalysisOptions::maxTension, "(numWires) N; empty: each wire's own")
        .def_readwrite("min_activation", &TensionAnalysisOptions::minActivation)
        .def_readwrite("max_activation", &TensionAnalysisOptions::maxActivation)
        .def_readwrite("reserves", &TensionAnalysisOptions::reserves)
        .def_readwrite("use_muscle_physiology", &TensionAnalysisOptions::useMusclePhysiology)
        .def_readwrite("activation_exponent", &TensionAnalysisOptions::activationExponent)
        .def_readwrite("unactuated_threshold", &TensionAnalysisOptions::unactuatedThreshold);
    py::class_<TensionMotionOptions>(m, "TensionMotionOptions", "tools/tension_motion.hpp's options.")
        .def(py::init<>())
        .def_readwrite("analysis", &TensionMotionOptions::analysis)
        .def_readwrite("lowpass_cutoff_hz", &TensionMotionOptions::lowpassCutoffHz, "negative: no filtering")
        .def_readwrite("start_time", &TensionMotionOptions::startTime)
        .def_readwrite("final_time", &TensionMotionOptions::finalTime)
        .def_readwrite("accelerations_from_speed_splines", &TensionMotionOptions::accelerationsFromSpeedSplines)
        .def_readwrite("contact", &TensionMotionOptions::contact);
}

void bindResults(py::module_& m) {
    py::enum_<DistributionStatus>(m, "DistributionStatus")
        .value("Optimal", DistributionStatus::Optimal)
        .value("Infeasible", DistributionStatus::Infeasible)
        .value("Failed", DistributionStatus::Failed);
    py::class_<TensionFrame>(m, "TensionFrame", "One frame's tensions, residuals and solver figures (a copy).")
        .def_readonly("status", &TensionFrame::status)
        .def_readonly("tau", &TensionFrame::tau)
        .def_readonly("tension", &TensionFrame::tension)
        .def_readonly("activation", &TensionFrame::activation)
        .def_readonly("reserve_force", &TensionFrame::reserveForce)
        .def_readonly("residual", &TensionFrame::residual)
        .def_readonly("reserve", &TensionFrame::reserve)
        .def_property_readonly("unactuated",
                               [](const TensionFrame& f) {
                                   py::array_t<bool> out(static_cast<py::ssize_t>(f.unactuated.size()));
                                   for (std::size_t i = 0; i < f.unactuated.size(); ++i)
                                       out.mutable_at(static_cast<py::ssize_t>(i)) = f.unactuated[i] != 0;
                                   return out;
                               })
        .def_readonly("torque_error", &TensionFrame::torqueError)
        .def_readonly("unactuated_residual", &TensionFrame::unactuatedResidual)
        .def_readonly("active_wires", &TensionFrame::activeWires)
        .def_readonly("iterations", &TensionFrame::iterations)
        .def_readonly("used_ipopt", &TensionFrame::usedIpopt);
    py::class_<TensionMotionResult>(m, "TensionMotionResult", "What `sinew tensions` writes, as StorageTables.")
        .def_readonly("tensions", &TensionMotionResult::tensions)
        .def_readonly("activations", &TensionMotionResult::activations)
        .def_readonly("reserves", &TensionMotionResult::reserves)
        .def_readonly("contact", &TensionMotionResult::contact)
        .def_readonly("joint_loads", &TensionMotionResult::jointLoads)
        .def_readonly("ligament_stress", &TensionMotionResult::ligamentStress)
        .def_readonly("report", &TensionMotionResult::report)
        .def_readonly("flagged_frames", &TensionMotionResult::flaggedFrames)
        .def_readonly("infeasible_frames", &TensionMotionResult::infeasibleFrames)
        .def_readonly("failed_frames", &TensionMotionResult::failedFrames)
        .def_readonly("ipopt_frames", &TensionMotionResult::ipoptFrames)
        .def_readonly("missing_rows", &TensionMotionResult::missingRows)
        .def_readonly("frame_seconds", &TensionMotionResult::frameSeconds);
    py::class_<TensionMotionSummary>(m, "TensionMotionSummary")
        .def_readonly("frames", &TensionMotionSummary::frames)
        .def_readonly("solved_frames", &TensionMotionSummary::solvedFrames)
        .def_readonly("median_seconds", &TensionMotionSummary::medianSeconds)
        .def_readonly("mean_seconds", &TensionMotionSummary::meanSeconds)
        .def_readonly("median_z", &TensionMotionSummary::medianZ)
        .def_readonly("mean_z", &TensionMotionSummary::meanZ)
        .def_readonly("max_z", &TensionMotionSummary::maxZ)
        .def_readonly("contact_frames", &TensionMotionSummary::contactFrames)
        .def_readonly("body_weight", &TensionMotionSummary::bodyWeight)
        .def_readonly("median_root_residual", &TensionMotionSummary::medianRootResidual)
        .def_readonly("max_root_residual", &TensionMotionSummary::maxRootResidual);
}

}  // namespace

void bindTensions(py::module_& m) {
    bindOptions(m);
    bindResults(m);
    py::class_<OwnedTensionAnalysis>(m, "TensionAnalysis",
                                     "One analysis per motion: inverse dynamics, the frame's problem and the "
                                     "method's solver, warm-started from frame to frame.")
        .def(py::init<std::shared_ptr<Model>, TensionAnalysisOptions>(), py::arg("model"),
             py::arg("options") = TensionAnalysisOptions())
        .def("calc_frame", &OwnedTensionAnalysis::calcFrame, py::arg("q"), py::arg("u"), py::arg("udot"),
             py::arg("link_forces") = py::none(),
             "One frame: q (nq), u and udot (nu), measured loads as link_forces (numLinks x 6).")
        .def("reset", [](OwnedTensionAnalysis& a) { a.get().reset(); }, "The next frame starts cold.")
        .def_property_readonly("solves_activations", [](OwnedTensionAnalysis& a) { return a.get().solvesActivations(); });

    m.def(
        "run_tension_analysis",
        [](const Model& model, const StorageTable& motion, const ExternalLoads* loads, const TensionMotionOptions& options) {
            py::gil_scoped_release release;
            return runTensionAnalysis(model, motion, loads, options);
        },
        py::arg("model"), py::arg("motion"), py::arg("external_loads") = nullptr,
        py::arg("options") = TensionMotionOptions(),
        "Tensions per frame of a coordinates table, processed as OpenSim's tools process it (what `sinew "
        "tensions` runs). Read the motion with allow_non_finite=True to keep rows with gaps.");
    m.def("summarize_tension_motion", &summarizeTensionMotion, py::arg("model"), py::arg("result"));
}

}  // namespace sinew::python

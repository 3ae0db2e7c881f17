#include "sinew/plugin/simbody_simulation.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "sinew/core/error.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/plugin/simbody_model.hpp"

namespace sinew {
namespace {

std::string formatNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

// Simbody refuses a body whose inertia about its origin, I_com + m (|c|^2 1 - c c^T), no longer holds the
// central inertia in double precision (MassProperties checks the shift back). Names the link where that
// loss is worst, or passes Simbody's own words on (first line only) when no link is suspect.
std::string describeSimbodyRefusal(const Model& model, const std::exception& e) {
    int worst = -1;
    double worstRatio = 0;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Link& link = model.getLink(i);
        if (link.isVirtual || link.mass <= 0) continue;
        const double smallest =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(link.inertia_Bcom, Eigen::EigenvaluesOnly).eigenvalues()[0];
        const double ratio = link.mass * link.com_B.squaredNorm() / std::max(smallest, 1e-300);
        if (ratio > worstRatio) worstRatio = ratio, worst = i;
    }
    if (worst >= 0 && worstRatio > 1e8) {
        const Link& link = model.getLink(worst);
        return "link '" + link.name + "': Simbody cannot represent its mass properties: the mass centre lies " +
               formatNumber(link.com_B.norm()) + " m from the link origin, so m |c|^2 = " +
               formatNumber(link.mass * link.com_B.squaredNorm()) + " kg m^2 swamps its central inertia (" +
               formatNumber(worstRatio) + " times its smallest principal moment); check the link's com and inertia";
    }
    std::string what = e.what();
    const std::size_t detail = what.find("Error detected by Simbody method");
    if (detail != std::string::npos) what = what.substr(detail);
    return "Simbody refused the model '" + model.getName() + "': " + what.substr(0, what.find('\n'));
}

}  // namespace

SimulationSummary simulateForward(const Model& model, const ForwardSimulationOptions& options,
                                  const std::function<void(const SimulationFrame&)>& onFrame) {
    const long numReports = checkSimulationOptions(options);

    SimbodyModelOptions systemOptions;
    systemOptions.hangBy = options.hangBy;
    std::optional<SimbodyModel> built;
    std::optional<SimTK::State> initial;
    try {
        built.emplace(model, systemOptions);
        initial.emplace(built->makeDefaultState(options.accuracy * 1e-3));
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(describeSimbodyRefusal(model, e));
    }
    const SimbodyModel& simbody = *built;
    const SimTK::MultibodySystem& system = simbody.getSystem();
    SimTK::State& state = *initial;
    if (options.initialSpeeds.size() > 0) {
        if (options.initialSpeeds.size() != model.getNumU())
            throw Error("initial speeds need " + std::to_string(model.getNumU()) + " values");
        state.updU() = toSimTK(options.initialSpeeds.head(state.getNU()));  // virtual links' speeds follow
        system.realize(state, SimTK::Stage::Velocity);
        system.projectU(state, options.accuracy * 1e-3);
    }

    SimTK::RungeKuttaMersonIntegrator integrator(system);
    integrator.setAccuracy(options.accuracy);
    integrator.setConstraintTolerance(options.accuracy);
    const bool adaptive = options.integrator == ForwardSimulationOptions::Integrator::Adaptive;
    // No setMinimumStepSize: at its minimum Simbody's integrator accepts steps that fail the error test,
    // silently; the loop below stops instead when the step it predicts falls below options.minStep.
    if (!adaptive) {
        // Equal steps no longer than fixedStep that land on the report times, as sinew's engine takes them.
        integrator.setFixedStepSize(options.reportInterval /
                                    std::max(1.0, std::ceil(options.reportInterval / options.fixedStep - 1e-9)));
    }
    SimTK::TimeStepper stepper(system, integrator);
    stepper.initialize(state);

    // The hung link's origin at the default pose, where the weld holds it, for the constraint violation.
    const int hangLink = options.hangBy.empty() ? -1 : model.findLinkIndex(options.hangBy);
    Data kinematics(model);
    calcPositionKinematics(model, kinematics, model.getDefaultQ());
    const Eigen::Vector3d p_GH =
        hangLink >= 0 ? kinematics.p_GB[static_cast<std::size_t>(hangLink)] : Eigen::Vector3d::Zero();

    SimulationSummary summary;
    SimulationFrame frame;
    auto report = [&](const SimTK::State& s) {
        system.realize(s, SimTK::Stage::Dynamics);
        frame.time = s.getTime();
        simbody.calcCoordinates(s, frame.q, frame.u);
        frame.tensions = simbody.calcWireTensions(s);
        if (const VirtualLinkWireForce* forks = simbody.getVirtualLinkWireForce())
            summary.maxVirtualLinkResidual =
                recordVirtualLinkResidual(summary.maxVirtualLinkResidual, forks->getEquilibrium().status, frame.time);
        summary.maxConstraintViolation = std::max(summary.maxConstraintViolation,
                                                  calcConstraintViolation(model, kinematics, frame.q, hangLink, p_GH));
        frame.kineticEnergy = system.calcKineticEnergy(s);
        frame.potentialEnergy = system.calcPotentialEnergy(s);
        const double energy = frame.kineticEnergy + frame.potentialEnergy;
        if (summary.frames == 0) summary.initialEnergy = energy;
        if (!std::isfinite(energy) || !frame.q.allFinite())
            throw Error("simulation diverged at t = " + formatNumber(frame.time) + " s (non-finite state)");
        summary.maxEnergyDrift = std::max(summary.maxEnergyDrift, std::abs(energy - summary.initialEnergy));
        summary.peakKineticEnergy = std::max(summary.peakKineticEnergy, frame.kineticEnergy);
        ++summary.frames;
        onFrame(frame);
    };

    const auto start = std::chrono::steady_clock::now();
    report(integrator.getState());
    for (long i = 1; i <= numReports; ++i) {
        const double t = getReportTime(options, i);
        // The step limit counts per stepTo call: what is left of the budget, re-armed after a partial return.
        while (integrator.getTime() < t) {
            const long left = options.maxSteps - integrator.getNumStepsAttempted();
            if (left <= 0)
                throw Error("simulation stopped at t = " + formatNumber(integrator.getTime()) +
                            " s: the step budget (--max-steps " + std::to_string(options.maxSteps) +
                            ") ran out; the model may be too stiff (check its stiffnesses, damping and masses) or "
                            "--max-steps too small");
            // Control comes back every kCheckSteps steps at most, to look at the step size.
            constexpr long kCheckSteps = 1000;
            integrator.setInternalStepLimit(static_cast<int>(std::min(left, kCheckSteps)));
            try {
                stepper.stepTo(t);
            } catch (const std::exception&) {
                // Simbody's message names its own source lines; the user needs the time and what to change.
                throw Error("simulation stopped at t = " + formatNumber(integrator.getTime()) +
                            " s: the integrator failed before t = " + formatNumber(t) +
                            " s (its step size underflowed or the state became non-finite); the model may be too stiff or diverging (check "
                            "its stiffnesses, damping, masses and wire points)");
            }
            if (adaptive && integrator.getPredictedNextStepSize() < options.minStep)
                throw Error("simulation stopped at t = " + formatNumber(integrator.getTime()) +
                            " s: the step size collapsed to " + formatNumber(integrator.getPredictedNextStepSize()) +
                            " s (below --min-step " + formatNumber(options.minStep) +
                            " s); the model may be too stiff or diverging (check its stiffnesses, damping, masses "
                            "and wire points)");
        }
        report(integrator.getState());
    }
    summary.steps = integrator.getNumStepsTaken();
    summary.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return summary;
}

}  // namespace sinew

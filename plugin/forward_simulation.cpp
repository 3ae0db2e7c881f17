#include "sinew/simbody/forward_simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/simbody/simbody_model.hpp"

namespace sinew {

SimulationSummary simulateForward(const Model& model, const ForwardSimulationOptions& options,
                                  const std::function<void(const SimulationFrame&)>& onFrame) {
    if (!(options.duration > 0) || !(options.reportInterval > 0) || !(options.accuracy > 0))
        throw Error("simulation needs duration, report interval and accuracy > 0");
    requireNoCouplers(model, "the Simbody forward simulation");

    SimbodyModelOptions systemOptions;
    systemOptions.hangBy = options.hangBy;
    const SimbodyModel simbody(model, systemOptions);
    const SimTK::MultibodySystem& system = simbody.getSystem();
    SimTK::State state = simbody.makeDefaultState(options.accuracy * 1e-3);
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
    if (options.integrator == ForwardSimulationOptions::Integrator::RungeKutta4Fixed) {
        if (!(options.fixedStep > 0)) throw Error("the fixed-step integrator needs a step > 0");
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
            throw Error("simulation diverged at t = " + std::to_string(frame.time) + " s (non-finite state)");
        summary.maxEnergyDrift = std::max(summary.maxEnergyDrift, std::abs(energy - summary.initialEnergy));
        summary.peakKineticEnergy = std::max(summary.peakKineticEnergy, frame.kineticEnergy);
        ++summary.frames;
        onFrame(frame);
    };

    const auto start = std::chrono::steady_clock::now();
    report(integrator.getState());
    const int numReports = static_cast<int>(std::floor(options.duration / options.reportInterval + 1e-9));
    for (int i = 1; i <= numReports; ++i) {
        const double t = std::min(options.duration, i * options.reportInterval);
        try {
            stepper.stepTo(t);
        } catch (const std::exception& e) {
            throw Error("integration failed before t = " + std::to_string(t) + " s: " + e.what());
        }
        report(integrator.getState());
    }
    summary.steps = integrator.getNumStepsTaken();
    summary.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return summary;
}

}  // namespace sinew

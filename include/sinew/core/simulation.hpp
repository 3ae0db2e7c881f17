#pragma once
// What a forward simulation is asked and what it reports, independent of the engine that runs it: sinew's
// own (core/forward_simulation.hpp, assembly-disassembly dynamics) or Simbody's (plugin/simbody_simulation.hpp).
// The same options give both engines the same problem, so their trajectories can be compared frame by frame.
#include <Eigen/Core>
#include <string>

namespace sinew {

struct ForwardSimulationOptions {
    enum class Integrator {
        // Error-controlled: Dormand-Prince 5(4) in sinew's engine, Runge-Kutta-Merson in Simbody's.
        Adaptive,
        // Fourth-order Runge-Kutta at a fixed step (sinew: the classic RK4; Simbody: Runge-Kutta-Merson with
        // its error control off). Each report interval is split into equal steps no longer than fixedStep.
        RungeKutta4Fixed
    };

    std::string hangBy;            // link welded to ground at its initial pose; empty for none
    double duration = 1.0;         // s
    double reportInterval = 0.01;  // s between output frames
    Integrator integrator = Integrator::Adaptive;
    double accuracy = 1e-6;    // relative accuracy of the adaptive integrator; also the constraint tolerance
    double fixedStep = 1e-3;   // s, the step of RungeKutta4Fixed
    Eigen::VectorXd initialSpeeds;  // u at t = 0 (nu), projected onto the loop constraints; empty: at rest
    // Budgets, so that a stiff or diverging model stops with a message naming the time instead of running
    // for hours: integrator steps attempted in all (rejected ones included), and the shortest adaptive step.
    long maxSteps = 1000000;
    double minStep = 1e-12;  // s
};

// At most this many output frames (each holds q, u and every wire's tension).
constexpr long kMaxSimulationFrames = 1000000;

const char* toString(ForwardSimulationOptions::Integrator integrator);

struct SimulationFrame {
    double time = 0;           // s
    Eigen::VectorXd q;         // nq
    Eigen::VectorXd u;         // nu
    Eigen::VectorXd tensions;  // N, per wire
    double kineticEnergy = 0;    // J
    double potentialEnergy = 0;  // J, gravity (-m g . p_com, Simbody's datum) plus conservative wire laws
};

struct SimulationSummary {
    int frames = 0;
    int steps = 0;                // integrator steps taken (accepted)
    // sinew's adaptive integrator: wire switches (a wire going slack or taut) located and stepped across.
    int wireSwitches = 0;
    double wallSeconds = 0;       // integration and reporting, not system construction
    double initialEnergy = 0;     // J
    double maxEnergyDrift = 0;    // J, max |E(t) - E(0)| over the reported frames
    double peakKineticEnergy = 0;  // J, scale for the drift
    // m, max over the reported frames of the position-constraint violation (calcConstraintViolation): how far
    // the loops and the hang have drifted open. Simbody projects it below the constraint tolerance; sinew's
    // engine holds the constraints at acceleration level, so it grows with the integration error.
    double maxConstraintViolation = 0;
    // N, max over the reported frames of the virtual links' equilibrium residual
    // (VirtualLinkEquilibriumStatus::residual): 0 to roundoff unless a damped wire's tension jumps as it goes
    // taut (no exact equilibrium then; the solve stops at the smallest residual it finds).
    double maxVirtualLinkResidual = 0;
};

}  // namespace sinew

#pragma once
// Forward simulation with sinew's own engine: the assembly-disassembly forward dynamics (forward_dynamics.hpp)
// under gravity and the wires' force laws, integrated by a Runge-Kutta method of sinew's own. Simbody-free;
// the same options run Simbody's engine through sinew/plugin/simbody_simulation.hpp.
#include <Eigen/Core>
#include <functional>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/simulation.hpp"

namespace sinew {

// Integrates the state (q, u) from the model's default pose with zero generalized forces: udot from
// calcForwardDynamics, qdot from u (quaternions: dq/dt = 1/2 [0; w_FM in F] * q, renormalised after every step;
// free-joint translations: dp_FM/dt = v_FM). Calls onFrame for t = 0 and every reportInterval up to duration.
//
// The loops and the hang (options.hangBy welds that link to ground where it is at t = 0) are imposed at
// acceleration level, as calcForwardDynamics does, and not projected: the position and velocity constraints
// drift with the integration error, which SimulationSummary::maxConstraintViolation reports. Initial speeds
// are projected onto the velocity constraints (least squares, unweighted).
//
// Integrators: Adaptive is Dormand-Prince 5(4) (Hairer, Norsett and Wanner, Solving ODEs I, 2nd ed., sec.
// II.4-5, Table 5.2), accepting a step when the RMS over q and u of err_i / (accuracy (1 + |y_i|)) is <= 1.
// A wire going slack or taut is a kink in the forces (a jump, with damping) that costs any Runge-Kutta
// method its order and misleads its error estimate, so when the set of pulling wires changes inside a step,
// the switch is located on the step's dense output, the step redone to just before it and the switch
// crossed by an Euler step of 1e-9 of the step (SimulationSummary::wireSwitches counts them).
// RungeKutta4Fixed is the classic fourth-order method, blind to switches. Both land exactly on the report
// times.
//
// Virtual links are not integrated: each evaluation puts them in quasi-static equilibrium under their wires
// (calcVirtualLinkEquilibrium, warm-started from the last accepted state), and their entries of q and u in
// the frames are that equilibrium's poses and twists (SimulationSummary::maxVirtualLinkResidual reports how
// well it held); the forward dynamics leaves them out.
//
// Throws sinew::Error for an unknown (or virtual) hang link, bad options, or a non-finite state, naming the
// time.
SimulationSummary simulateForwardSinew(const Model& model, const ForwardSimulationOptions& options,
                                       const std::function<void(const SimulationFrame&)>& onFrame);

// The report times of a run are t_i = min(i * reportInterval, duration), i = 0..n, the last exactly at
// `duration` (0.015 s at an interval of 0.01 s reports 0, 0.01, 0.015). Returns n, after checking the
// options both engines share: duration, interval, accuracy, step and budgets finite and > 0, at most
// kMaxSimulationFrames frames, an interval the times can resolve. Throws sinew::Error naming the option.
long checkSimulationOptions(const ForwardSimulationOptions& options);
double getReportTime(const ForwardSimulationOptions& options, long i);

// Largest position-constraint violation at q, m: over the loops the gap |p_A - p_B| between the two loop
// points, over the couplers |q_dep - s f(q_ind)| and the locked coordinates |q - default| (rad or m), and
// for hangLink >= 0 the distance of that link's origin from p_GH, where it was hung. Runs
// calcPositionKinematics into `data`.
double calcConstraintViolation(const Model& model, Data& data, const Eigen::VectorXd& q, int hangLink = -1,
                               const Eigen::Vector3d& p_GH = Eigen::Vector3d::Zero());

}  // namespace sinew

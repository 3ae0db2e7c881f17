#pragma once
// The solver of OpenSim's static optimization problem once it is in activations (every row exact, weights
// p, WireVariables::Activation in tension_method_registry.hpp):
//
//     min Σ_j weight_j / p |x_j|^p   s.t.  A x = tau,  lower <= x <= upper,  free variables unbounded.
//
// p = 2 (OpenSim's default) is the active-set QP (active_set_solver.hpp); other exponents p >= 1 (convex)
// are Ipopt (ipopt_solver.hpp), milliseconds per frame, whose frames with no x within the bounds are
// Infeasible with the phase-1 reserve and the least-squares answer (infeasible_frame.hpp).
#include <memory>

#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/ipopt_solver.hpp"
#include "sinew/tensions/tension_solver.hpp"

namespace sinew {

class StaticOptimizationSolver final : public TensionSolver {
public:
    // Throws sinew::Error for an exponent below 1 or not finite.
    explicit StaticOptimizationSolver(double exponent = 2, ActiveSetOptions options = {});

    void solve(const DistributionProblem& problem, DistributionResult& result) override;
    void reset() override { activeSet_.reset(); }

private:
    double exponent_;
    double infeasibilityTolerance_;
    ActiveSetSolver activeSet_;
    std::unique_ptr<IpoptSolver> ipopt_;  // p != 2
};

}  // namespace sinew

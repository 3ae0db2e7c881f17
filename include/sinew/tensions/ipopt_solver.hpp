#pragma once
// Ipopt (interior point, MUMPS) on a tension-distribution problem (docs/tensions.md, "Ipopt"):
//
//     min Σ_j weight_j / p |x_j|^p + ½ Σ_{tolerance rows} (tau - A x)_i²
//     s.t. (A x)_i = tau_i on equality rows, lower <= x <= upper on the bounded variables,
//
// free variables unbounded and costless. p = 2 is the active-set QP's problem (active_set_solver.hpp), which
// falls back on this solver when it fails; p != 2 is OpenSim's static optimization with its
// activation_exponent (static_optimization.hpp), convex for p >= 1. Slower than the active set (a cold
// interior-point solve per frame, milliseconds on a gait model), so it is the fallback, not the default.
#include <memory>

#include "sinew/tensions/distribution_problem.hpp"
#include "sinew/tensions/tension_solver.hpp"

namespace sinew {

struct IpoptSolverOptions {
    double tolerance = 1e-12;  // Ipopt's tol (scaled KKT error)
    int maxIterations = 3000;
    double exponent = 2;  // the cost exponent p of solve(problem, result)
};

// Not thread-safe: one per thread. Keeps one IpoptApplication.
class IpoptSolver final : public TensionSolver {
public:
    explicit IpoptSolver(IpoptSolverOptions options = {});
    ~IpoptSolver();
    IpoptSolver(const IpoptSolver&) = delete;
    IpoptSolver& operator=(const IpoptSolver&) = delete;

    // Solves `problem` (validated; throws sinew::Error when malformed, or when exponent < 1 or is not
    // finite) with cost exponent p = `exponent` into `result`: status Optimal, Infeasible (Ipopt found the
    // rows unreachable; result.reserve is left zero, the phase-1 LP gives it) or Failed; usedIpopt true;
    // x within the bounds; multipliers as the QP's (d objective / d tau; on tolerance rows the residual).
    void solve(const DistributionProblem& problem, double exponent, DistributionResult& result);
    // The same with the options' exponent.
    void solve(const DistributionProblem& problem, DistributionResult& result) override {
        solve(problem, exponent_, result);
    }
    // Every solve is cold (an interior point takes no warm start from the last frame).
    void reset() override {}

private:
    struct Backend;
    std::unique_ptr<Backend> backend_;
    double exponent_;
};

}  // namespace sinew

#pragma once
// One interface for every tension-distribution objective (docs/tensions.md): a solver turns one frame's
// DistributionProblem into a DistributionResult and may keep what it learnt (a basis, multipliers) as the
// next frame's warm start until reset(). The LP (lp_solver.hpp, the paper's Eq. 11-12), the active-set QP
// (active_set_solver.hpp, Eq. 14), Ipopt (ipopt_solver.hpp) and OpenSim's static optimization
// (static_optimization_solver.hpp) implement it; tension_method_registry.hpp names them.
#include "sinew/tensions/distribution_problem.hpp"

namespace sinew {

class TensionSolver {
public:
    virtual ~TensionSolver() = default;

    // Solves `problem` (validated; throws sinew::Error when malformed) into `result`, whose buffers are
    // reused from frame to frame.
    virtual void solve(const DistributionProblem& problem, DistributionResult& result) = 0;
    // The next solve starts cold.
    virtual void reset() = 0;
};

}  // namespace sinew

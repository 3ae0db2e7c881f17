#pragma once
// The LP tension distribution with Clp's dual simplex (docs/tensions.md, "The LP"):
//
//     min cost^T x   s.t.  tau - tolerance <= A x <= tau + tolerance (equality rows: A x = tau),
//                          lower <= x <= upper on the bounded variables, free variables unbounded.
//
// One solver per sequence of frames: it keeps its ClpSimplex and, while the sparsity pattern of A stays the
// same, replaces the matrix values, bounds and costs and re-solves from the previous frame's basis. An
// infeasible frame is followed by a phase-1 LP (min sum |reserve| with a free reserve on every row), whose
// answer says which rows (DOFs) lack muscle.
#include <memory>

#include "sinew/tensions/distribution_problem.hpp"

namespace sinew {

class LpSolver {
public:
    LpSolver();
    ~LpSolver();
    LpSolver(const LpSolver&) = delete;
    LpSolver& operator=(const LpSolver&) = delete;

    // Solves `problem` (validated; throws sinew::Error when malformed) into `result`. result.multipliers
    // are the row duals y (reduced costs cost - A^T y); x is within its bounds (Clp's answer, clamped).
    void solve(const DistributionProblem& problem, DistributionResult& result);
    // The next solve starts cold: a new ClpSimplex and an all-slack basis.
    void reset();

private:
    struct Backend;
    std::unique_ptr<Backend> backend_;
};

}  // namespace sinew

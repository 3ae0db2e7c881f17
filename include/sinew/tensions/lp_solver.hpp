#pragma once
// The LP tension distribution with Clp's dual simplex (docs/tensions.md, "The LP"; the paper's Eq. 11-12):
//
//     min cost^T x   s.t.  tau - tolerance <= A x <= tau + tolerance (equality rows: A x = tau),
//                          lower <= x <= upper on the bounded variables, free variables unbounded.
//
// One solver per sequence of frames: it keeps the previous frame's basis and, while the sizes of A stay the
// same, re-solves from it, first by its own warm dual simplex (warm_dual_simplex.hpp), which answers only an
// optimum it has proved, and otherwise by Clp from the same basis. An
// infeasible frame is followed by a phase-1 LP (min sum |reserve| with a free reserve on every row), whose
// answer says which rows (DOFs) lack muscle.
#include <memory>

#include "sinew/tensions/distribution_problem.hpp"
#include "sinew/tensions/tension_solver.hpp"

namespace sinew {

class LpSolver final : public TensionSolver {
public:
    LpSolver();
    ~LpSolver();
    LpSolver(const LpSolver&) = delete;
    LpSolver& operator=(const LpSolver&) = delete;

    // Solves `problem` (validated; throws sinew::Error when malformed) into `result`. result.multipliers
    // are the row duals y (reduced costs cost - A^T y); x is within its bounds (Clp's answer, clamped). An
    // infeasible frame gets phase 1's least (L1) reserves and, among the x that reach them, the least cost.
    void solve(const DistributionProblem& problem, DistributionResult& result) override;
    // The next solve starts cold: a new ClpSimplex and the all-slack basis with the free columns basic.
    void reset() override;
    // Frames since construction or reset that the warm path (WarmDualSimplex) solved without Clp.
    int getWarmFrames() const;

private:
    // Clp's dual simplex from the last frame's basis, phase 1 and the least-cost LP with reserves;
    // warmDualUnbounded: the warm path found the frame infeasible, so phase 1 goes first.
    void solveWithClp(const DistributionProblem& problem, DistributionResult& result, bool warmDualUnbounded);
    void solveWithReserves(const DistributionProblem& problem, const Eigen::VectorXd& reserve, DistributionResult& result);

    struct Backend;
    std::unique_ptr<Backend> backend_;
    DistributionProblem withReserves_;  // an infeasible frame's problem with its reserves taken off tau
};

// The phase-1 LP alone: min Σ|reserve_i| over x within its bounds such that every row of A x + reserve is
// within its band (equality rows exact). reserve (rows) is then the smallest (L1) generalized force per row
// that makes `problem` feasible, zero when it is; x a point that reaches it. Adds Clp's pivots to
// `iterations`; false when Clp fails.
bool solvePhaseOneLp(const DistributionProblem& problem, Eigen::VectorXd& x, Eigen::VectorXd& reserve,
                     int& iterations);

}  // namespace sinew

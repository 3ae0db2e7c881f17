#pragma once
// The LP's warm path (docs/tensions.md, "The warm path"): a bounded dual simplex that re-solves
//
//     min cost^T x   s.t.  rowLower <= A x <= rowUpper,  columnLower <= x <= columnUpper
//
// from the previous frame's optimal basis. A motion's consecutive frames change A, the bounds and the costs a
// little, so that basis is a few dual pivots from optimal (9 on the whole-body benchmark). Clp pays a fresh
// set-up for each frame (scaling, the row copy, a factorisation at the start and another at the end): six
// times the pivots' work. This path keeps nothing but the basis: it factorises the basis matrix with KLU
// (sparse LU, SuiteSparse), moves the variables whose reduced costs the frame turned to their other bounds
// (artificial ones where they have none), and pivots on the unscaled problem with product-form updates and
// the bound-flipping ratio test. It answers only a basis it has proved optimal (primal and dual feasible to
// its tolerances, with values and reduced costs recomputed from the factors, no variable at an artificial
// bound). Anything else (an infeasible frame, a singular basis, an optimum at an artificial bound, more
// pivots than allowed) is left to Clp: the outcome says why, and the caller's basis is then unchanged.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace sinew {

// Clp's basis status codes (ClpSimplex::Status), in which LpSolver keeps its warm basis: one per column, then
// one per row (the row's activity variable).
enum class SimplexStatus : unsigned char { Free = 0, Basic = 1, AtUpper = 2, AtLower = 3, SuperBasic = 4, Fixed = 5 };

// The LP's data; bounds beyond ±1e30 are infinite. The arrays must outlive the solve.
struct LinearProgram {
    const Eigen::SparseMatrix<double>* A = nullptr;  // compressed, column-major
    const double* columnLower = nullptr;
    const double* columnUpper = nullptr;
    const double* cost = nullptr;
    const double* rowLower = nullptr;
    const double* rowUpper = nullptr;
};

struct WarmDualSimplexOptions {
    int maxPivots = 500;     // past this Clp takes over: its pricing is better on long runs
    int refactorEvery = 30;  // product-form updates before the basis is factorised afresh
    // Absolute tolerances, in the problem's units (newtons and newton metres for tensions): a basic variable
    // may be this far beyond a bound, a reduced cost this far on the wrong side of zero.
    double primalTolerance = 1e-9;
    double dualTolerance = 1e-9;
};

enum class WarmDualOutcome {
    Optimal,          // proved optimal: values and duals are set, the status array holds the optimal basis
    NoBasis,          // the status array is no basis of this problem (sizes, counts, superbasic variables), or
                      // A is not compressed
    NotDualFeasible,  // the optimum leaves an unbounded variable at the artificial bound that its reduced
                      // cost sent it to (the basis was not dual feasible, and no real bound mends it)
    DualUnbounded,    // no entering variable: the frame is primal infeasible
    Singular,         // the basis matrix is singular or too ill-conditioned
    TooManyPivots     // maxPivots reached
};

const char* toString(WarmDualOutcome outcome);

class BasisFactor;  // KLU's factors of the basis matrix and their product-form updates (warm_dual_simplex.cpp)

class WarmDualSimplex {
public:
    WarmDualSimplex();
    ~WarmDualSimplex();
    WarmDualSimplex(const WarmDualSimplex&) = delete;
    WarmDualSimplex& operator=(const WarmDualSimplex&) = delete;

    // Re-solves `lp` from `status` (columns then rows, Clp's codes). On Optimal, `status` becomes the optimal
    // basis; otherwise it is left as it was.
    WarmDualOutcome solve(const LinearProgram& lp, std::vector<unsigned char>& status,
                          const WarmDualSimplexOptions& options = {});

    const Eigen::VectorXd& getColumnValues() const { return columnValues_; }
    // y with reduced costs cost - A^T y (Clp's row duals: > 0 holds a row at its lower bound).
    const Eigen::VectorXd& getRowDuals() const { return rowDuals_; }
    int getPivots() const { return pivots_; }

private:
    std::unique_ptr<BasisFactor> factor_;
    Eigen::VectorXd columnValues_, rowDuals_;
    int pivots_ = 0;
};

}  // namespace sinew

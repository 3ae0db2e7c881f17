#pragma once
// One frame of the tension-distribution problem (docs/tensions.md): generalized forces tau (rows: DOFs,
// and any extra equilibrium rows) to be produced by many more variables than rows,
//
//     A x ≈ tau,   x = [bounded (wire tensions, activations, reserves); free (loop forces ...)],
//
// where column j of A is the generalized force per unit of variable j (for wires A = -J^T, the sign of
// docs/wire-jacobian.md). Rows are either tolerance rows (the LP keeps them within ±tolerance, the QP puts
// them in its least-squares error) or equality rows (virtual-link equilibrium, static optimization).
// The solvers (lp_solver.hpp, active_set_solver.hpp) read it and fill a DistributionResult.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace sinew {

struct DistributionProblem {
    // (rows x (numBounded + numFree)), column-major and compressed; bounded columns first. A solver keeps
    // its warm start while the sparsity pattern stays the same (explicit zeros are fine).
    Eigen::SparseMatrix<double> A;
    int numFree = 0;  // the last numFree columns are unbounded and cost nothing (loop forces, ...)
    Eigen::VectorXd lower, upper;  // (numBounded) bounds on the bounded variables; ±infinity allowed
    Eigen::VectorXd cost;          // (numBounded) LP cost per unit, >= 0 for a bounded LP
    // (numBounded) > 0: the QP's weights, objective ½ Σ weight_j x_j² (+ ½ |tau - A x|² over the
    // tolerance rows). Small for least squares (the regulariser that makes the answer unique); 2 for
    // static optimization in activations (Σ a²).
    Eigen::VectorXd weight;
    Eigen::VectorXd target;     // tau (rows)
    Eigen::VectorXd tolerance;  // (rows) LP band half-width delta >= 0 of the tolerance rows
    std::vector<bool> isEquality;  // (rows) true: A x = tau exactly in every method

    int getNumRows() const { return static_cast<int>(A.rows()); }
    int getNumVariables() const { return static_cast<int>(A.cols()); }
    int getNumBounded() const { return static_cast<int>(A.cols()) - numFree; }
};

// Throws sinew::Error naming the field (and index) that does not fit: sizes, NaN, lower > upper,
// weight <= 0, tolerance < 0, an uncompressed matrix.
void validateDistributionProblem(const DistributionProblem& problem);

enum class DistributionStatus {
    Optimal,     // KKT conditions met
    Infeasible,  // no x within the bounds meets the equality / tolerance rows; see DistributionResult::reserve
    Failed       // the solver stopped without an answer (iteration limit, numerical trouble)
};
const char* toString(DistributionStatus status);

// How far (x, multipliers) are from the optimality conditions, each relative to the problem's scale so
// that 1e-6 means six digits: primal = row and bound violations (rows beyond their band, relative to
// max(1, |tau|, |A||x|)); dual = the Lagrangian's projected gradient over the variables; complementarity
// = multipliers on rows that are not at the side of the band the multiplier's sign says.
struct KktResiduals {
    double primal = 0;
    double dual = 0;
    double complementarity = 0;
    double getMax() const;
};

struct DistributionResult {
    DistributionStatus status = DistributionStatus::Failed;
    Eigen::VectorXd x;            // (numVariables) never NaN; within the bounds
    Eigen::VectorXd multipliers;  // (rows) the row multipliers y: d(objective)/d(tau)
    Eigen::VectorXd residual;     // (rows) tau - A x
    double objective = 0;         // the method's objective
    double torqueError = 0;       // the paper's Z = ½ |tau - A x|² over all rows (Eq. 10)
    int activeVariables = 0;      // bounded variables off their lower bound (wires pulling)
    int iterations = 0;           // simplex pivots, or active-set (Newton) steps
    // The frame was solved by the Ipopt fallback (ipopt_solver.hpp) after the active-set solver failed, or
    // by Ipopt as the static optimization of an activation exponent other than 2.
    bool usedIpopt = false;
    KktResiduals kkt;
    // Infeasible frames: the smallest (L1) generalized force per row that, added to A x, makes the frame
    // feasible (phase-1 LP; for the QP and static optimization on the equality rows, zero on tolerance
    // rows): which DOF lacks muscle. Zero otherwise. (rows)
    Eigen::VectorXd reserve;
};

// Residuals of the LP  min cost^T x  s.t. rows within tau ± tolerance (equality rows exact), bounds, at
// (x, y), with reduced costs cost - A^T y.
KktResiduals calcLpKktResiduals(const DistributionProblem& problem, const Eigen::VectorXd& x,
                                const Eigen::VectorXd& y);
// Residuals of the QP  min ½ Σ weight (x - center)² + ½ |tau - A x|²_tolerance rows  s.t. equality rows,
// bounds, at (x, y); y on the tolerance rows is their residual by definition, only the equality rows' y are
// read. center (numBounded; empty: 0) is a proximal step's (ActiveSetOptions::proximalSteps).
KktResiduals calcQpKktResiduals(const DistributionProblem& problem, const Eigen::VectorXd& x,
                                const Eigen::VectorXd& y, const Eigen::VectorXd& center = Eigen::VectorXd());

// Fills residual, torqueError and activeVariables of `result` from result.x.
void calcResultSummary(const DistributionProblem& problem, DistributionResult& result);

}  // namespace sinew

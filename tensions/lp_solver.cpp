#include "sinew/tensions/lp_solver.hpp"

#include "sinew/tensions/warm_dual_simplex.hpp"

#include <ClpSimplex.hpp>
#include <CoinPackedMatrix.hpp>
#include <algorithm>
#include <cmath>
#include <vector>

namespace sinew {
namespace {

double toClp(double bound) { return std::max(-COIN_DBL_MAX, std::min(COIN_DBL_MAX, bound)); }

// Row and column bounds and costs of the problem, in Clp's terms.
struct LpArrays {
    std::vector<double> rowLower, rowUpper, columnLower, columnUpper, cost;

    void fill(const DistributionProblem& problem) {
        const int rows = problem.getNumRows(), columns = problem.getNumVariables();
        rowLower.resize(static_cast<std::size_t>(rows));
        rowUpper.resize(static_cast<std::size_t>(rows));
        for (int i = 0; i < rows; ++i) {
            const std::size_t ii = static_cast<std::size_t>(i);
            const double band = problem.isEquality[ii] ? 0 : problem.tolerance[i];
            rowLower[ii] = problem.target[i] - band;
            rowUpper[ii] = problem.target[i] + band;
        }
        columnLower.assign(static_cast<std::size_t>(columns), -COIN_DBL_MAX);
        columnUpper.assign(static_cast<std::size_t>(columns), COIN_DBL_MAX);
        cost.assign(static_cast<std::size_t>(columns), 0.0);
        for (int j = 0; j < problem.getNumBounded(); ++j) {
            const std::size_t jj = static_cast<std::size_t>(j);
            columnLower[jj] = toClp(problem.lower[j]);
            columnUpper[jj] = toClp(problem.upper[j]);
            cost[jj] = problem.cost[j];
        }
    }
};

void clampToBounds(const DistributionProblem& problem, Eigen::VectorXd& x) {
    for (int j = 0; j < problem.getNumBounded(); ++j) x[j] = std::min(std::max(x[j], problem.lower[j]), problem.upper[j]);
}

// Whether clamping x into its bounds would move a row by more than 1e-9 of tau's size: an answer kept to a
// solver's tolerance in some scaled space can end that far beyond a bound (see finishWithinBounds).
bool movesRowsWhenClamped(const DistributionProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& answer) {
    constexpr double kClampShift = 1e-9;
    Eigen::VectorXd clampMove = answer;
    clampToBounds(problem, clampMove);
    clampMove -= answer;
    const double size = std::max(1.0, problem.target.cwiseAbs().maxCoeff());
    return !clampMove.isZero() && (problem.A * clampMove).cwiseAbs().maxCoeff() > kClampShift * size;
}

// The cold start: Clp's all-slack basis with every free column (loop force) basic in place of the slack of
// the row, not yet taken, where the column's coefficient is largest. A nonbasic free column is given fake
// bounds (±dual bound, 1e10) by the dual simplex, which must then pivot it in through huge primal
// infeasibilities: on the whole-body benchmark this start cut the slowest of its 200 cold solves from 1,320
// pivots to 401 (mean 487 to 347, docs/tensions.md "Speed"). A singular choice is repaired by Clp's
// factorization, which puts slacks back.
void startFromSlacksAndFreeColumns(const DistributionProblem& problem, ClpSimplex& simplex,
                                   std::vector<char>& rowTaken) {
    simplex.allSlackBasis(true);
    rowTaken.assign(static_cast<std::size_t>(problem.getNumRows()), 0);
    for (int j = problem.getNumBounded(); j < problem.getNumVariables(); ++j) {
        int row = -1;
        double largest = 0;
        for (Eigen::SparseMatrix<double>::InnerIterator it(problem.A, j); it; ++it)
            if (!rowTaken[static_cast<std::size_t>(it.row())] && std::abs(it.value()) > largest)
                largest = std::abs(it.value()), row = static_cast<int>(it.row());
        if (row < 0) continue;  // a zero column: it stays nonbasic
        rowTaken[static_cast<std::size_t>(row)] = 1;
        simplex.setColumnStatus(j, ClpSimplex::basic);
        simplex.setRowStatus(row, ClpSimplex::atLowerBound);
    }
}

// A reserve's cost per unit in phase 1: an equality row (a virtual link's equilibrium) is no generalized
// force any actuator could supply, so it is given up only where no tensions within the bounds hold it
// (the QP keeps it exact); at cost 1 the kick's LP left a virtual link 47 N out of balance to save a few
// N m of joint torque.
double calcReserveCost(const DistributionProblem& problem, int row) {
    constexpr double kEqualityReserveCost = 1e4;
    return problem.isEquality[static_cast<std::size_t>(row)] ? kEqualityReserveCost : 1.0;
}

// Phase 1's x and reserve from Clp's solution; false when the reserves' sum exceeds what x = 0 (within the
// bounds when every range holds 0) leaves: Clp's answer is then no minimum.
bool readPhaseOne(const DistributionProblem& problem, const LpArrays& arrays, const ClpSimplex& simplex,
                  Eigen::VectorXd& x, Eigen::VectorXd& reserve) {
    const int rows = problem.getNumRows(), columns = problem.getNumVariables();
    const double* solution = simplex.getColSolution();
    x = Eigen::Map<const Eigen::VectorXd>(solution, columns);
    reserve = Eigen::Map<const Eigen::VectorXd>(solution + columns, rows) -
              Eigen::Map<const Eigen::VectorXd>(solution + columns + rows, rows);
    bool zeroWithinBounds = true;
    for (int j = 0; j < columns; ++j)
        zeroWithinBounds &= arrays.columnLower[static_cast<std::size_t>(j)] <= 0 && arrays.columnUpper[static_cast<std::size_t>(j)] >= 0;
    if (!zeroWithinBounds || !x.allFinite() || !reserve.allFinite()) return x.allFinite() && reserve.allFinite();
    double atZero = 0, needed = 0;
    for (int i = 0; i < rows; ++i) {
        const double cost = calcReserveCost(problem, i);
        atZero += cost * std::max({0.0, arrays.rowLower[static_cast<std::size_t>(i)], -arrays.rowUpper[static_cast<std::size_t>(i)]});
        needed += cost * std::abs(reserve[i]);
    }
    return needed <= atZero * (1 + 1e-6) + 1e-9;
}

// The phase-1 LP: min sum(c_i (s+ + s-)) over x within its bounds and s+, s- >= 0 with
// tau - tolerance <= A x + s+ - s- <= tau + tolerance. Returns false when Clp fails; the reserve is s+ - s-.
// warmBasis (may be null): Clp's status array of an earlier phase 1 of the same size to start from (a
// motion's infeasible frames come in runs); given back with this one's optimal basis, or emptied.
bool solvePhaseOne(const DistributionProblem& problem, const LpArrays& arrays, Eigen::VectorXd& x,
                   Eigen::VectorXd& reserve, int& iterations, std::vector<unsigned char>* warmBasis = nullptr) {
    const int rows = problem.getNumRows(), columns = problem.getNumVariables();
    const Eigen::SparseMatrix<double>& A = problem.A;
    std::vector<int> starts(A.outerIndexPtr(), A.outerIndexPtr() + columns + 1);
    std::vector<int> indices(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    std::vector<double> values(A.valuePtr(), A.valuePtr() + A.nonZeros());
    std::vector<double> columnLower = arrays.columnLower, columnUpper = arrays.columnUpper;
    std::vector<double> cost(static_cast<std::size_t>(columns), 0.0);
    for (const double sign : {1.0, -1.0}) {
        for (int i = 0; i < rows; ++i) {
            indices.push_back(i);
            values.push_back(sign);
            starts.push_back(static_cast<int>(indices.size()));
            columnLower.push_back(0);
            columnUpper.push_back(COIN_DBL_MAX);
            cost.push_back(calcReserveCost(problem, i));
        }
    }
    ClpSimplex simplex;
    const auto load = [&] {
        simplex = ClpSimplex();
        simplex.setLogLevel(0);
        simplex.loadProblem(columns + 2 * rows, rows, starts.data(), indices.data(), values.data(), columnLower.data(),
                            columnUpper.data(), cost.data(), arrays.rowLower.data(), arrays.rowUpper.data());
    };
    const std::size_t statuses = static_cast<std::size_t>(columns + 3 * rows);
    const auto succeeded = [&] {
        if (simplex.status() != 0 || !readPhaseOne(problem, arrays, simplex, x, reserve)) return false;
        if (warmBasis) warmBasis->assign(simplex.statusArray(), simplex.statusArray() + statuses);
        return true;
    };
    // From the last phase 1's basis the kick's runs of infeasible frames take a median of 71 pivots against
    // 306 cold, but a few stall on degeneracy (up to 6,000): past `rows` pivots the cold start takes over,
    // in a fresh simplex (a capped Clp's perturbed state is no start, see LpSolver::Backend::run).
    if (warmBasis && warmBasis->size() == statuses) {
        load();
        simplex.copyinStatus(warmBasis->data());
        simplex.setMaximumIterations(rows);
        simplex.dual();
        iterations += simplex.numberIterations();
        if (succeeded()) return true;
    }
    if (warmBasis) warmBasis->clear();
    load();
    std::vector<char> rowTaken;
    startFromSlacksAndFreeColumns(problem, simplex, rowTaken);  // x's columns keep their indices
    simplex.dual();
    if (simplex.status() != 0) simplex.primal();
    iterations += simplex.numberIterations();
    if (succeeded()) return true;
    // Clp has called a phase 1 optimal whose reserves exceed those of x = 0 (1e8 N m against the kick's
    // few hundred, with the free loop columns and unbounded contact forces): again from the slack basis,
    // without scaling, by the primal simplex.
    simplex.scaling(0);
    simplex.allSlackBasis(true);
    simplex.primal();
    iterations += simplex.numberIterations();
    return succeeded();
}

}  // namespace

bool solvePhaseOneLp(const DistributionProblem& problem, Eigen::VectorXd& x, Eigen::VectorXd& reserve,
                     int& iterations) {
    validateDistributionProblem(problem);
    LpArrays arrays;
    arrays.fill(problem);
    return solvePhaseOne(problem, arrays, x, reserve, iterations);
}

struct LpSolver::Backend {
    ClpSimplex simplex;
    LpArrays arrays;
    std::vector<unsigned char> basis;  // the last frame's final basis, Clp's status codes (empty: cold)
    std::vector<char> rowTaken;        // startFromSlacksAndFreeColumns's workspace
    std::vector<unsigned char> phaseOneBasis;  // the last phase 1's optimal basis
    bool lastInfeasible = false;               // the last frame's status
    WarmDualSimplex warm;
    std::vector<unsigned char> warmBasis;  // the warm path's copy of `basis`, kept only when it proves optimal
    int warmFrames = 0;

    Backend() { simplex.setLogLevel(0); }

    bool hasBasisFor(const DistributionProblem& problem) const {
        return basis.size() == static_cast<std::size_t>(problem.getNumRows() + problem.getNumVariables());
    }

    // Loads A, bounds and costs (arrays filled for `problem`), and gives Clp the last frame's basis when it
    // fits; else the cold start.
    void load(const DistributionProblem& problem) {
        const Eigen::SparseMatrix<double>& A = problem.A;
        simplex.loadProblem(static_cast<int>(A.cols()), static_cast<int>(A.rows()), A.outerIndexPtr(), A.innerIndexPtr(),
                            A.valuePtr(), arrays.columnLower.data(), arrays.columnUpper.data(), arrays.cost.data(),
                            arrays.rowLower.data(), arrays.rowUpper.data());
        if (hasBasisFor(problem)) simplex.copyinStatus(basis.data());
        else startFromSlacksAndFreeColumns(problem, simplex, rowTaken);
    }

    void keepClpBasis() {
        basis.assign(simplex.statusArray(), simplex.statusArray() + simplex.numberRows() + simplex.numberColumns());
    }

    // The warm path (docs/tensions.md): the last frame's basis re-solved by WarmDualSimplex, kept when it is
    // proved optimal and its answer lies within the bounds as Clp's finish requires; any other outcome
    // leaves the frame to Clp, from that same basis (NoBasis: not tried).
    WarmDualOutcome solveWarm(const DistributionProblem& problem, DistributionResult& result) {
        if (lastInfeasible || !hasBasisFor(problem)) return WarmDualOutcome::NoBasis;
        const LinearProgram lp{&problem.A, arrays.columnLower.data(), arrays.columnUpper.data(), arrays.cost.data(),
                               arrays.rowLower.data(), arrays.rowUpper.data()};
        warmBasis = basis;
        const WarmDualOutcome outcome = warm.solve(lp, warmBasis);
        if (outcome != WarmDualOutcome::Optimal) return outcome;
        if (movesRowsWhenClamped(problem, warm.getColumnValues())) return WarmDualOutcome::NoBasis;
        result.x = warm.getColumnValues();
        basis.swap(warmBasis);
        result.multipliers = warm.getRowDuals();
        result.iterations = warm.getPivots();
        ++warmFrames;
        return WarmDualOutcome::Optimal;
    }

    // Dual simplex from the current basis; on trouble (iteration limit, numerical errors) once more from
    // the cold start, then the primal simplex. Clp's status: 0 optimal, 1 infeasible, others failed. Each
    // try is capped at 20 pivots per row and column: a warm basis can stall the dual simplex on a degenerate
    // frame (two frames of a kick's re-fit, whose feet's force rows are exact, ran 1e6 pivots, 3 min each,
    // where the cold start takes 3,000 to 4,000).
    // After a capped try Clp's own state (its perturbed costs and bounds) is no start: the cold start reloads
    // the problem into a fresh simplex (reusing it returned "optimal" with Z = 3e37 on the re-fit's next frame).
    int run(const DistributionProblem& problem) {
        const int pivotCap = 20 * (simplex.numberRows() + simplex.numberColumns());
        simplex.setMaximumIterations(pivotCap);
        simplex.dual();
        if (simplex.status() <= 1) return finishWithinBounds(problem);
        simplex = ClpSimplex();
        simplex.setLogLevel(0);
        basis.clear();
        load(problem);
        simplex.setMaximumIterations(pivotCap);
        simplex.dual();
        if (simplex.status() > 1) simplex.primal();
        return finishWithinBounds(problem);
    }

    // Clp keeps the bounds to its primal tolerance (1e-7) in the scaled problem: a column scaled up for its
    // millimetre moment arms can end beyond a 1e6 N cap by millinewtons (5 mN at the kick's 3.917 s), and
    // clamping it back moved a virtual link 4 mN out of balance. Where clamping would move any row by more
    // than kClampShift of tau's size, the optimum is finished unscaled from its own basis, where the
    // tolerance is in newtons (3 to 170 primal pivots on the kick's three such frames); should that fail,
    // the scaled answer stands. Returns Clp's status.
    int finishWithinBounds(const DistributionProblem& problem) {
        if (simplex.status() != 0) return simplex.status();
        if (!movesRowsWhenClamped(problem, Eigen::Map<const Eigen::VectorXd>(simplex.primalColumnSolution(),
                                                                             problem.getNumVariables())))
            return 0;
        ClpSimplex unscaled(simplex);
        unscaled.scaling(0);
        unscaled.primal(1);  // a values pass: from the answer in hand
        if (unscaled.status() != 0) return 0;
        unscaled.scaling(simplex.scalingFlag());
        unscaled.setNumberIterations(simplex.numberIterations() + unscaled.numberIterations());
        simplex = unscaled;
        return 0;
    }
};

// Phase 1's x is any point that needs the least reserves, its tensions as large as the bounds allow (a wire
// at 1e6 N on the kick). With the reserves given (tau less them), the LP's own objective picks the least
// total tension among those points; the frame stays Infeasible, its reserves reported.
void LpSolver::solveWithReserves(const DistributionProblem& problem, const Eigen::VectorXd& reserve,
                                 DistributionResult& result) {
    withReserves_ = problem;
    withReserves_.target -= reserve;
    // Phase 1 meets the band's edges: a hair of slack so that roundoff leaves the shifted LP feasible.
    const double scale = std::max(1.0, problem.target.cwiseAbs().maxCoeff());
    withReserves_.tolerance.array() += 1e-9 * scale;
    backend_->arrays.fill(withReserves_);
    backend_->load(withReserves_);
    if (backend_->run(withReserves_) != 0) return;  // phase 1's x stands
    result.x = Eigen::Map<const Eigen::VectorXd>(backend_->simplex.primalColumnSolution(), problem.getNumVariables());
    result.iterations += backend_->simplex.numberIterations();
}

LpSolver::LpSolver() : backend_(std::make_unique<Backend>()) {}
LpSolver::~LpSolver() = default;

void LpSolver::reset() { backend_ = std::make_unique<Backend>(); }

int LpSolver::getWarmFrames() const { return backend_->warmFrames; }

void LpSolver::solve(const DistributionProblem& problem, DistributionResult& result) {
    validateDistributionProblem(problem);
    const int rows = problem.getNumRows();
    backend_->arrays.fill(problem);
    result.iterations = 0;
    result.usedIpopt = false;
    result.reserve.setZero(rows);
    result.multipliers.setZero(rows);
    result.status = DistributionStatus::Failed;
    const WarmDualOutcome warm = backend_->solveWarm(problem, result);
    if (warm == WarmDualOutcome::Optimal) {
        result.status = DistributionStatus::Optimal;
    } else {
        solveWithClp(problem, result, warm == WarmDualOutcome::DualUnbounded);
        backend_->keepClpBasis();
    }
    if (!result.x.allFinite()) result.x.setZero();
    if (!result.multipliers.allFinite()) result.multipliers.setZero();
    clampToBounds(problem, result.x);
    calcResultSummary(problem, result);
    result.objective = problem.cost.dot(result.x.head(problem.getNumBounded()));
    result.kkt = calcLpKktResiduals(problem, result.x, result.multipliers);
}

void LpSolver::solveWithClp(const DistributionProblem& problem, DistributionResult& result, bool warmDualUnbounded) {
    const int rows = problem.getNumRows(), columns = problem.getNumVariables();
    backend_->load(problem);
    const double scale = std::max(1.0, problem.target.cwiseAbs().maxCoeff());
    const auto needsReserves = [&](const Eigen::VectorXd& reserve) {
        return reserve.cwiseAbs().maxCoeff() > 1e-6 * scale;  // Clp's feasibility tolerance is 1e-7
    };
    Eigen::VectorXd reserve;
    // After an infeasible frame, phase 1 goes first, warm from that frame's: it proves the next of a run of
    // infeasible frames so in fewer pivots than the dual simplex takes to find it out.
    // So does it where the warm path's dual ran unbounded: Clp's dual simplex would find the same.
    bool infeasible = (backend_->lastInfeasible || warmDualUnbounded) &&
                      solvePhaseOne(problem, backend_->arrays, result.x, reserve, result.iterations, &backend_->phaseOneBasis) &&
                      needsReserves(reserve);
    int status = 1;
    if (!infeasible) {
        result.x.setZero(columns);
        status = backend_->run(problem);
        result.iterations += backend_->simplex.numberIterations();
        // Confirm with phase 1: a warm-started dual simplex may call a nearly infeasible frame infeasible.
        if (status == 1 &&
            solvePhaseOne(problem, backend_->arrays, result.x, reserve, result.iterations, &backend_->phaseOneBasis)) {
            infeasible = needsReserves(reserve);
            if (!infeasible) {
                startFromSlacksAndFreeColumns(problem, backend_->simplex, backend_->rowTaken);
                backend_->simplex.dual();
                status = backend_->finishWithinBounds(problem);
                result.iterations += backend_->simplex.numberIterations();
                // Within Clp's tolerances of feasible and still refused from the cold start: the frame needs
                // the tiny reserves phase 1 found, and says so with them (its x is phase 1's).
                if (status != 0) {
                    result.status = DistributionStatus::Infeasible;
                    result.reserve = reserve;
                }
            }
        }
    }
    if (infeasible) {
        result.status = DistributionStatus::Infeasible;
        result.reserve = reserve;
        solveWithReserves(problem, reserve, result);
    }
    backend_->lastInfeasible = infeasible;
    if (status == 0) {
        result.status = DistributionStatus::Optimal;
        result.x = Eigen::Map<const Eigen::VectorXd>(backend_->simplex.primalColumnSolution(), columns);
        result.multipliers = Eigen::Map<const Eigen::VectorXd>(backend_->simplex.dualRowSolution(), rows);
    }
}

}  // namespace sinew

#include "sinew/tensions/active_set_solver.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "sinew/tensions/equality_rows_polish.hpp"
#include "sinew/tensions/infeasible_frame.hpp"

namespace sinew {
namespace {

using SparseColumn = Eigen::SparseMatrix<double>::InnerIterator;

// L L^T + sign w w^T for a lower Cholesky factor L, in place, O(n^2) (Golub and Van Loan, Matrix
// Computations, 4th ed., section 6.5.4). `w` is overwritten. False when a downdate would leave the matrix
// (numerically) indefinite; L is then garbage and must be refactorised.
bool updateCholesky(Eigen::MatrixXd& L, Eigen::VectorXd& w, double sign) {
    const Eigen::Index n = L.rows();
    // Columns before w's first nonzero stay as they are (a rotation with c = 1, s = 0): a wire reaches
    // only the rows of the joints it spans (on the whole-body benchmark w starts 89 % zeros, its first
    // nonzero a sixth of the way down).
    Eigen::Index k = 0;
    while (k < n && w[k] == 0) ++k;
    double* wValues = w.data();
    for (; k < n; ++k) {
        double* column = &L(0, k);
        const double Lkk = column[k];
        const double r2 = Lkk * Lkk + sign * w[k] * w[k];
        if (!(r2 > 1e-10 * Lkk * Lkk)) return false;
        const double r = std::sqrt(r2);
        const double c = r / Lkk, s = w[k] / Lkk, signedS = sign * s, inverseC = 1 / c;
        column[k] = r;
        // One pass over the column and w (the update is bound by their memory traffic, not its flops).
        for (Eigen::Index i = k + 1; i < n; ++i) {
            const double updated = (column[i] + signedS * wValues[i]) * inverseC;
            column[i] = updated;
            wValues[i] = c * wValues[i] - s * updated;
        }
    }
    return true;
}

// The largest equality-row residual relative to the rows' size (tau and A x = tau - residual): what an
// answer is held to against ActiveSetOptions::infeasibilityTolerance.
double calcEqualityResidual(const DistributionProblem& problem, const Eigen::VectorXd& residual) {
    const double tauScale = problem.target.size() ? problem.target.cwiseAbs().maxCoeff() : 0.0;
    const double rowScale = std::max({1.0, tauScale, (problem.target - residual).cwiseAbs().maxCoeff()});
    double largest = 0;
    for (int i = 0; i < problem.getNumRows(); ++i)
        if (problem.isEquality[static_cast<std::size_t>(i)]) largest = std::max(largest, std::abs(residual[i]) / rowScale);
    return largest;
}

// ½ Σ weight (x - center)² + ½ |tau - A x|² over the tolerance rows, from result.x and result.residual.
double calcQpObjective(const DistributionProblem& problem, const DistributionResult& result, const Eigen::VectorXd& center) {
    double objective = 0.5 * problem.weight.dot((result.x.head(problem.getNumBounded()) - center).cwiseAbs2());
    for (int i = 0; i < problem.getNumRows(); ++i)
        if (!problem.isEquality[static_cast<std::size_t>(i)]) objective += 0.5 * result.residual[i] * result.residual[i];
    return objective;
}

}  // namespace

ActiveSetSolver::ActiveSetSolver(ActiveSetOptions options) : options_(options) {}

// Sizes the buffers, reduces by the free columns, and sets the warm start: the previous multipliers moved
// into this frame's null(G^T).
void ActiveSetSolver::setUpFrame(const DistributionProblem& problem) {
    validateDistributionProblem(problem);
    factorValid_ = false;
    const int rows = problem.getNumRows(), numBounded = problem.getNumBounded();
    // The free columns reach few rows (a loop's: the joints from its two links to the root; 36 of 198 on the
    // whole-body model), so Q, and the reduction by it, acts on those rows alone: they go first in rowOrder_.
    rank_ = 0;
    numSupportRows_ = 0;
    rowOrder_.clear();
    rowPosition_.assign(static_cast<std::size_t>(rows), -1);
    for (int j = numBounded; j < problem.getNumVariables(); ++j)
        for (SparseColumn it(problem.A, j); it; ++it)
            if (it.value() != 0 && rowPosition_[static_cast<std::size_t>(it.row())] < 0) {
                rowPosition_[static_cast<std::size_t>(it.row())] = numSupportRows_++;
                rowOrder_.push_back(static_cast<int>(it.row()));
            }
    for (int i = 0; i < rows; ++i)
        if (rowPosition_[static_cast<std::size_t>(i)] < 0) {
            rowPosition_[static_cast<std::size_t>(i)] = static_cast<int>(rowOrder_.size());
            rowOrder_.push_back(i);
        }
    supportWork_.resize(numSupportRows_);
    if (numSupportRows_ > 0) {
        G_.setZero(numSupportRows_, problem.numFree);
        for (int j = numBounded; j < problem.getNumVariables(); ++j)
            for (SparseColumn it(problem.A, j); it; ++it)
                if (it.value() != 0) G_(rowPosition_[static_cast<std::size_t>(it.row())], j - numBounded) = it.value();
        qr_.setThreshold(1e-10);
        qr_.compute(G_);
        rank_ = static_cast<int>(qr_.rank());
        // Q's last columns span null(G^T) on the support rows: explicit, the reductions are products with
        // them (a 36 x 24 block on the whole body) instead of Q's reflectors one at a time, which took 60 %
        // of each factorisation.
        const Eigen::MatrixXd Q = qr_.householderQ();
        nullBasis_ = Q.rightCols(numSupportRows_ - rank_);
    }
    // Equality rows: regulariser relative to the mean column term a_j^T a_j / weight_j.
    double columnTerm = 0;
    int columns = 0;
    for (int j = 0; j < numBounded; ++j) {
        const double norm2 = problem.A.col(j).squaredNorm();
        if (norm2 > 0) columnTerm += norm2 / problem.weight[j], ++columns;
    }
    const double equalitySigma = options_.equalityRegularization * (columns ? columnTerm / columns : 1.0);
    sigma_.resize(rows);
    for (int i = 0; i < rows; ++i) sigma_[i] = problem.isEquality[static_cast<std::size_t>(i)] ? equalitySigma : 1.0;

    const int reduced = rows - rank_;
    if (center_.size() != numBounded) center_.setZero(numBounded);
    v_.resize(numBounded);
    x_.resize(numBounded);
    slopeOfX_.resize(numBounded);
    regime_.resize(static_cast<std::size_t>(numBounded));
    factored_.resize(static_cast<std::size_t>(numBounded));
    gradient_.resize(rows);
    direction_.resize(rows);
    rowWork_.resize(rows);
    reducedGradient_.resize(reduced);
    reducedDirection_.resize(reduced);
    reducedWork_.resize(reduced);
    events_.reserve(2 * static_cast<std::size_t>(numBounded));
    startFrom(hasWarmStart_ ? y_ : Eigen::VectorXd());
}

// y_ = `start` moved into this frame's null(G^T), where the dual is finite; zero where `start` is no
// start for this problem (another size, or not finite).
void ActiveSetSolver::startFrom(const Eigen::VectorXd& start) {
    const Eigen::Index rows = rowPosition_.size();
    if (start.size() != rows || !start.allFinite()) {
        y_.setZero(rows);
        return;
    }
    if (&start != &y_) y_ = start;
    if (rank_ > 0) {
        toReduced(y_, reducedWork_);
        fromReduced(reducedWork_, y_);
    }
}

// Reduced coordinates (rank_ > 0): Q^T's last numSupportRows_ - rank_ components on the support rows, then
// the other rows in rowOrder_.
void ActiveSetSolver::toReduced(const Eigen::VectorXd& rowVector, Eigen::VectorXd& reduced) {
    if (rank_ == 0) {
        reduced = rowVector;
        return;
    }
    const Eigen::Index support = numSupportRows_, kept = support - rank_;
    for (Eigen::Index k = 0; k < support; ++k) supportWork_[k] = rowVector[rowOrder_[static_cast<std::size_t>(k)]];
    reduced.head(kept).noalias() = nullBasis_.transpose() * supportWork_;
    for (Eigen::Index k = support; k < rowVector.size(); ++k) reduced[k - rank_] = rowVector[rowOrder_[static_cast<std::size_t>(k)]];
}

void ActiveSetSolver::fromReduced(const Eigen::VectorXd& reduced, Eigen::VectorXd& rowVector) {
    if (rank_ == 0) {
        rowVector = reduced;
        return;
    }
    const Eigen::Index support = numSupportRows_, kept = support - rank_;
    supportWork_.noalias() = nullBasis_ * reduced.head(kept);
    for (Eigen::Index k = 0; k < support; ++k) rowVector[rowOrder_[static_cast<std::size_t>(k)]] = supportWork_[k];
    for (Eigen::Index k = support; k < rowVector.size(); ++k) rowVector[rowOrder_[static_cast<std::size_t>(k)]] = reduced[k - rank_];
}

// x(y) = clamp(center_j + a_j^T y / weight_j) and the dual gradient tau + shift - Sigma y - A_bounded x
// (docs/tensions.md, eq. QP-2).
void ActiveSetSolver::evaluate(const DistributionProblem& problem) {
    gradient_ = problem.target + equalityShift_ - sigma_.cwiseProduct(y_);
    for (int j = 0; j < problem.getNumBounded(); ++j) {
        double aty = 0;
        for (SparseColumn it(problem.A, j); it; ++it) aty += it.value() * y_[it.row()];
        v_[j] = center_[j] + aty / problem.weight[j];
        const double lower = problem.lower[j], upper = problem.upper[j];
        regime_[static_cast<std::size_t>(j)] = v_[j] <= lower ? AtLower : v_[j] >= upper ? AtUpper : Free;
        x_[j] = std::min(std::max(v_[j], lower), upper);
        for (SparseColumn it(problem.A, j); it; ++it) gradient_[it.row()] -= it.value() * x_[j];
    }
}

// The Newton matrix Z^T (Sigma + sum over free j of a_j a_j^T / weight_j) Z from scratch, and its Cholesky factor.
bool ActiveSetSolver::factorize(const DistributionProblem& problem) {
    const int rows = problem.getNumRows();
    // Rows in rowOrder_ when reducing (support rows first), so that Q acts on K's leading rows and columns.
    const bool reduce = rank_ > 0;
    const auto at = [&](Eigen::Index row) -> Eigen::Index { return reduce ? rowPosition_[static_cast<std::size_t>(row)] : row; };
    K_.setZero(rows, rows);
    for (int i = 0; i < rows; ++i) K_(at(i), at(i)) = sigma_[i];
    // A's pattern holds every row a variable may reach; at a given pose most of a wire's are explicit zeros
    // (on the whole-body model 2 of 3), skipped here.
    for (int j = 0; j < problem.getNumBounded(); ++j) {
        if (regime_[static_cast<std::size_t>(j)] != Free) continue;
        for (SparseColumn p(problem.A, j); p; ++p) {
            if (p.value() == 0) continue;
            const double scaled = p.value() / problem.weight[j];
            for (SparseColumn q(problem.A, j); q; ++q) K_(at(p.row()), at(q.row())) += scaled * q.value();
        }
    }
    const Eigen::Index reduced = rows - rank_;
    if (reduce) {
        // [Z 0; 0 I]^T K [Z 0; 0 I], Z = nullBasis_: the lower triangle, all the factorisation reads.
        const Eigen::Index support = numSupportRows_, kept = support - rank_, others = rows - support;
        L_.resize(reduced, reduced);
        supportBlock_.noalias() = K_.topLeftCorner(support, support) * nullBasis_;
        L_.topLeftCorner(kept, kept).noalias() = nullBasis_.transpose() * supportBlock_;
        L_.bottomLeftCorner(others, kept).noalias() = K_.bottomLeftCorner(others, support) * nullBasis_;
        L_.bottomRightCorner(others, others) = K_.bottomRightCorner(others, others);
        L_.topRightCorner(kept, others).setZero();
    } else {
        L_ = K_;
    }
    const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(L_);
    factored_ = regime_;
    factorUpdates_ = 0;
    return llt.info() == Eigen::Success;
}

// Rank-one up/down-dates for the variables that entered or left the free set since the factorisation;
// false when there are too many (a new factorisation is cheaper) or a downdate fails.
bool ActiveSetSolver::updateFactor(const DistributionProblem& problem) {
    const int numBounded = problem.getNumBounded();
    int changes = 0;
    for (std::size_t j = 0; j < regime_.size(); ++j)
        if ((regime_[j] == Free) != (factored_[j] == Free)) ++changes;
    if (changes > std::max<Eigen::Index>(4, L_.rows() / 8)) return false;
    for (int j = 0; j < numBounded; ++j) {
        const std::size_t jj = static_cast<std::size_t>(j);
        if ((regime_[jj] == Free) == (factored_[jj] == Free)) continue;
        direction_.setZero();
        for (SparseColumn it(problem.A, j); it; ++it) direction_[it.row()] = it.value() / std::sqrt(problem.weight[j]);
        toReduced(direction_, reducedWork_);
        if (!updateCholesky(L_, reducedWork_, regime_[jj] == Free ? 1.0 : -1.0)) return false;
        factored_[jj] = regime_[jj];
        ++factorUpdates_;
    }
    return true;
}

// Exact line search along direction_ on the dual, a concave piecewise quadratic: its slope is piecewise
// linear in t and changes where a variable meets a bound, so walk those breakpoints in order until the
// slope reaches zero.
double ActiveSetSolver::searchLine(const DistributionProblem& problem) {
    double slopeAt = gradient_.dot(direction_);  // > 0: Newton directions ascend
    const double sigmaTerm = direction_.dot(sigma_.cwiseProduct(direction_));
    double curvature = -sigmaTerm;
    events_.clear();
    for (int j = 0; j < problem.getNumBounded(); ++j) {
        double s = 0;
        for (SparseColumn it(problem.A, j); it; ++it) s += it.value() * direction_[it.row()];
        if (s == 0) continue;
        const double weight = problem.weight[j], rate = s / weight, c = s * s / weight;
        const double lower = problem.lower[j], upper = problem.upper[j], v = v_[j];
        const Regime regime = regime_[static_cast<std::size_t>(j)];
        if (regime == Free) {
            curvature -= c;
            const double bound = rate > 0 ? upper : lower;
            if (std::isfinite(bound)) events_.push_back({(bound - v) / rate, c});
        } else if (lower < upper && ((regime == AtLower && rate > 0) || (regime == AtUpper && rate < 0))) {
            const double enter = regime == AtLower ? lower : upper, leave = regime == AtLower ? upper : lower;
            events_.push_back({(enter - v) / rate, -c});
            if (std::isfinite(leave)) events_.push_back({(leave - v) / rate, c});
        }
    }
    const auto later = [](const Event& a, const Event& b) { return a.t > b.t; };
    std::make_heap(events_.begin(), events_.end(), later);
    double t = 0;
    while (!events_.empty()) {
        const Event next = events_.front();
        const double slopeAtNext = slopeAt + curvature * (next.t - t);
        if (slopeAtNext <= 0) break;
        slopeAt = slopeAtNext;
        t = next.t;
        // Rounding in the running sum must not make the dual look convex: Sigma keeps it strictly concave.
        curvature = std::min(curvature + next.slopeChange, -sigmaTerm);
        std::pop_heap(events_.begin(), events_.end(), later);
        events_.pop_back();
    }
    return t - slopeAt / curvature;
}

void ActiveSetSolver::solve(const DistributionProblem& problem, DistributionResult& result) {
    // An infeasible frame's dual grows without bound (up to the equality regulariser) and its Newton steps
    // would run to the cap: a frame still unsolved after kStallIterations steps, a few times what a
    // feasible frame takes cold, is checked for feasibility first.
    const int firstSteps = std::min(options_.maxIterations, kStallIterations);
    lpSolved_ = false;
    if (startFromLp(problem, result)) return;
    center_.setZero(problem.getNumBounded());
    solveDual(problem, result, firstSteps);
    if (result.status == DistributionStatus::Optimal) return refineProximally(problem, result);
    // Stalled, or an equality row left unmet: the phase-1 LP tells an infeasible frame from a failure.
    const DistributionSolve solveLeastSquares = [this](const DistributionProblem& relaxed, DistributionResult& answer) {
        hasWarmStart_ = false;  // the stalled multipliers are no start
        solveDual(relaxed, answer);
    };
    if (reportInfeasibleFrame(problem, 2.0, options_.infeasibilityTolerance, solveLeastSquares, result)) return;
    if (result.status == DistributionStatus::Failed && result.iterations == firstSteps &&
        firstSteps < options_.maxIterations) {  // feasible and slow: on from where the steps stopped
        hasWarmStart_ = true;
        solveDual(problem, result, options_.maxIterations - firstSteps);
        result.iterations += firstSteps;
        if (result.status == DistributionStatus::Optimal) return refineProximally(problem, result);
    }
    if (!options_.ipoptFallback) return;
    if (!ipopt_) ipopt_ = std::make_unique<IpoptSolver>();
    const int iterations = result.iterations;
    ipopt_->solve(problem, 2.0, result);
    result.iterations += iterations;
    if (result.status != DistributionStatus::Optimal) return;
    // An interior point stops near the bounds, not on them: a few dual Newton steps from Ipopt's multipliers
    // find the exact face (the QP's KKT to roundoff). Kept only when they converge.
    y_ = result.multipliers;
    hasWarmStart_ = true;
    solveDual(problem, polished_, kPolishIterations);
    if (polished_.status == DistributionStatus::Optimal) {
        polished_.iterations += result.iterations;
        polished_.usedIpopt = true;
        std::swap(result, polished_);
    }
    refineProximally(problem, result);
}

// The steps start from the LP's answer where its Z is the lower one and it meets the equality rows: the
// first step's Z is then at most the LP's (its objective at the LP's x is that Z). The next frame starts
// from this frame's regularised multipliers: the steps' own, those of a QP centred at this frame's answer,
// are near zero and would leave it a cold start (10 Newton steps instead of 3 on the whole-body benchmark).
void ActiveSetSolver::refineProximally(const DistributionProblem& problem, DistributionResult& result) {
    if (options_.proximalSteps <= 0) return;
    const int numBounded = problem.getNumBounded();
    center_ = result.x.head(numBounded);
    double centerError = result.torqueError;
    const bool fromLp = options_.proximalFromLp && solveLp(problem) && lpAnswer_.torqueError < centerError;
    if (fromLp) {
        center_ = lpAnswer_.x.head(numBounded);
        centerError = lpAnswer_.torqueError;
    }
    takeProximalSteps(problem, centerError, fromLp, result);
}

// A frame whose LP answer meets every row to the proximal floor (ActiveSetOptions::proximalResidualFloor)
// takes its steps from that answer without the regularised optimum: the optimum could be the start only
// with a Z as small, and on the whole-body benchmark it cost half the frame. False (and nothing solved
// but the LP) where the LP's answer is not such a start or the first step does not take.
bool ActiveSetSolver::startFromLp(const DistributionProblem& problem, DistributionResult& result) {
    if (options_.proximalSteps <= 0 || !options_.proximalFromLp || !solveLp(problem) ||
        lpAnswer_.torqueError > calcProximalFloor(problem))
        return false;
    setUpFrame(problem);  // the steps keep the frame's set-up; the warm start stays the last regularised y
    center_ = lpAnswer_.x.head(problem.getNumBounded());
    result.iterations = 0;
    result.usedIpopt = false;
    return takeProximalSteps(problem, lpAnswer_.torqueError, true, result) > 0;
}

// The LP's answer (lp_solver.hpp, the problem's band rows and costs), solved at most once a frame: true
// when it meets the equality rows, a start for the proximal steps (an infeasible frame's answer, with its
// bands left open by the phase-1 reserves, is one too).
bool ActiveSetSolver::solveLp(const DistributionProblem& problem) {
    if (!lpSolved_) {
        if (!lp_) lp_ = std::make_unique<LpSolver>();
        lp_->solve(problem, lpAnswer_);
        lpSolved_ = true;
    }
    return lpAnswer_.status != DistributionStatus::Failed &&
           calcEqualityResidual(problem, lpAnswer_.residual) <= options_.infeasibilityTolerance;
}

// Z at which the steps stop: the tolerance rows' residual RMS at the floor times the largest generalized force.
double ActiveSetSolver::calcProximalFloor(const DistributionProblem& problem) const {
    int toleranceRows = 0;
    for (int i = 0; i < problem.getNumRows(); ++i) toleranceRows += !problem.isEquality[static_cast<std::size_t>(i)];
    const double residual = options_.proximalResidualFloor * (problem.target.size() ? problem.target.cwiseAbs().maxCoeff() : 0.0);
    return 0.5 * toleranceRows * residual * residual;
}

// Proximal steps from center_ (whose Z is centerError; fromLp: the LP's answer), each replacing `result` when
// it lowers Z; the number taken. Where each step's dual starts:
// - the first from the regularised optimum: y = 0, where x is its centre and every variable keeps the
//   optimum's regime, so the step's Newton matrix is the optimum's last one;
// - the first from the LP's answer, a vertex with half the wires on a bound: where the last frame's first
//   step from the LP ended, as that answer moves little frame to frame (1.5 instead of 4.1 ms a frame on
//   the whole-body benchmark, whose y = 0 left the step to free those wires);
// - the others: where the step before ended (y_ as it left it). A step's y is its answer's residual on the
//   tolerance rows, and the steps converge to a least-squares answer, whose residual is not zero where Z is
//   not (on the kick's strike 6 to 25 Newton steps a step instead of 12 to 50).
// Neither the free columns' QR nor the Newton matrix depends on the centre, so the steps keep the frame's
// set-up (every caller's last solveDual or setUpFrame was of this problem): one QR a frame instead of 6.
// The y_ they are called with, the regularised one, is put back for the next frame.
int ActiveSetSolver::takeProximalSteps(const DistributionProblem& problem, double centerError, bool fromLp,
                                       DistributionResult& result) {
    const double floorError = calcProximalFloor(problem);
    regularisedY_ = y_;
    int taken = 0;
    for (int step = 0; step < options_.proximalSteps; ++step) {
        if (step == 0 && fromLp) startFrom(lpStepY_);
        else if (step == 0) y_.setZero();
        hasWarmStart_ = true;
        solveDual(problem, proximal_, -1, true);
        if (proximal_.status != DistributionStatus::Optimal || !(proximal_.torqueError <= centerError)) break;
        const bool levelled = centerError - proximal_.torqueError <= options_.proximalTolerance * centerError ||
                              proximal_.torqueError <= floorError;
        proximal_.iterations += result.iterations;
        proximal_.usedIpopt = result.usedIpopt;
        if (step == 0 && fromLp) lpStepY_ = y_;
        std::swap(result, proximal_);
        ++taken;
        if (levelled) break;
        center_ = result.x.head(problem.getNumBounded());
        centerError = result.torqueError;
    }
    center_.setZero();
    y_ = regularisedY_;
    hasWarmStart_ = true;
    return taken;
}

// Newton steps on the dual from y_ until converged (true) or `limit` iterations in all, a non-finite step
// or a singular factor (false). fullStep: whether the last step was a full one (carried across passes);
// relativeGradient: the last dual gradient relative to the size of the generalized forces.
bool ActiveSetSolver::runNewton(const DistributionProblem& problem, double tauScale, int limit, int& iterations,
                                bool& fullStep, double& relativeGradient) {
    for (;;) {
        evaluate(problem);
        const bool exactStep = fullStep && regime_ == stepped_;
        toReduced(gradient_, reducedGradient_);
        // Size of the generalized forces: tau and A x (= tau - gradient - Sigma y).
        rowWork_ = problem.target - gradient_ - sigma_.cwiseProduct(y_);
        const double scale = std::max(tauScale, rowWork_.cwiseAbs().maxCoeff());
        const double gradientNorm = reducedGradient_.size() ? reducedGradient_.cwiseAbs().maxCoeff() : 0.0;
        relativeGradient = scale > 0 ? gradientNorm / scale : gradientNorm;
        if (!std::isfinite(gradientNorm)) return false;
        if (gradientNorm <= options_.tolerance * scale || (exactStep && gradientNorm <= options_.roundoffTolerance * scale))
            return true;
        if (iterations >= limit) return false;
        if (!factorValid_ || !updateFactor(problem)) {
            factorValid_ = factorize(problem);
            if (!factorValid_) return false;
        }
        reducedDirection_ = reducedGradient_;
        L_.triangularView<Eigen::Lower>().solveInPlace(reducedDirection_);
        L_.triangularView<Eigen::Lower>().adjoint().solveInPlace(reducedDirection_);
        fromReduced(reducedDirection_, direction_);
        stepped_ = regime_;
        const double step = searchLine(problem);
        fullStep = std::abs(step - 1) <= 1e-3;
        if (!std::isfinite(step)) return false;
        y_ += step * direction_;
        ++iterations;
    }
}

// After a converged pass: false when the equality rows are met to roundoff; otherwise keeps the pass as the
// one to fall back to and shifts their targets by sigma y for the next (the method of multipliers).
bool ActiveSetSolver::shiftEqualityTargets(const DistributionProblem& problem, double tauScale) {
    double offset = 0, size = tauScale;
    for (int i = 0; i < problem.getNumRows(); ++i) {
        if (!problem.isEquality[static_cast<std::size_t>(i)]) continue;
        offset = std::max(offset, std::abs(sigma_[i] * y_[i] - equalityShift_[i]));
        size = std::max(size, std::abs(rowWork_[i]));
    }
    if (offset <= kEqualityRoundoff * std::max(1.0, size)) return false;
    convergedY_ = y_;
    convergedShift_ = equalityShift_;
    for (int i = 0; i < problem.getNumRows(); ++i)
        if (problem.isEquality[static_cast<std::size_t>(i)]) equalityShift_[i] = sigma_[i] * y_[i];
    return true;
}

// The dual Newton active set alone, within maxIterations (default: the options'): Optimal, Infeasible
// (converged with an equality row unmet; its residual as reserve) or Failed.
void ActiveSetSolver::solveDual(const DistributionProblem& problem, DistributionResult& result, int maxIterations,
                                bool sameProblem) {
    if (maxIterations < 0) maxIterations = options_.maxIterations;
    // A factor that has taken up/down-dates is renewed: their rounding passes the exact-step test (runNewton)
    // at a dual residual of 1e-6 where a fresh factor ends at 4e-9 (tests/tensions/test_wire_problem.cpp).
    if (!sameProblem) setUpFrame(problem);
    else if (factorUpdates_ > 0) factorValid_ = false;
    const double tauScale = problem.target.size() ? problem.target.cwiseAbs().maxCoeff() : 0.0;
    bool converged = false, fullStep = false;
    int iterations = 0;
    equalityShift_.setZero(problem.getNumRows());
    // The regulariser leaves each equality row off by sigma y (tau - A x = Sigma y - shift at the dual's
    // optimum), a milli-newton on a virtual link that a frame pulls hard against (multipliers of 1e3-1e9
    // N on the kick). The method of multipliers: the rows' targets shifted by sigma y and the Newton steps
    // resumed, warm, in the same regime and with the same factor; each pass leaves them off by sigma times
    // the change of their multipliers. A pass that ends at the rounding floor (a gradient within
    // roundoffTolerance) stands although no last full step proved it: after a shift of 1e-4 N the kick's
    // strike frames end at 1e-10 of tau, their last steps cut short by breakpoints at t ~ 0 (variables
    // on their bounds), with the rows met to 2e-9 N. A pass that does not converge within a few steps
    // otherwise (rows that the bounds let the answer meet only to about what sigma y left, whose
    // multipliers then grow without end) is undone: the last converged pass stands.
    for (int pass = 0;; ++pass) {
        const int passLimit = pass == 0 ? maxIterations : iterations + kEqualityPassIterations;
        double relativeGradient = 0;
        converged = runNewton(problem, tauScale, passLimit, iterations, fullStep, relativeGradient);
        if (!converged && pass > 0 && relativeGradient <= options_.roundoffTolerance) converged = true;
        if (!converged && pass > 0) {
            y_ = convergedY_;
            equalityShift_ = convergedShift_;
            evaluate(problem);
            converged = true;
            break;
        }
        if (!converged || pass == kEqualityPasses || !shiftEqualityTargets(problem, tauScale)) break;
        fullStep = false;
    }
    if (!y_.allFinite()) {  // numerical breakdown: report the bounds-feasible point of y = 0, never NaN
        y_.setZero();
        evaluate(problem);
        converged = false;
    }
    writeDualResult(problem, converged, iterations, result);
}

// The primal answer, summary and status at the multipliers y_ (evaluated).
void ActiveSetSolver::writeDualResult(const DistributionProblem& problem, bool converged, int iterations,
                                      DistributionResult& result) {
    const int numBounded = problem.getNumBounded();
    result.x.resize(problem.getNumVariables());
    result.x.head(numBounded) = x_;
    // Free variables: at the optimum the gradient lies in range(G), and G lambda takes it up.
    if (problem.numFree > 0) {
        result.x.tail(problem.numFree).setZero();  // no support rows: the free columns are zero
        if (numSupportRows_ > 0) {
            for (int k = 0; k < numSupportRows_; ++k) supportWork_[k] = gradient_[rowOrder_[static_cast<std::size_t>(k)]];
            result.x.tail(problem.numFree) = qr_.solve(supportWork_);
        }
    }
    result.multipliers = y_;
    // The regulariser leaves the equality rows off by sigma y: projected onto them.
    if (converged) polishEqualityRows(problem, problem.weight, result.x, result.multipliers);
    result.iterations = iterations;
    result.usedIpopt = false;
    calcResultSummary(problem, result);
    result.objective = calcQpObjective(problem, result, center_);
    const double equalityResidual = calcEqualityResidual(problem, result.residual);
    result.reserve.setZero(problem.getNumRows());
    if (!converged) {
        result.status = DistributionStatus::Failed;
    } else if (equalityResidual > options_.infeasibilityTolerance) {
        result.status = DistributionStatus::Infeasible;
        for (int i = 0; i < problem.getNumRows(); ++i)
            if (problem.isEquality[static_cast<std::size_t>(i)]) result.reserve[i] = result.residual[i];
    } else {
        result.status = DistributionStatus::Optimal;
    }
    result.kkt = calcQpKktResiduals(problem, result.x, result.multipliers, center_);
    hasWarmStart_ = converged;
}

}  // namespace sinew

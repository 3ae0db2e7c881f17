#include "sinew/tensions/warm_dual_simplex.hpp"

#include <klu.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sinew {
namespace {

constexpr double kInfinite = 1e30;

// An unbounded variable's artificial other bound, this far from its finite one (newtons for the contact
// forces: a thousand times a body's weight).
constexpr double kArtificialRange = 1e6;

// Below this reciprocal condition estimate the basis is left to Clp, which repairs singular bases.
constexpr double kSmallestReciprocalCondition = 1e-13;

// A dual Devex weight past this resets the reference framework (the weights estimate |e_k^T B^-1|^2 against
// the basis they started from; after pivots on small elements the estimate is no longer worth its error).
constexpr double kLargestDevexWeight = 1e8;

}  // namespace

const char* toString(WarmDualOutcome outcome) {
    switch (outcome) {
        case WarmDualOutcome::Optimal: return "optimal";
        case WarmDualOutcome::NoBasis: return "no basis";
        case WarmDualOutcome::NotDualFeasible: return "not dual feasible";
        case WarmDualOutcome::DualUnbounded: return "dual unbounded";
        case WarmDualOutcome::Singular: return "singular basis";
        case WarmDualOutcome::TooManyPivots: return "too many pivots";
    }
    return "unknown";
}

// KLU's LU factors of the basis matrix B (its columns: A's for basic columns, -e_i for row i's activity) and
// the product-form updates since: B_k = B_0 E_1 ... E_k, E_i the identity with column p_i replaced by the
// entering column in the basis of its pivot.
//
// The triangular solves are done here on the factors klu_extract gives, P (Rs^-1 B) Q = L U + F with L and
// U block diagonal (BTF's blocks) and F the blocks above: klu_solve with one right-hand side took about
// 38,000 instructions on the whole body's 198 x 198 bases (about 40 blocks), these substitutions 25,000.
class BasisFactor {
public:
    klu_common common{};
    klu_symbolic* symbolic = nullptr;
    klu_numeric* numeric = nullptr;
    int size = 0;
    std::vector<int> starts, rowIndices;
    std::vector<double> values;
    std::vector<int> etaRows;
    std::vector<Eigen::VectorXd> etaColumns;  // kept allocated across frames
    int etas = 0;

    BasisFactor() { klu_defaults(&common); }
    ~BasisFactor() { release(); }
    BasisFactor(const BasisFactor&) = delete;
    BasisFactor& operator=(const BasisFactor&) = delete;

    void release() {
        if (numeric) klu_free_numeric(&numeric, &common);
        if (symbolic) klu_free_symbolic(&symbolic, &common);
    }

    // Factorises the basis whose k-th column is variable heads[k]; false when singular or ill-conditioned.
    bool factorize(const Eigen::SparseMatrix<double>& A, const std::vector<int>& heads) {
        release();
        etas = 0;
        const int columns = static_cast<int>(A.cols());
        const int* columnStarts = A.outerIndexPtr();
        size = static_cast<int>(heads.size());
        starts.resize(heads.size() + 1);
        starts[0] = 0;
        for (std::size_t k = 0; k < heads.size(); ++k) {
            const int j = heads[k];
            starts[k + 1] = starts[k] + (j < columns ? columnStarts[j + 1] - columnStarts[j] : 1);
        }
        rowIndices.resize(static_cast<std::size_t>(starts.back()));
        values.resize(static_cast<std::size_t>(starts.back()));
        for (std::size_t k = 0; k < heads.size(); ++k) {
            const int j = heads[k];
            const std::size_t at = static_cast<std::size_t>(starts[k]);
            if (j >= columns) {
                rowIndices[at] = j - columns;
                values[at] = -1.0;
                continue;
            }
            std::copy(A.innerIndexPtr() + columnStarts[j], A.innerIndexPtr() + columnStarts[j + 1], rowIndices.begin() + static_cast<std::ptrdiff_t>(at));
            std::copy(A.valuePtr() + columnStarts[j], A.valuePtr() + columnStarts[j + 1], values.begin() + static_cast<std::ptrdiff_t>(at));
        }
        symbolic = klu_analyze(size, starts.data(), rowIndices.data(), &common);
        if (!symbolic) return false;
        numeric = klu_factor(starts.data(), rowIndices.data(), values.data(), symbolic, &common);
        if (!numeric || common.status != KLU_OK) return false;
        klu_rcond(symbolic, numeric, &common);
        return common.rcond >= kSmallestReciprocalCondition && extract();
    }

    // v <- B^-1 v
    void ftran(Eigen::VectorXd& v) {
        double* x = work_.data();
        const int* order = rowOrder_.data();
        for (int k = 0; k < size; ++k) x[k] = v[order[k]] * inverseRowScale_[static_cast<std::size_t>(k)];
        const Triangle L(lower_), U(upper_), F(offBlock_);
        const double *lowerDiagonal = lowerDiagonal_.data(), *upperDiagonal = upperDiagonal_.data();
        for (int block = static_cast<int>(blockStarts_.size()) - 2; block >= 0; --block) {
            const int first = blockStarts_[static_cast<std::size_t>(block)], end = blockStarts_[static_cast<std::size_t>(block) + 1];
            for (int col = first; col < end; ++col) {
                const double xc = x[col] * lowerDiagonal[col];
                x[col] = xc;
                for (int e = L.start[col]; e < L.start[col + 1]; ++e) x[L.row[e]] -= L.value[e] * xc;
            }
            for (int col = end - 1; col >= first; --col) {
                const double xc = x[col] * upperDiagonal[col];
                x[col] = xc;
                for (int e = U.start[col]; e < U.start[col + 1]; ++e) x[U.row[e]] -= U.value[e] * xc;
            }
            for (int col = first; col < end; ++col) {
                const double xc = x[col];
                for (int e = F.start[col]; e < F.start[col + 1]; ++e) x[F.row[e]] -= F.value[e] * xc;
            }
        }
        order = columnOrder_.data();
        for (int k = 0; k < size; ++k) v[order[k]] = x[k];
        for (int k = 0; k < etas; ++k) {
            const Eigen::VectorXd& a = etaColumns[static_cast<std::size_t>(k)];
            const int p = etaRows[static_cast<std::size_t>(k)];
            const double vp = v[p] / a[p];
            v.noalias() -= vp * a;
            v[p] = vp;
        }
    }

    // v <- B^-T v
    void btran(Eigen::VectorXd& v) {
        for (int k = etas - 1; k >= 0; --k) {
            const Eigen::VectorXd& a = etaColumns[static_cast<std::size_t>(k)];
            const int p = etaRows[static_cast<std::size_t>(k)];
            v[p] = (v[p] - (a.dot(v) - a[p] * v[p])) / a[p];
        }
        double* x = work_.data();
        const int* order = columnOrder_.data();
        for (int k = 0; k < size; ++k) x[k] = v[order[k]];
        const Triangle L(lower_), U(upper_), F(offBlock_);
        const double *lowerDiagonal = lowerDiagonal_.data(), *upperDiagonal = upperDiagonal_.data();
        for (std::size_t block = 0; block + 1 < blockStarts_.size(); ++block) {
            const int first = blockStarts_[block], end = blockStarts_[block + 1];
            for (int col = first; col < end; ++col) {
                double xc = x[col];
                for (int e = F.start[col]; e < F.start[col + 1]; ++e) xc -= F.value[e] * x[F.row[e]];
                for (int e = U.start[col]; e < U.start[col + 1]; ++e) xc -= U.value[e] * x[U.row[e]];
                x[col] = xc * upperDiagonal[col];
            }
            for (int col = end - 1; col >= first; --col) {
                double xc = x[col];
                for (int e = L.start[col]; e < L.start[col + 1]; ++e) xc -= L.value[e] * x[L.row[e]];
                x[col] = xc * lowerDiagonal[col];
            }
        }
        order = rowOrder_.data();
        for (int k = 0; k < size; ++k) v[order[k]] = x[k] * inverseRowScale_[static_cast<std::size_t>(k)];
    }

    void addEta(int row, const Eigen::VectorXd& column) {
        if (static_cast<int>(etaColumns.size()) <= etas) {
            etaColumns.emplace_back();
            etaRows.push_back(0);
        }
        etaColumns[static_cast<std::size_t>(etas)] = column;
        etaRows[static_cast<std::size_t>(etas)] = row;
        ++etas;
    }

private:
    // A triangle's or F's entries off the diagonal, column by column.
    struct Entries {
        std::vector<int> start, row;
        std::vector<double> value;
    };
    // Their arrays as plain pointers, which the solves' loops keep in registers.
    struct Triangle {
        explicit Triangle(const Entries& e) : start(e.start.data()), row(e.row.data()), value(e.value.data()) {}
        const int* start;
        const int* row;
        const double* value;
    };

    // klu_extract's factors, split into diagonals (inverted) and the entries off them.
    bool extract() {
        const std::size_t n = static_cast<std::size_t>(size);
        const int lnz = numeric->lnz, unz = numeric->unz, nzoff = numeric->nzoff;
        extractedL_.start.resize(n + 1), extractedL_.row.resize(static_cast<std::size_t>(lnz)), extractedL_.value.resize(static_cast<std::size_t>(lnz));
        extractedU_.start.resize(n + 1), extractedU_.row.resize(static_cast<std::size_t>(unz)), extractedU_.value.resize(static_cast<std::size_t>(unz));
        offBlock_.start.resize(n + 1), offBlock_.row.resize(static_cast<std::size_t>(nzoff)), offBlock_.value.resize(static_cast<std::size_t>(nzoff));
        rowOrder_.resize(n), columnOrder_.resize(n), inverseRowScale_.resize(n);
        blockStarts_.resize(static_cast<std::size_t>(symbolic->nblocks) + 1);
        if (!klu_extract(numeric, symbolic, extractedL_.start.data(), extractedL_.row.data(), extractedL_.value.data(),
                         extractedU_.start.data(), extractedU_.row.data(), extractedU_.value.data(), offBlock_.start.data(),
                         offBlock_.row.data(), offBlock_.value.data(), rowOrder_.data(), columnOrder_.data(),
                         inverseRowScale_.data(), blockStarts_.data(), &common))
            return false;
        // Row k of P (Rs^-1 B) Q is row rowOrder_[k] of B over Rs[k] (extracted in the permuted order).
        for (double& scale : inverseRowScale_) scale = 1 / scale;
        lowerDiagonal_.resize(size), upperDiagonal_.resize(size), work_.resize(size);
        return splitDiagonal(extractedL_, lower_, lowerDiagonal_) && splitDiagonal(extractedU_, upper_, upperDiagonal_);
    }

    static bool splitDiagonal(const Entries& triangle, Entries& offDiagonal, Eigen::VectorXd& inverseDiagonal) {
        offDiagonal.start.assign(1, 0);
        offDiagonal.row.clear();
        offDiagonal.value.clear();
        inverseDiagonal.setZero();
        for (Eigen::Index col = 0; col < inverseDiagonal.size(); ++col) {
            for (int e = triangle.start[static_cast<std::size_t>(col)]; e < triangle.start[static_cast<std::size_t>(col) + 1]; ++e) {
                const std::size_t ee = static_cast<std::size_t>(e);
                if (triangle.row[ee] == col) {
                    inverseDiagonal[col] = 1 / triangle.value[ee];
                } else {
                    offDiagonal.row.push_back(triangle.row[ee]);
                    offDiagonal.value.push_back(triangle.value[ee]);
                }
            }
            offDiagonal.start.push_back(static_cast<int>(offDiagonal.row.size()));
        }
        return inverseDiagonal.allFinite() && (inverseDiagonal.array() != 0).all();
    }

    Entries extractedL_, extractedU_, lower_, upper_, offBlock_;
    std::vector<int> rowOrder_, columnOrder_, blockStarts_;
    std::vector<double> inverseRowScale_;
    Eigen::VectorXd lowerDiagonal_, upperDiagonal_, work_;
};

namespace {

// One solve's working state: the variables are A's columns, then the rows' activities (column -e_i).
class DualSimplexRun {
public:
    DualSimplexRun(const LinearProgram& lp, const WarmDualSimplexOptions& options)
        : A_(*lp.A), lp_(lp), options_(options), rows_(static_cast<int>(A_.rows())), columns_(static_cast<int>(A_.cols())) {}

    // Reads Clp's status codes; false when they are no basis of this problem.
    bool readBasis(const std::vector<unsigned char>& status) {
        const int total = rows_ + columns_;
        if (static_cast<int>(status.size()) != total) return false;
        state_.resize(static_cast<std::size_t>(total));
        value_.setZero(total);
        position_.assign(static_cast<std::size_t>(total), -1);
        artificial_.assign(static_cast<std::size_t>(total), 0);
        heads_.clear();
        for (int j = 0; j < total; ++j) {
            const auto code = static_cast<SimplexStatus>(status[static_cast<std::size_t>(j)] & 7);
            const double low = lower(j), up = upper(j);
            SimplexStatus& state = state_[static_cast<std::size_t>(j)];
            if (code == SimplexStatus::Basic) {
                state = SimplexStatus::Basic;
                position_[static_cast<std::size_t>(j)] = static_cast<int>(heads_.size());
                heads_.push_back(j);
            } else if (code == SimplexStatus::SuperBasic) {
                return false;
            } else if (low == up) {
                state = SimplexStatus::Fixed;
                value_[j] = low;
            } else if (code == SimplexStatus::AtUpper) {
                if (up >= kInfinite) return false;
                state = SimplexStatus::AtUpper;
                value_[j] = up;
            } else if (code == SimplexStatus::Free) {
                if (low > -kInfinite || up < kInfinite) return false;
                state = SimplexStatus::Free;
            } else {
                if (low <= -kInfinite) return false;  // at lower (or fixed, which Clp gives only to low == up)
                state = SimplexStatus::AtLower;
                value_[j] = low;
            }
        }
        return static_cast<int>(heads_.size()) == rows_;
    }

    WarmDualOutcome run(BasisFactor& factor, int& pivots) {
        if (!refresh(factor)) return WarmDualOutcome::Singular;
        weights_.setOnes(rows_);
        bool verified = false;  // the values and reduced costs were computed afresh since the last pivot
        for (;;) {
            const int leaving = chooseLeavingRow();
            if (leaving < 0) {
                if (factor.etas == 0 || verified)
                    return isAtArtificialBound() ? WarmDualOutcome::NotDualFeasible : WarmDualOutcome::Optimal;
                verified = true;
                // Proved only on values and reduced costs computed afresh, not on the updated ones.
                if (!refresh(factor, false)) return WarmDualOutcome::Singular;
                continue;
            }
            if (pivots >= options_.maxPivots) return WarmDualOutcome::TooManyPivots;
            verified = false;
            const PivotResult result = pivot(factor, leaving);
            if (result == PivotResult::DualUnbounded) return WarmDualOutcome::DualUnbounded;
            if (result == PivotResult::LostAccuracy) {
                // The updates' rounding, or a poor factorisation: once more from a fresh one.
                if (factor.etas == 0) return WarmDualOutcome::Singular;
                if (!refresh(factor)) return WarmDualOutcome::Singular;
                continue;
            }
            ++pivots;
            if (factor.etas >= options_.refactorEvery) {
                if (!refresh(factor)) return WarmDualOutcome::Singular;
            }
        }
    }

    void writeBasis(std::vector<unsigned char>& status) const {
        for (std::size_t j = 0; j < state_.size(); ++j) status[j] = static_cast<unsigned char>(state_[j]);
    }

    void readSolution(Eigen::VectorXd& columnValues, Eigen::VectorXd& rowDuals) const {
        columnValues.resize(columns_);
        for (int j = 0; j < columns_; ++j) {
            const int k = position_[static_cast<std::size_t>(j)];
            columnValues[j] = k >= 0 ? basicValues_[k] : value_[j];
        }
        rowDuals = duals_;
    }

private:
    double lower(int j) const { return j < columns_ ? lp_.columnLower[j] : lp_.rowLower[j - columns_]; }
    double upper(int j) const { return j < columns_ ? lp_.columnUpper[j] : lp_.rowUpper[j - columns_]; }
    double cost(int j) const { return j < columns_ ? lp_.cost[j] : 0.0; }

    // alpha_j = column j of [A -I] times v
    double dotColumn(int j, const Eigen::VectorXd& v) const {
        if (j >= columns_) return -v[j - columns_];
        // Two sums: one chain of dependent additions was the pivot's longest latency.
        const int* row = A_.innerIndexPtr();
        const double* value = A_.valuePtr();
        int k = A_.outerIndexPtr()[j];
        const int end = A_.outerIndexPtr()[j + 1];
        double even = 0, odd = 0;
        for (; k + 1 < end; k += 2) {
            even += value[k] * v[row[k]];
            odd += value[k + 1] * v[row[k + 1]];
        }
        if (k < end) even += value[k] * v[row[k]];
        return even + odd;
    }

    // v -= (column j of [A -I]) * t
    void subtractColumn(int j, double t, Eigen::VectorXd& v) const {
        if (j >= columns_) {
            v[j - columns_] += t;
            return;
        }
        for (Eigen::SparseMatrix<double>::InnerIterator it(A_, j); it; ++it) v[it.row()] -= it.value() * t;
    }

    // A fresh factorisation (unless `refactor` is false: the current one with its updates), the reduced
    // costs from the costs, dual feasibility restored by moving each nonbasic variable whose reduced cost
    // points the wrong way to its other bound (the frame's change of A turns some: a wire at its cap that no
    // longer pays, a row's band edge), an artificial one where it has none; then the basic values from the
    // nonbasic ones. False when the basis is singular.
    bool refresh(BasisFactor& factor, bool refactor = true) {
        if (refactor && !factor.factorize(A_, heads_)) return false;
        duals_.resize(rows_);
        for (int k = 0; k < rows_; ++k) duals_[k] = cost(heads_[static_cast<std::size_t>(k)]);
        factor.btran(duals_);
        reducedCosts_.setZero(rows_ + columns_);
        for (int j = 0; j < rows_ + columns_; ++j)
            if (position_[static_cast<std::size_t>(j)] < 0) reducedCosts_[j] = cost(j) - dotColumn(j, duals_);
        flipToDualFeasibility();
        computeBasicValues(factor);
        return basicValues_.allFinite() && duals_.allFinite();
    }

    // B x_B = -N x_N (the rows' activities are variables: [A -I] z = 0).
    void computeBasicValues(BasisFactor& factor) {
        basicValues_.setZero(rows_);
        for (int j = 0; j < rows_ + columns_; ++j)
            if (position_[static_cast<std::size_t>(j)] < 0 && value_[j] != 0) subtractColumn(j, value_[j], basicValues_);
        factor.ftran(basicValues_);
    }

    void flipToDualFeasibility() {
        const double tolerance = options_.dualTolerance;
        for (int j = 0; j < rows_ + columns_; ++j) {
            const double d = reducedCosts_[j];
            SimplexStatus& s = state_[static_cast<std::size_t>(j)];
            const bool free = s == SimplexStatus::Free && std::abs(d) > tolerance;
            const bool wrongAtLower = (s == SimplexStatus::AtLower && d < -tolerance) || (free && d < 0);
            const bool wrongAtUpper = (s == SimplexStatus::AtUpper && d > tolerance) || (free && d > 0);
            if (!wrongAtLower && !wrongAtUpper) continue;
            s = wrongAtLower ? SimplexStatus::AtUpper : SimplexStatus::AtLower;
            const double other = wrongAtLower ? upper(j) : lower(j);
            const bool unbounded = !(std::abs(other) < kInfinite);
            // An artificial bound is kArtificialRange from the variable's finite bound, or from 0 if it has none.
            const double anchor = std::abs(lower(j)) < kInfinite ? lower(j) : std::abs(upper(j)) < kInfinite ? upper(j) : 0.0;
            value_[j] = !unbounded ? other : wrongAtLower ? anchor + kArtificialRange : anchor - kArtificialRange;
            artificial_[static_cast<std::size_t>(j)] = unbounded;
        }
    }

    bool isAtArtificialBound() const { return std::find(artificial_.begin(), artificial_.end(), 1) != artificial_.end(); }

    // The basic variable whose infeasibility is largest against its row's dual Devex weight (Forrest and
    // Goldfarb's reference framework: an estimate of |e_k^T B^-1|^2 relative to the basis the solve started
    // from), or -1 when every one is within the tolerance. Dantzig's rule (the largest infeasibility alone)
    // took a median of 75 pivots on the kick's warm frames.
    int chooseLeavingRow() const {
        int leaving = -1;
        double best = 0;
        const double tolerance = options_.primalTolerance;
        for (int k = 0; k < rows_; ++k) {
            const int j = heads_[static_cast<std::size_t>(k)];
            const double v = basicValues_[k];
            const double beyond = std::max(lower(j) - v, v - upper(j));
            if (beyond <= tolerance) continue;
            // The first infeasible row is taken whatever its score: an infeasible basis is never called optimal.
            const double score = beyond * beyond / weights_[k];
            if (leaving < 0 || score > best) best = score, leaving = k;
        }
        return leaving;
    }

    // Devex's update for a pivot on row p whose entering column, through the basis before the pivot, is
    // column_. A small pivot grows the other rows' weights by its ratios squared; past kLargestDevexWeight
    // (or not finite) the reference framework starts again from the current basis, as Devex does.
    void updateWeights(int p) {
        const double pivot = column_[p], weight = weights_[p];
        double largest = 0;
        for (int k = 0; k < rows_; ++k) {
            const double ratio = column_[k] / pivot;
            weights_[k] = std::max(weights_[k], ratio * ratio * weight);
            largest = std::max(largest, weights_[k]);
        }
        weights_[p] = std::max(weight / (pivot * pivot), 1.0);
        if (!(std::max(largest, weights_[p]) <= kLargestDevexWeight)) weights_.setOnes();
    }

    enum class PivotResult { Pivoted, DualUnbounded, LostAccuracy };

    // One dual simplex pivot on basis row p.
    PivotResult pivot(BasisFactor& factor, int p) {
        const int leavingVariable = heads_[static_cast<std::size_t>(p)];
        const bool toUpper = basicValues_[p] > upper(leavingVariable);
        const double direction = toUpper ? 1.0 : -1.0;
        const double bound = toUpper ? upper(leavingVariable) : lower(leavingVariable);

        row_.setZero(rows_);
        row_[p] = 1.0;
        factor.btran(row_);
        alpha_.resize(rows_ + columns_);  // read only where nonbasic
        double largestAlpha = 0;
        for (int j = 0; j < rows_ + columns_; ++j) {
            if (state_[static_cast<std::size_t>(j)] == SimplexStatus::Basic) continue;
            alpha_[j] = dotColumn(j, row_);
            largestAlpha = std::max(largestAlpha, std::abs(alpha_[j]));
        }
        const double pivotTolerance = 1e-9 * std::max(1.0, largestAlpha);
        const double dualTolerance = options_.dualTolerance;
        // The reduced cost of nonbasic j moves as d_j - t * direction * alpha_j, t >= 0: it reaches zero at
        // its breakpoint t = d_j / (direction * alpha_j) if the sign is the one that makes it wrong there.
        candidates_.clear();
        for (int j = 0; j < rows_ + columns_; ++j) {
            const SimplexStatus s = state_[static_cast<std::size_t>(j)];
            if (s == SimplexStatus::Basic || s == SimplexStatus::Fixed) continue;
            const double a = direction * alpha_[j], d = reducedCosts_[j];
            const bool fromLower = (s == SimplexStatus::AtLower || s == SimplexStatus::Free) && a > pivotTolerance;
            const bool fromUpper = (s == SimplexStatus::AtUpper || s == SimplexStatus::Free) && a < -pivotTolerance;
            if (!fromLower && !fromUpper) continue;
            candidates_.push_back({j, std::max(0.0, d / a)});
        }
        // Bound flipping (the long-step ratio test): passing a boxed variable's breakpoint moves it to its
        // other bound, which takes |alpha_j| (u_j - l_j) off the leaving row's infeasibility; the step goes on
        // while some is left. The rows' narrow bands make most breakpoints such flips. The breakpoints are
        // taken in order from a heap: a few are passed of the hundreds there may be.
        const auto later = [](const Candidate& x, const Candidate& y) { return x.ratio > y.ratio; };
        std::make_heap(candidates_.begin(), candidates_.end(), later);
        double infeasibility = std::abs(basicValues_[p] - bound);
        flips_.clear();
        std::size_t first = candidates_.size();  // candidates_[first, end) are the breakpoints not passed
        while (first > 0) {
            const int j = candidates_.front().variable;
            const double range = upper(j) - lower(j);
            const double drop = std::abs(alpha_[j]) * range;
            if (!(range < kInfinite) || drop >= infeasibility) break;
            infeasibility -= drop;
            flips_.push_back(j);
            std::pop_heap(candidates_.begin(), candidates_.begin() + static_cast<std::ptrdiff_t>(first), later);
            --first;
        }
        if (first == 0) return PivotResult::DualUnbounded;
        // Harris' two passes among the breakpoints left: the largest pivot whose breakpoint is within the
        // tolerance-relaxed bound of the nearest. A relaxed bound is no less than its breakpoint, so the
        // breakpoints beyond the smallest relaxed bound so far need not be looked at: they stay in the heap.
        double step = std::numeric_limits<double>::infinity();
        std::size_t near = first;  // candidates_[near, first) are the breakpoints within the step
        while (near > 0 && candidates_.front().ratio <= step) {
            const int j = candidates_.front().variable;
            step = std::min(step, (std::abs(reducedCosts_[j]) + dualTolerance) / std::abs(alpha_[j]));
            std::pop_heap(candidates_.begin(), candidates_.begin() + static_cast<std::ptrdiff_t>(near), later);
            --near;
        }
        int entering = -1;
        double largestPivot = 0;
        for (std::size_t k = near; k < first; ++k) {
            const Candidate& c = candidates_[k];
            if (c.ratio <= step && std::abs(alpha_[c.variable]) > largestPivot)
                largestPivot = std::abs(alpha_[c.variable]), entering = c.variable;
        }
        if (entering < 0) return PivotResult::DualUnbounded;

        column_.setZero(rows_);
        subtractColumn(entering, -1.0, column_);
        factor.ftran(column_);
        // The pivot seen from its row and from its column must agree, or the factors have lost accuracy.
        if (std::abs(column_[p] - alpha_[entering]) > 1e-8 * (1 + std::abs(alpha_[entering])) ||
            std::abs(column_[p]) < pivotTolerance)
            return PivotResult::LostAccuracy;

        const double dualStep = std::max(0.0, reducedCosts_[entering] / (direction * alpha_[entering])) * direction;
        for (int j = 0; j < rows_ + columns_; ++j)
            if (state_[static_cast<std::size_t>(j)] != SimplexStatus::Basic) reducedCosts_[j] -= dualStep * alpha_[j];
        if (!flips_.empty()) {
            flipMove_.setZero(rows_);
            for (const int j : flips_) {
                SimplexStatus& s = state_[static_cast<std::size_t>(j)];
                const double move = s == SimplexStatus::AtLower ? upper(j) - lower(j) : lower(j) - upper(j);
                s = s == SimplexStatus::AtLower ? SimplexStatus::AtUpper : SimplexStatus::AtLower;
                value_[j] += move;
                subtractColumn(j, move, flipMove_);
            }
            factor.ftran(flipMove_);
            basicValues_ += flipMove_;
        }
        updateWeights(p);
        const double primalStep = (basicValues_[p] - bound) / column_[p];
        basicValues_.noalias() -= primalStep * column_;
        basicValues_[p] = value_[entering] + primalStep;

        reducedCosts_[entering] = 0;
        reducedCosts_[leavingVariable] = -dualStep;
        value_[leavingVariable] = bound;
        state_[static_cast<std::size_t>(leavingVariable)] = lower(leavingVariable) == upper(leavingVariable) ? SimplexStatus::Fixed
                                                            : toUpper                                         ? SimplexStatus::AtUpper
                                                                                                              : SimplexStatus::AtLower;
        position_[static_cast<std::size_t>(leavingVariable)] = -1;
        state_[static_cast<std::size_t>(entering)] = SimplexStatus::Basic;
        position_[static_cast<std::size_t>(entering)] = p;
        artificial_[static_cast<std::size_t>(entering)] = 0;
        heads_[static_cast<std::size_t>(p)] = entering;
        factor.addEta(p, column_);
        return PivotResult::Pivoted;
    }

    const Eigen::SparseMatrix<double>& A_;
    const LinearProgram& lp_;
    const WarmDualSimplexOptions& options_;
    const int rows_, columns_;
    std::vector<SimplexStatus> state_;
    Eigen::VectorXd value_;        // nonbasic variables' values (bounds, or 0 when free)
    std::vector<int> position_;    // a basic variable's row in the basis, -1 when nonbasic
    // Nonbasic at an artificial bound: kArtificialRange from its finite bound, where the other one is infinite
    // and its reduced cost wants it there (Clp's fake bounds: the contact forces' columns have no cap). An
    // optimum with one there proves nothing about the real problem and goes to Clp.
    std::vector<char> artificial_;
    std::vector<int> heads_;       // the basic variable of each basis row
    Eigen::VectorXd basicValues_, duals_, reducedCosts_, row_, alpha_, column_;
    Eigen::VectorXd weights_;  // per basis row: its dual Devex weight
    struct Candidate {
        int variable;
        double ratio;  // the breakpoint
    };
    std::vector<Candidate> candidates_;  // the ratio test's
    std::vector<int> flips_;             // the boxed variables the ratio test passes
    Eigen::VectorXd flipMove_;
};

}  // namespace

WarmDualSimplex::WarmDualSimplex() : factor_(std::make_unique<BasisFactor>()) {}
WarmDualSimplex::~WarmDualSimplex() = default;

WarmDualOutcome WarmDualSimplex::solve(const LinearProgram& lp, std::vector<unsigned char>& status,
                                       const WarmDualSimplexOptions& options) {
    pivots_ = 0;
    if (!lp.A || !lp.A->isCompressed()) return WarmDualOutcome::NoBasis;
    DualSimplexRun run(lp, options);
    if (!run.readBasis(status)) return WarmDualOutcome::NoBasis;
    const WarmDualOutcome outcome = run.run(*factor_, pivots_);
    if (outcome != WarmDualOutcome::Optimal) return outcome;
    run.readSolution(columnValues_, rowDuals_);
    run.writeBasis(status);
    return outcome;
}

}  // namespace sinew

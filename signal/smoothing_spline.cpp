#include "sinew/signal/smoothing_spline.hpp"

#include <Eigen/SVD>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

constexpr int kMaxOrder = 2 * SmoothingSpline::kMaxHalfOrder;
using Window = std::array<double, kMaxOrder>;
using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

// The derivatives lowest..highest at t of sum_j a_j B_j, the B-splines of `order` on `knots`, for any
// coefficient window a (window[r] = a_{span-order+1+r}), where t lies in the knot span [knots[span],
// knots[span+1]) (or at its right end). For each derivative the coefficients are differenced once more (each
// difference lowers the order by one), then de Boor's recurrence evaluates the lower-order spline (de Boor,
// A Practical Guide to Splines, ch. X). Differencing the coefficients first keeps the high derivatives that
// the natural conditions and the roughness integrals need accurate: differencing the basis functions'
// values instead (The NURBS Book's A2.3) lost digits enough to move a degree-7 fit by 2e-7. The
// recurrence's factors depend on the knots and t alone, so they are computed once and applied to every
// window that shares them: a table's splines on the same sites, or the unit windows that give the
// B-splines themselves.
class SpanRecurrence {
public:
    SpanRecurrence(const Eigen::VectorXd& knots, int order, int span, double t, int lowest, int highest)
        : order_(order), lowest_(lowest), highest_(highest) {
        const int first = span - order + 1;  // global index of window[0]
        for (int derivative = 1; derivative <= highest; ++derivative)
            for (int r = order - 1; r >= derivative; --r) {
                const int j = first + r;
                knotSpans_[derivative][r] = knots(j + order - derivative) - knots(j);
            }
        for (int derivative = lowest; derivative <= highest; ++derivative) {
            const int reduced = order - derivative;
            for (int level = 1; level < reduced; ++level)
                for (int r = order - 1; r >= derivative + level; --r) {
                    const int j = first + r;
                    alphas_[derivative][level][r] = (t - knots(j)) / (knots(j + reduced - level) - knots(j));
                }
        }
    }

    // derivatives[lowest..highest] for the window a.
    void apply(Window a, double* derivatives) const {
        for (int derivative = 0; derivative <= highest_; ++derivative) {
            if (derivative > 0)
                for (int r = order_ - 1; r >= derivative; --r)
                    a[r] = (order_ - derivative) * (a[r] - a[r - 1]) / knotSpans_[derivative][r];
            if (derivative < lowest_) continue;
            Window b = a;
            const int reduced = order_ - derivative;
            for (int level = 1; level < reduced; ++level)
                for (int r = order_ - 1; r >= derivative + level; --r) {
                    const double alpha = alphas_[derivative][level][r];
                    b[r] = (1 - alpha) * b[r - 1] + alpha * b[r];
                }
            derivatives[derivative] = b[order_ - 1];
        }
    }

private:
    int order_, lowest_, highest_;  // highest < order
    std::array<Window, kMaxOrder> knotSpans_;                  // [derivative][r]: the differences' divisors
    std::array<std::array<Window, kMaxOrder>, kMaxOrder> alphas_;  // [derivative][level][r]: de Boor's weights
};

// The order-many B-splines that do not vanish on `span`, each differentiated `derivative` (< order) times, at t.
Window basisOnSpan(const Eigen::VectorXd& knots, int order, int span, double t, int derivative) {
    const SpanRecurrence recurrence(knots, order, span, t, derivative, derivative);
    Window values{};
    std::array<double, kMaxOrder> derivatives;
    for (int r = 0; r < order; ++r) {
        Window unit{};
        unit[r] = 1;
        recurrence.apply(unit, derivatives.data());
        values[r] = derivatives[static_cast<std::size_t>(derivative)];
    }
    return values;
}

// The knot span holding t for sites x: interval i = [x_i, x_{i+1}) is span order - 1 + i; the last
// interval is closed.
int findSpan(const Eigen::VectorXd& x, int order, double t) {
    const Eigen::Index n = x.size();
    const Eigen::Index i = std::upper_bound(x.data(), x.data() + n, t) - x.data() - 1;
    return order - 1 + static_cast<int>(std::clamp<Eigen::Index>(i, 0, n - 2));
}

// Gauss-Legendre nodes and weights on [-1, 1] with m points, exact for polynomials of degree 2m - 1
// (Abramowitz and Stegun 25.4.30); m points integrate the products of m-th derivatives exactly.
std::vector<std::array<double, 2>> gaussLegendre(int m) {
    switch (m) {
        case 1: return {{0.0, 2.0}};
        case 2: return {{-0.5773502691896257, 1.0}, {0.5773502691896257, 1.0}};
        case 3: return {{-0.7745966692414834, 5.0 / 9}, {0.0, 8.0 / 9}, {0.7745966692414834, 5.0 / 9}};
        default:
            return {{-0.8611363115940526, 0.3478548451374538}, {-0.3399810435848563, 0.6521451548625461},
                    {0.3399810435848563, 0.6521451548625461}, {0.8611363115940526, 0.3478548451374538}};
    }
}

// A symmetric banded matrix of half-bandwidth b, lower band stored by diagonals: band(d, i) = A(i + d, i).
struct SymmetricBand {
    int b = 0;
    Eigen::MatrixXd band;

    int size() const { return static_cast<int>(band.cols()); }
    static SymmetricBand fromSparse(const SparseMatrix& a, int b) {
        SymmetricBand s{b, Eigen::MatrixXd::Zero(b + 1, a.cols())};
        for (int j = 0; j < a.outerSize(); ++j)
            for (SparseMatrix::InnerIterator it(a, j); it; ++it)
                if (it.row() >= j) s.band(it.row() - j, j) = it.value();
        return s;
    }
    // sum_ij A_ij C_ij over the full symmetric matrices
    double dot(const SymmetricBand& c) const {
        return band.row(0).dot(c.band.row(0)) + 2 * band.bottomRows(b).cwiseProduct(c.band.bottomRows(b)).sum();
    }
};

// In-place A = L D L^T (L unit lower triangular with the band of A): afterwards band(0, i) = D_i and
// band(d, i) = L(i + d, i). False if a pivot is not positive (A not numerically positive definite).
bool factorLDLT(SymmetricBand& a) {
    const int n = a.size(), b = a.b;
    auto L = [&](int i, int k) -> double& { return a.band(i - k, k); };
    for (int j = 0; j < n; ++j) {
        for (int k = std::max(0, j - b); k < j; ++k) a.band(0, j) -= L(j, k) * L(j, k) * a.band(0, k);
        if (!(a.band(0, j) > 0)) return false;
        for (int i = j + 1; i <= std::min(n - 1, j + b); ++i) {
            for (int k = std::max(0, i - b); k < j; ++k) L(i, j) -= L(i, k) * L(j, k) * a.band(0, k);
            L(i, j) /= a.band(0, j);
        }
    }
    return true;
}

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Row i of a VectorXd or a RowMajorMatrix: its columns' entries, contiguous.
template <typename Columns>
double* rowOf(Columns& x, Eigen::Index i) {
    return x.data() + i * x.cols();
}
template <typename Columns>
const double* rowOf(const Columns& x, Eigen::Index i) {
    return x.data() + i * x.cols();
}

// target[j] += scale * source[j] over a row of `columns` entries: a plain loop that the compiler vectorizes,
// several times cheaper than an Eigen expression per row at the few dozen columns of a table.
inline void addScaledRow(double* target, const double* source, double scale, Eigen::Index columns) {
    for (Eigen::Index j = 0; j < columns; ++j) target[j] += scale * source[j];
}

// Solves in place for x, a VectorXd or a RowMajorMatrix of many columns. The matrix is solved row by row,
// a row of all its columns one vector operation, each column's arithmetic that of a one-column solve.
template <typename Columns>
void solveLDLT(const SymmetricBand& f, Columns& x) {
    const int n = f.size(), b = f.b;
    const Eigen::Index columns = x.cols();
    for (int i = 0; i < n; ++i)
        for (int k = std::max(0, i - b); k < i; ++k) addScaledRow(rowOf(x, i), rowOf(x, k), -f.band(i - k, k), columns);
    for (int i = 0; i < n; ++i) x.row(i) /= f.band(0, i);
    for (int i = n - 1; i >= 0; --i)
        for (int k = i + 1; k <= std::min(n - 1, i + b); ++k) addScaledRow(rowOf(x, i), rowOf(x, k), -f.band(k - i, i), columns);
}

// The band of A^-1 from A = L D L^T, by the recurrence A^-1 = D^-1 L^-1 + (I - L^T) A^-1 run from the last
// row up (Hutchinson and de Hoog 1985; Erisman and Tinney 1975): O(n b^2), never the full inverse.
SymmetricBand bandOfInverse(const SymmetricBand& f) {
    const int n = f.size(), b = f.b;
    SymmetricBand z{b, Eigen::MatrixXd::Zero(b + 1, n)};
    auto Z = [&](int i, int j) { return i <= j ? z.band(j - i, i) : z.band(i - j, j); };
    for (int i = n - 1; i >= 0; --i) {
        const int last = std::min(n - 1, i + b);
        for (int j = last; j > i; --j) {
            double zij = 0;
            for (int k = i + 1; k <= last; ++k) zij -= f.band(k - i, i) * Z(k, j);
            z.band(j - i, i) = zij;
        }
        double zii = 1 / f.band(0, i);
        for (int k = i + 1; k <= last; ++k) zii -= f.band(k - i, i) * Z(k, i);
        z.band(0, i) = zii;
    }
    return z;
}

std::string sample(const char* what, Eigen::Index i, double value) {
    return std::string(what) + "[" + std::to_string(i) + "] = " + std::to_string(value);
}

}  // namespace

// The fit of one data set for any smoothing parameter p. The spline lives in the natural subspace of the
// B-spline space (knots at the sites, order 2m) spanned by n basis functions N_c = sum_g Z(g, c) B_g that
// satisfy s^(j)(x_0) = s^(j)(x_{n-1}) = 0 for j = m..2m-2. With N(i, c) = N_c(x_i), W = diag(w) and
// P(c, d) = integral N_c^(m) N_d^(m), the minimizer has coefficients solving (H + p P) c = N^T W y,
// H = N^T W N; both are banded and H is positive definite (N is square and nonsingular), so p = 0 is the
// interpolant. Derivation in docs/signal-processing.md.
class NaturalSplineFitter {
public:
    struct Trial {
        bool solved = false;  // false where H + p P is not numerically positive definite (p far too large)
        double p = 0;
        Eigen::VectorXd c;  // natural-basis coefficients (n)
        double meanSquaredResidual = 0;
        double residualDegreesOfFreedom = 0;  // n - trace(A) = p trace((H + p P)^-1 P)
    };

    NaturalSplineFitter(int degree, const Eigen::Ref<const Eigen::VectorXd>& x,
                        const Eigen::Ref<const Eigen::VectorXd>& y, const Eigen::Ref<const Eigen::VectorXd>& weights)
        : NaturalSplineFitter(degree, x, weights, true) {
        setValues(y);
    }

    // The sites' basis, collocation and roughness alone: what every series sampled at these sites shares,
    // and the costly part of a fit (setValues then takes O(n) per series). Without `roughness` only the
    // interpolant (p = 0) can be solved for, and the roughness integrals, most of the set-up, are skipped.
    NaturalSplineFitter(int degree, const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& weights,
                        bool roughness)
        : x_(x) {
        if (degree < 1 || degree > 2 * SmoothingSpline::kMaxHalfOrder - 1 || degree % 2 == 0)
            throw Error("smoothing spline: degree " + std::to_string(degree) + "; expected 1, 3, 5 or 7");
        m_ = (degree + 1) / 2;
        n_ = static_cast<int>(x.size());
        if (n_ < 2 * m_)
            throw Error("smoothing spline: " + std::to_string(n_) + " samples; degree " + std::to_string(degree) +
                        " needs at least " + std::to_string(2 * m_));
        w_ = weights.size() == 0 ? Eigen::VectorXd::Ones(n_) : Eigen::VectorXd(weights);
        if (w_.size() != n_)
            throw Error("smoothing spline: " + std::to_string(w_.size()) + " weights for " + std::to_string(n_) + " sites");
        for (Eigen::Index i = 0; i < n_; ++i) {
            if (!std::isfinite(x_(i))) throw Error("smoothing spline: site " + sample("x", i, x_(i)) + " is not finite");
            if (!(std::isfinite(w_(i)) && w_(i) > 0))
                throw Error("smoothing spline: weight " + sample("w", i, w_(i)) + "; expected a finite value > 0");
            if (i > 0 && !(x_(i) > x_(i - 1)))
                throw Error("smoothing spline: " + sample("x", i, x_(i)) + " does not exceed " +
                            sample("x", i - 1, x_(i - 1)) + "; the sites must be strictly increasing");
        }
        const int order = 2 * m_, count = n_ + 2 * m_ - 2;  // B-spline order and number of B-splines
        knots_.resize(count + order);
        knots_.head(order).setConstant(x_(0));
        knots_.segment(order, n_ - 2) = x_.segment(1, n_ - 2);
        knots_.tail(order).setConstant(x_(n_ - 1));

        buildNaturalEnds(order, count);
        buildCollocation(order);
        SparseMatrix P;
        int b = static_cast<int>(rowValues_.cols()) - 1;  // H's half-bandwidth from N's rows
        if (roughness) {
            const SparseMatrix Z = naturalBasisMatrix(count);
            P = Z.transpose() * buildRoughness(order, count) * Z;
            for (int j = 0; j < P.outerSize(); ++j)
                for (SparseMatrix::InnerIterator it(P, j); it; ++it) b = std::max(b, static_cast<int>(it.row()) - j);
        }
        // H = N^T W N, row by row of N
        H_ = {b, Eigen::MatrixXd::Zero(b + 1, n_)};
        for (int i = 0; i < n_; ++i)
            for (Eigen::Index c = 0; c < rowValues_.cols(); ++c)
                for (Eigen::Index d = 0; d <= c; ++d)
                    H_.band(c - d, rowFirst_[i] + d) += w_(i) * rowValues_(i, c) * rowValues_(i, d);
        P_ = roughness ? SymmetricBand::fromSparse(P, b) : SymmetricBand{b, Eigen::MatrixXd::Zero(b + 1, n_)};
        roughness_ = roughness;
        // Interpolation only: every series shares H's factors.
        if (!roughness) {
            interpolationFactors_ = H_;
            interpolationSolvable_ = factorLDLT(interpolationFactors_);
        }
        sites_ = std::make_shared<const SmoothingSpline::Sites>(SmoothingSpline::Sites{x_, knots_});
    }

    void setValues(const Eigen::Ref<const Eigen::VectorXd>& y) {
        if (y.size() != n_)
            throw Error("smoothing spline: " + std::to_string(y.size()) + " values for " + std::to_string(n_) + " sites");
        checkFinite(y);
        y_ = y;
        rhs_ = weightedCollocationTransposed(y_);
    }

    // The interpolant (p = 0) of every column of `values` (one row per site, as interpolateColumns checks),
    // each column's arithmetic that of setValues and solve(0), but each sparse product done once for the
    // whole table.
    std::vector<SmoothingSpline> interpolate(const Eigen::Ref<const Eigen::MatrixXd>& values) const {
        for (Eigen::Index j = 0; j < values.cols(); ++j) checkFinite(values.col(j));
        if (!interpolationSolvable_) makeSpline(Trial{});  // throws, naming the sites
        const RowMajorMatrix rows = values;
        RowMajorMatrix c = weightedCollocationTransposed(rows);
        solveLDLT(interpolationFactors_, c);
        const Eigen::VectorXd squares = weightedResidualSquares(rows, c);
        std::vector<SmoothingSpline> splines;
        splines.reserve(static_cast<std::size_t>(values.cols()));
        for (Eigen::Index j = 0; j < values.cols(); ++j) {
            SmoothingSpline& s = splines.emplace_back(SmoothingSpline());
            s.halfOrder_ = m_;
            s.sites_ = sites_;
            s.coefficients_ = toBSplineCoefficients(c, j);
            s.meanSquaredResidual_ = squares(j) / n_;
        }
        return splines;
    }

    const Eigen::VectorXd& getX() const { return x_; }

    // p that weighs the roughness like the data term: trace(H) / trace(P).
    double naturalScale() const { return H_.band.row(0).sum() / P_.band.row(0).sum(); }

    Trial solve(double p) const {
        if (p != 0 && !roughness_) throw Error("smoothing spline: a fit set up for interpolation only was asked to smooth");
        Trial trial;
        trial.p = p;
        SymmetricBand smoothing;
        const SymmetricBand* factors = &interpolationFactors_;
        if (roughness_) {
            smoothing = {H_.b, H_.band + p * P_.band};
            if (!factorLDLT(smoothing)) return trial;
            factors = &smoothing;
        } else if (!interpolationSolvable_) {
            return trial;
        }
        const SymmetricBand& g = *factors;
        trial.solved = true;
        trial.c = rhs_;
        solveLDLT(g, trial.c);
        trial.meanSquaredResidual = weightedResidualSquares(y_, trial.c)(0) / n_;
        trial.residualDegreesOfFreedom = p > 0 ? p * bandOfInverse(g).dot(P_) : 0.0;
        return trial;
    }

    SmoothingSpline makeSpline(const Trial& trial) const {
        if (!trial.solved) {
            // No smoothing parameter factored: the sites' spacing is beyond what double precision resolves.
            Eigen::Index gap = 0;
            (x_.tail(n_ - 1) - x_.head(n_ - 1)).minCoeff(&gap);
            throw Error("smoothing spline: no fit in double precision for these sites; the closest are " +
                        sample("x", gap, x_(gap)) + " and " + sample("x", gap + 1, x_(gap + 1)) + " over a span of " +
                        std::to_string(x_(n_ - 1) - x_(0)) + " (sites too close together, too far apart or too large)");
        }
        SmoothingSpline s;
        s.halfOrder_ = m_;
        s.sites_ = sites_;
        s.coefficients_ = toBSplineCoefficients(trial.c, 0);
        s.smoothingParameter_ = trial.p;
        s.meanSquaredResidual_ = trial.meanSquaredResidual;
        s.residualDegreesOfFreedom_ = trial.residualDegreesOfFreedom;
        return s;
    }

    int size() const { return n_; }

private:
    static void checkFinite(const Eigen::Ref<const Eigen::VectorXd>& y) {
        for (Eigen::Index i = 0; i < y.size(); ++i)
            if (!std::isfinite(y(i))) throw Error("smoothing spline: value " + sample("y", i, y(i)) + " is not finite");
    }

    // Z (B-splines x natural basis). At each end only the 2m - 1 B-splines nearest to it have derivatives of
    // order m..2m-2 there; their coefficients must satisfy the m - 1 natural conditions, and an orthonormal
    // basis of that null space (m vectors, from the SVD of the row-normalized conditions) gives m
    // well-scaled natural basis functions. (Solving for some coefficients in terms of others instead gives
    // combinations with coefficients ~ 1/h^(m-1) and a badly conditioned system.) The other B-splines are
    // natural already: B-spline g in [2m - 1, count - 2m] is natural basis function g - m + 1. Z is kept as
    // the two ends' null spaces: B-spline s from an end (s < 2m - 1) is sum_f end(s, f) N_f, f counted from
    // that end too.
    void buildNaturalEnds(int order, int count) {
        for (const bool left : {true, false}) {
            const int span = left ? order - 1 : count - 1;
            const double end = left ? x_(0) : x_(n_ - 1);
            auto global = [&](int s) { return left ? s : count - 1 - s; };  // B-spline s from this end
            Eigen::MatrixXd conditions = Eigen::MatrixXd::Zero(std::max(m_ - 1, 1), 2 * m_ - 1);
            for (int q = 0; q < m_ - 1; ++q) {
                const Window d = basisOnSpan(knots_, order, span, end, m_ + q);
                for (int s = 0; s < 2 * m_ - 1; ++s) conditions(q, s) = d[global(s) - (span - order + 1)];
                conditions.row(q).normalize();
            }
            const Eigen::JacobiSVD<Eigen::MatrixXd> svd(conditions, Eigen::ComputeFullV);
            (left ? leftEnd_ : rightEnd_) = svd.matrixV().rightCols(m_);
        }
    }

    // B-spline g as natural basis functions: (column, weight) pairs in increasing column order, the order in
    // which sums over them are taken.
    template <typename Visit>
    void forEachNaturalColumn(int g, int count, Visit visit) const {
        if (g < 2 * m_ - 1) {
            for (int f = 0; f < m_; ++f) visit(f, leftEnd_(g, f));
        } else if (g > count - 2 * m_) {
            for (int f = m_ - 1; f >= 0; --f) visit(n_ - 1 - f, rightEnd_(count - 1 - g, f));
        } else {
            visit(g - m_ + 1, 1.0);
        }
    }

    SparseMatrix naturalBasisMatrix(int count) const {
        Triplets z;
        for (int g = 0; g < count; ++g) forEachNaturalColumn(g, count, [&](int c, double v) { z.emplace_back(g, c, v); });
        SparseMatrix Z(count, n_);
        Z.setFromTriplets(z.begin(), z.end());
        return Z;
    }

    // N(i, c) = N_c(x_i), row by row: each row's non-zeros lie in rowValues_.cols() columns from rowFirst_[i].
    void buildCollocation(int order) {
        const int count = n_ + 2 * m_ - 2;
        std::vector<int> spans(static_cast<std::size_t>(n_)), last(static_cast<std::size_t>(n_));
        rowFirst_.assign(static_cast<std::size_t>(n_), n_);
        int width = 1;
        for (int i = 0; i < n_; ++i) {
            const std::size_t row = static_cast<std::size_t>(i);
            spans[row] = findSpan(x_, order, x_(i));
            for (int g = spans[row] - order + 1; g <= spans[row]; ++g)
                forEachNaturalColumn(g, count, [&](int c, double) {
                    rowFirst_[row] = std::min(rowFirst_[row], c);
                    last[row] = std::max(last[row], c);
                });
            width = std::max(width, last[row] - rowFirst_[row] + 1);
        }
        rowValues_ = Eigen::MatrixXd::Zero(n_, width);
        for (int i = 0; i < n_; ++i) {
            const std::size_t row = static_cast<std::size_t>(i);
            rowFirst_[row] = std::min(rowFirst_[row], n_ - width);
            const Window values = basisOnSpan(knots_, order, spans[row], x_(i), 0);
            for (int r = 0; r < order; ++r)
                forEachNaturalColumn(spans[row] - order + 1 + r, count,
                                     [&](int c, double v) { rowValues_(i, c - rowFirst_[row]) += values[static_cast<std::size_t>(r)] * v; });
        }
    }

    // N^T (W v) for a column or a table of columns (row-major: each step one row of every column).
    template <typename Values>
    RowMajorMatrix weightedCollocationTransposed(const Values& v) const {
        const Eigen::Index columns = v.cols();
        RowMajorMatrix result = RowMajorMatrix::Zero(n_, columns);
        Eigen::VectorXd weighted(columns);
        for (int i = 0; i < n_; ++i) {
            for (Eigen::Index j = 0; j < columns; ++j) weighted(j) = w_(i) * rowOf(v, i)[j];
            for (Eigen::Index c = 0; c < rowValues_.cols(); ++c)
                addScaledRow(rowOf(result, rowFirst_[static_cast<std::size_t>(i)] + c), weighted.data(), rowValues_(i, c),
                             columns);
        }
        return result;
    }

    // sum_i w_i (v - N c)_ij^2 for each column j: each column's residual v - (N c) formed and weighed as
    // the sparse products did, one column at a time (no table of residuals).
    template <typename Values, typename Coefficients>
    Eigen::VectorXd weightedResidualSquares(const Values& v, const Coefficients& c) const {
        Eigen::VectorXd squares(v.cols()), residual(n_);
        for (Eigen::Index j = 0; j < v.cols(); ++j) {
            for (int i = 0; i < n_; ++i) {
                const Eigen::Index first = rowFirst_[static_cast<std::size_t>(i)];
                double r = v(i, j);
                for (Eigen::Index k = 0; k < rowValues_.cols(); ++k) r -= rowValues_(i, k) * c(first + k, j);
                residual(i) = r;
            }
            squares(j) = residual.cwiseAbs2().dot(w_);
        }
        return squares;
    }

    // Z c: the B-spline coefficients of column `column` of natural-basis coefficients c.
    template <typename Coefficients>
    Eigen::VectorXd toBSplineCoefficients(const Coefficients& c, Eigen::Index column) const {
        const int count = n_ + 2 * m_ - 2;
        Eigen::VectorXd a = Eigen::VectorXd::Zero(count);
        for (int g = 0; g < count; ++g)
            forEachNaturalColumn(g, count, [&](int natural, double v) { a(g) += v * c(natural, column); });
        return a;
    }

    // Omega(g, h) = integral over [x_0, x_{n-1}] of B_g^(m) B_h^(m), interval by interval.
    SparseMatrix buildRoughness(int order, int count) const {
        const auto rule = gaussLegendre(m_);
        Triplets omega;
        for (int i = 0; i + 1 < n_; ++i) {
            const int span = order - 1 + i, first = span - order + 1;
            const double half = (x_(i + 1) - x_(i)) / 2;
            for (const auto& [node, weight] : rule) {
                const Window d = basisOnSpan(knots_, order, span, x_(i) + half * (1 + node), m_);
                for (int r = 0; r < order; ++r)
                    for (int s = 0; s < order; ++s) omega.emplace_back(first + r, first + s, weight * half * d[r] * d[s]);
            }
        }
        SparseMatrix omegaMatrix(count, count);
        omegaMatrix.setFromTriplets(omega.begin(), omega.end());
        return omegaMatrix;
    }

    int m_ = 0, n_ = 0;
    bool roughness_ = true;
    bool interpolationSolvable_ = false;
    SymmetricBand interpolationFactors_;  // H = L D L^T, without roughness
    Eigen::VectorXd x_, y_, w_, knots_, rhs_;
    Eigen::MatrixXd leftEnd_, rightEnd_;  // Z at the ends ((2m - 1) x m each), buildNaturalEnds
    std::vector<int> rowFirst_;           // N's rows, buildCollocation
    Eigen::MatrixXd rowValues_;
    SymmetricBand H_, P_;
    std::shared_ptr<const SmoothingSpline::Sites> sites_;  // what the fitted splines share
};

namespace {

// The trial minimizing `criterion` over p = scale 10^e, scale = trace(H) / trace(P): e on a grid from -10
// (interpolation for all practical purposes) to 10 (near the polynomial limit; beyond it the polynomial
// part of the solution drowns in rounding, as in GCVSPL), then a golden-section search in e around the
// best grid point down to 1e-6. With `tryInterpolation`, p = 0 competes too.
template <typename Criterion>
NaturalSplineFitter::Trial minimize(const NaturalSplineFitter& fitter, Criterion criterion, bool tryInterpolation) {
    const double scale = fitter.naturalScale();
    constexpr double lowest = -10, highest = 10, step = 0.25;
    auto trialAt = [&](double e) { return fitter.solve(scale * std::pow(10.0, e)); };
    auto valueOf = [&](const NaturalSplineFitter::Trial& t) {
        return t.solved ? criterion(t) : std::numeric_limits<double>::infinity();
    };
    NaturalSplineFitter::Trial best = fitter.solve(0);
    double bestValue = tryInterpolation ? valueOf(best) : std::numeric_limits<double>::infinity(), bestE = lowest;
    for (double e = lowest; e <= highest; e += step) {
        NaturalSplineFitter::Trial trial = trialAt(e);
        const double value = valueOf(trial);
        if (value < bestValue) best = std::move(trial), bestValue = value, bestE = e;
    }
    if (best.p == 0) return best;
    const double goldenFraction = (std::sqrt(5.0) - 1) / 2;
    double a = std::max(lowest, bestE - step), d = std::min(highest, bestE + step);
    double b = d - goldenFraction * (d - a), c = a + goldenFraction * (d - a);
    NaturalSplineFitter::Trial tb = trialAt(b), tc = trialAt(c);
    double fb = valueOf(tb), fc = valueOf(tc);
    while (d - a > 1e-6) {
        if (fb <= fc) {
            d = c, c = b, tc = std::move(tb), fc = fb;
            b = d - goldenFraction * (d - a), tb = trialAt(b), fb = valueOf(tb);
        } else {
            a = b, b = c, tb = std::move(tc), fb = fc;
            c = a + goldenFraction * (d - a), tc = trialAt(c), fc = valueOf(tc);
        }
    }
    if (fb < bestValue) best = std::move(tb), bestValue = fb;
    if (fc < bestValue) best = std::move(tc);
    return best;
}

}  // namespace

SmoothingSpline SmoothingSpline::fitForSmoothingParameter(int degree, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                          const Eigen::Ref<const Eigen::VectorXd>& y, double p,
                                                          const Eigen::Ref<const Eigen::VectorXd>& weights) {
    const NaturalSplineFitter fitter(degree, x, y, weights);
    if (!(std::isfinite(p) && p >= 0))
        throw Error("smoothing spline: smoothing parameter " + std::to_string(p) + "; expected a finite value >= 0");
    const NaturalSplineFitter::Trial trial = fitter.solve(p);
    if (!trial.solved)
        throw Error("smoothing spline: smoothing parameter " + std::to_string(p) + " is beyond what double precision " +
                    "resolves for these sites (p trace(P) / trace(H) = " + std::to_string(p / fitter.naturalScale()) + ")");
    return fitter.makeSpline(trial);
}

SmoothingSpline SmoothingSpline::fitFromGCV(int degree, const Eigen::Ref<const Eigen::VectorXd>& x,
                                            const Eigen::Ref<const Eigen::VectorXd>& y,
                                            const Eigen::Ref<const Eigen::VectorXd>& weights) {
    const NaturalSplineFitter fitter(degree, x, y, weights);
    const double n = fitter.size();
    auto gcv = [n](const NaturalSplineFitter::Trial& t) {
        const double dofFraction = t.residualDegreesOfFreedom / n;
        return t.meanSquaredResidual / (dofFraction * dofFraction);
    };
    return fitter.makeSpline(minimize(fitter, gcv, false));
}

SmoothingSpline SmoothingSpline::fitFromErrorVariance(int degree, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                      const Eigen::Ref<const Eigen::VectorXd>& y, double variance,
                                                      const Eigen::Ref<const Eigen::VectorXd>& weights) {
    const NaturalSplineFitter fitter(degree, x, y, weights);
    if (!(std::isfinite(variance) && variance >= 0))
        throw Error("smoothing spline: error variance " + std::to_string(variance) +
                    "; expected a finite value >= 0 (use fitFromGCV when it is unknown)");
    // With no error the estimated mean squared error is the residual alone, smallest when interpolating.
    if (variance == 0) return fitter.makeSpline(fitter.solve(0));  // p = 0: H alone is positive definite
    const double n = fitter.size();
    auto meanSquaredError = [n, variance](const NaturalSplineFitter::Trial& t) {
        return t.meanSquaredResidual - variance * (2 * t.residualDegreesOfFreedom / n - 1);
    };
    return fitter.makeSpline(minimize(fitter, meanSquaredError, true));
}

namespace {

void checkOneRowPerSite(Eigen::Index rows, Eigen::Index sites) {
    if (rows != sites)
        throw Error("smoothing spline: " + std::to_string(rows) + " rows of values for " + std::to_string(sites) + " sites");
}

}  // namespace

std::vector<SmoothingSpline> SmoothingSpline::interpolateColumns(int degree, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                                const Eigen::Ref<const Eigen::MatrixXd>& values) {
    checkOneRowPerSite(values.rows(), x.size());  // a table of the wrong height is reported before bad sites
    return SplineInterpolation(degree, x).interpolate(values);
}

SplineInterpolation::SplineInterpolation(int degree, const Eigen::Ref<const Eigen::VectorXd>& x)
    : degree_(degree), fitter_(std::make_shared<const NaturalSplineFitter>(degree, x, Eigen::VectorXd(), /*roughness=*/false)) {}

std::vector<SmoothingSpline> SplineInterpolation::interpolate(const Eigen::Ref<const Eigen::MatrixXd>& values) const {
    checkOneRowPerSite(values.rows(), getX().size());
    return fitter_->interpolate(values);
}

const Eigen::VectorXd& SplineInterpolation::getX() const { return fitter_->getX(); }

namespace {

// Where t lies among a spline's sites: what every spline on the same sites shares. Outside the sites the
// natural continuation is the Taylor polynomial of degree m - 1 at the end, so only derivatives below m
// are taken there.
struct SpanLocation {
    int order = 0, lowest = 0, evaluated = 0;  // the derivatives wanted from `lowest`; `evaluated`: the highest taken on the span
    int span = 0;
    bool outside = false;
    double end = 0, t = 0;
    std::optional<SpanRecurrence> recurrence;

    // The derivatives lowest..highest (0 <= lowest <= highest) at t: a caller after one derivative skips the
    // lower ones' de Boor passes.
    SpanLocation(const Eigen::VectorXd& x, const Eigen::VectorXd& knots, int m, double time, int lowestWanted, int highest)
        : order(2 * m), lowest(lowestWanted), t(time) {
        if (highest < 0) throw Error("smoothing spline: derivative order " + std::to_string(highest) + "; expected >= 0");
        if (!std::isfinite(t)) throw Error("smoothing spline: evaluated at a non-finite time");
        const Eigen::Index n = x.size();
        outside = t < x(0) || t > x(n - 1);
        end = t < x(0) ? x(0) : x(n - 1);
        span = findSpan(x, order, outside ? end : t);
        evaluated = outside ? m - 1 : std::min(order - 1, highest);
        recurrence.emplace(knots, order, span, outside ? end : t, std::min(lowest, evaluated), evaluated);
    }

    // derivatives[lowest..highest] of the spline with these B-spline coefficients.
    void evaluate(const Eigen::VectorXd& coefficients, int highest, double* derivatives) const {
        Window window{};
        for (int r = 0; r < order; ++r) window[static_cast<std::size_t>(r)] = coefficients(span - order + 1 + r);
        std::array<double, kMaxOrder> atSpan{};
        recurrence->apply(window, atSpan.data());
        for (int d = lowest; d <= highest; ++d) {
            double value = 0;
            if (!outside) {
                value = d <= evaluated ? atSpan[static_cast<std::size_t>(d)] : 0.0;
            } else {
                double term = 1;
                for (int j = d; j <= evaluated; ++j) {
                    value += atSpan[static_cast<std::size_t>(j)] * term;
                    term *= (t - end) / (j - d + 1);
                }
            }
            derivatives[d] = value;
        }
    }
};

}  // namespace

double SmoothingSpline::calcValue(double t) const {
    double value = 0;
    calcDerivatives(t, 0, &value);
    return value;
}

double SmoothingSpline::calcDerivative(double t, int order) const {
    if (order < 0) throw Error("smoothing spline: derivative order " + std::to_string(order) + "; expected >= 0");
    if (order >= 2 * halfOrder_) {
        if (!std::isfinite(t)) throw Error("smoothing spline: evaluated at a non-finite time");
        return 0;
    }
    std::array<double, kMaxOrder> derivatives;
    SpanLocation(sites_->x, sites_->knots, halfOrder_, t, order, order).evaluate(coefficients_, order, derivatives.data());
    return derivatives[static_cast<std::size_t>(order)];
}

void SmoothingSpline::calcDerivatives(double t, int highest, double* derivatives) const {
    SpanLocation(sites_->x, sites_->knots, halfOrder_, t, 0, highest).evaluate(coefficients_, highest, derivatives);
}

void SmoothingSpline::calcDerivatives(const SmoothingSpline* splines, std::size_t count, double t, int highest,
                                      double* derivatives) {
    std::optional<SpanLocation> shared;
    for (std::size_t j = 0; j < count; ++j) {
        const SmoothingSpline& s = splines[j];
        const bool sameSites = j > 0 && s.sites_ == splines[j - 1].sites_ && s.halfOrder_ == splines[j - 1].halfOrder_;
        if (!sameSites) shared.emplace(s.sites_->x, s.sites_->knots, s.halfOrder_, t, 0, highest);
        shared->evaluate(s.coefficients_, highest, derivatives + j * static_cast<std::size_t>(highest + 1));
    }
}

double SmoothingSpline::getGeneralizedCrossValidation() const {
    if (residualDegreesOfFreedom_ <= 0) return std::numeric_limits<double>::quiet_NaN();
    const double dofFraction = residualDegreesOfFreedom_ / static_cast<double>(sites_->x.size());
    return meanSquaredResidual_ / (dofFraction * dofFraction);
}

double SmoothingSpline::getErrorVarianceEstimate() const {
    if (residualDegreesOfFreedom_ <= 0) return std::numeric_limits<double>::quiet_NaN();
    return meanSquaredResidual_ * static_cast<double>(sites_->x.size()) / residualDegreesOfFreedom_;
}

}  // namespace sinew

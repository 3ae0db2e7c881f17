#pragma once
// Natural smoothing splines of odd degree with the smoothing chosen by generalized cross-validation, a
// known error variance, or given outright: the splines of Woltring's GCVSPL (Adv. Eng. Software 8:104-113,
// 1986) that OpenSim's GCVSpline / SimTK::SplineFitter fit, computed here with B-splines and banded
// factorizations (docs/signal-processing.md, "Smoothing splines").
#include <Eigen/Core>
#include <memory>
#include <vector>

namespace sinew {

class NaturalSplineFitter;
class SmoothingSpline;

// The interpolating splines' set-up on one set of sites: the basis and its factorization, the costly part
// of SmoothingSpline::interpolateColumns, kept to fit more tables sampled at the same sites (each column's
// arithmetic is the same either way). Immutable; copies share the set-up.
class SplineInterpolation {
public:
    // Throws sinew::Error as interpolateColumns does for the degree and the sites.
    SplineInterpolation(int degree, const Eigen::Ref<const Eigen::VectorXd>& x);
    // interpolateColumns(degree, x, values).
    std::vector<SmoothingSpline> interpolate(const Eigen::Ref<const Eigen::MatrixXd>& values) const;
    int getDegree() const { return degree_; }
    const Eigen::VectorXd& getX() const;

private:
    int degree_;
    std::shared_ptr<const NaturalSplineFitter> fitter_;
};

// The natural spline s of degree 2m - 1 (m = 1..4: linear, cubic, quintic, heptic) with knots at the data
// sites x_0 < ... < x_{n-1} that minimizes
//     sum_i w_i (y_i - s(x_i))^2 + p * integral (d^m s / dt^m)^2 dt
// for a smoothing parameter p >= 0: p = 0 interpolates, p -> infinity tends to the weighted least-squares
// polynomial of degree m - 1. Natural: outside [x_0, x_{n-1}] s continues as the polynomial of degree
// m - 1 it joins there. Immutable once fitted; evaluating allocates nothing.
//
// Every fit needs n >= 2m finite samples with strictly increasing sites and positive weights (empty
// weights: all 1) and throws sinew::Error naming the offending sample otherwise.
class SmoothingSpline {
public:
    static constexpr int kMaxHalfOrder = 4;

    // p given (Woltring's mode 1; SimTK::SplineFitter::fitForSmoothingParameter).
    static SmoothingSpline fitForSmoothingParameter(int degree, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                    const Eigen::Ref<const Eigen::VectorXd>& y, double p,
                                                    const Eigen::Ref<const Eigen::VectorXd>& weights = Eigen::VectorXd());
    // p minimizing the generalized cross-validation function (RSS/n) / (1 - trace(A)/n)^2, A the influence
    // matrix y -> s(x) (mode 2; fitFromGCV; OpenSim's GCVSpline with a negative error variance).
    static SmoothingSpline fitFromGCV(int degree, const Eigen::Ref<const Eigen::VectorXd>& x,
                                      const Eigen::Ref<const Eigen::VectorXd>& y,
                                      const Eigen::Ref<const Eigen::VectorXd>& weights = Eigen::VectorXd());
    // p minimizing the estimate of the true mean squared error RSS/n - variance (2 (1 - trace(A)/n) - 1)
    // for a known error variance >= 0 (mode 3; fitFromErrorVariance). Variance 0 interpolates: OpenSim's
    // GCVSpline default, which its inverse dynamics tool uses for the coordinates.
    static SmoothingSpline fitFromErrorVariance(int degree, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                const Eigen::Ref<const Eigen::VectorXd>& y, double variance,
                                                const Eigen::Ref<const Eigen::VectorXd>& weights = Eigen::VectorXd());

    // The interpolating splines (fitFromErrorVariance with variance 0, all weights 1) of every column of
    // `values` (n rows, one per site): the sites' basis is built once for all the columns, which makes a
    // motion's hundreds of coordinates cost little more than one.
    static std::vector<SmoothingSpline> interpolateColumns(int degree, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                           const Eigen::Ref<const Eigen::MatrixXd>& values);

    double calcValue(double t) const;
    // d^order s / dt^order at t for order >= 0 (zero above the degree); throws sinew::Error for order < 0.
    double calcDerivative(double t, int order) const;
    // s and its derivatives of orders 1..highest at t into derivatives[0..highest], from one look-up of t's
    // interval (each value bitwise what calcDerivative gives).
    void calcDerivatives(double t, int highest, double* derivatives) const;
    // The derivatives 0..highest at t of splines[0..count): derivatives[j * (highest + 1) + d] for splines[j]
    // (a column-major (highest + 1) x count matrix), each bitwise what calcDerivative gives. Splines that
    // interpolateColumns fitted together share their sites: t's interval and the knot-dependent factors of
    // de Boor's recurrence are then found once for all of them.
    static void calcDerivatives(const SmoothingSpline* splines, std::size_t count, double t, int highest,
                                double* derivatives);

    int getDegree() const { return 2 * halfOrder_ - 1; }
    const Eigen::VectorXd& getX() const { return sites_->x; }
    double getSmoothingParameter() const { return smoothingParameter_; }
    // Fit statistics in Woltring's terms: the weighted mean squared residual RSS/n, the residual degrees of
    // freedom n - trace(A) (0 when interpolating, n - m for the polynomial limit), the GCV value and the
    // error variance estimate RSS / (n - trace(A)) (both NaN when interpolating).
    double getMeanSquaredResidual() const { return meanSquaredResidual_; }
    double getResidualDegreesOfFreedom() const { return residualDegreesOfFreedom_; }
    double getGeneralizedCrossValidation() const;
    double getErrorVarianceEstimate() const;

private:
    SmoothingSpline() = default;
    friend class NaturalSplineFitter;

    struct Sites {
        Eigen::VectorXd x;      // data sites (n)
        Eigen::VectorXd knots;  // B-spline knots: x_0 and x_{n-1} repeated 2m times, interior sites once (n + 4m - 2)
    };

    int halfOrder_ = 0;                   // m; the spline order is 2m
    std::shared_ptr<const Sites> sites_;  // shared by the splines of one fit's columns
    Eigen::VectorXd coefficients_;        // B-spline coefficients (n + 2m - 2); they satisfy the natural end conditions
    double smoothingParameter_ = 0;
    double meanSquaredResidual_ = 0;
    double residualDegreesOfFreedom_ = 0;
};

}  // namespace sinew

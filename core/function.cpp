#include "sinew/core/function.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// OpenSim's SimmMacros.h: knot gaps are floored at kTinyGap, and an abscissa within kRoundoff of an end
// knot is taken as that knot. Kept so splines evaluate as OpenSim's do.
constexpr double kTinyGap = 1e-7;
constexpr double kRoundoff = 2e-13;

void requireFinite(const std::vector<double>& values, const std::string& what) {
    for (double v : values)
        if (!std::isfinite(v)) throw Error("function: " + what + " must be finite (got " + std::to_string(v) + ")");
}

void checkKnots(const std::vector<double>& x, const std::vector<double>& y, const char* kind) {
    const std::string label = std::string(kind) + ": ";
    if (x.size() != y.size())
        throw Error(label + "x has " + std::to_string(x.size()) + " values but y has " + std::to_string(y.size()));
    if (x.size() < 2) throw Error(label + "needs at least 2 knots, got " + std::to_string(x.size()));
    requireFinite(x, label + "x");
    requireFinite(y, label + "y");
    for (std::size_t i = 1; i < x.size(); ++i)
        if (!(x[i] > x[i - 1]))
            throw Error(label + "x must be strictly increasing (x[" + std::to_string(i) + "] = " + std::to_string(x[i]) +
                        " after " + std::to_string(x[i - 1]) + ")");
}

}  // namespace

Function Function::constant(double value) {
    Function f;
    f.type_ = Type::Constant;
    f.coefficients_ = {value};
    requireFinite(f.coefficients_, "constant value");
    return f;
}

Function Function::linear(double slope, double intercept) {
    Function f;
    f.type_ = Type::Linear;
    f.coefficients_ = {slope, intercept};
    requireFinite(f.coefficients_, "linear function coefficients");
    return f;
}

Function Function::polynomial(std::vector<double> coefficientsHighestFirst) {
    if (coefficientsHighestFirst.empty()) throw Error("polynomial: needs at least one coefficient");
    requireFinite(coefficientsHighestFirst, "polynomial coefficients");
    Function f;
    f.type_ = Type::Polynomial;
    f.coefficients_ = std::move(coefficientsHighestFirst);
    return f;
}

Function Function::simmSpline(std::vector<double> x, std::vector<double> y) {
    checkKnots(x, y, "SimmSpline");
    return fitSpline(Type::SimmSpline, std::move(x), std::move(y));
}

Function Function::naturalCubicSpline(std::vector<double> x, std::vector<double> y) {
    checkKnots(x, y, "NaturalCubicSpline");
    return fitSpline(Type::NaturalCubicSpline, std::move(x), std::move(y));
}

// Forsythe, Malcolm and Moler, Computer Methods for Mathematical Computations (1977), SPLINE: a tridiagonal
// system for the second-derivative terms, whose end rows match the third derivative of the cubic through
// the four end knots (zero with only three knots). OpenSim's SimmSpline::calcCoefficients is this routine.
Function Function::fitSpline(Type type, std::vector<double> x, std::vector<double> y) {
    Function f;
    f.type_ = type;
    const std::size_t n = x.size();
    std::vector<double> b(n), c(n), d(n);
    if (n == 2) {
        const double slope = (y[1] - y[0]) / std::max(kTinyGap, x[1] - x[0]);
        b = {slope, slope};
        c = {0, 0};
        d = {0, 0};
    } else {
        const std::size_t last = n - 1;
        // d: knot gaps (the off-diagonal), b: diagonal, c: right-hand side (divided differences).
        d[0] = std::max(kTinyGap, x[1] - x[0]);
        c[1] = (y[1] - y[0]) / d[0];
        for (std::size_t i = 1; i < last; ++i) {
            d[i] = std::max(kTinyGap, x[i + 1] - x[i]);
            b[i] = 2.0 * (d[i - 1] + d[i]);
            c[i + 1] = (y[i + 1] - y[i]) / d[i];
            c[i] = c[i + 1] - c[i];
        }
        b[0] = -d[0];
        b[last] = -d[last - 1];
        c[0] = 0.0;
        c[last] = 0.0;
        if (n > 3) {
            const double gap31 = std::max(kTinyGap, x[3] - x[1]), gap20 = std::max(kTinyGap, x[2] - x[0]);
            const double gap30 = std::max(kTinyGap, x[3] - x[0]);
            const double gapEnd1 = std::max(kTinyGap, x[last] - x[n - 3]), gapEnd2 = std::max(kTinyGap, x[last - 1] - x[n - 4]);
            const double gapEnd3 = std::max(kTinyGap, x[last] - x[n - 4]);
            c[0] = (c[2] / gap31 - c[1] / gap20) * d[0] * d[0] / gap30;
            c[last] = -(c[last - 1] / gapEnd1 - c[n - 3] / gapEnd2) * d[last - 1] * d[last - 1] / gapEnd3;
        }
        for (std::size_t i = 1; i < n; ++i) {  // forward elimination
            const double t = d[i - 1] / b[i - 1];
            b[i] -= t * d[i - 1];
            c[i] -= t * c[i - 1];
        }
        c[last] /= b[last];  // back substitution
        for (std::size_t i = last; i-- > 0;) c[i] = (c[i] - d[i] * c[i + 1]) / b[i];
        // Cubic coefficients per segment.
        b[last] = (y[last] - y[last - 1]) / d[last - 1] + d[last - 1] * (c[last - 1] + 2.0 * c[last]);
        for (std::size_t i = 0; i < last; ++i) {
            b[i] = (y[i + 1] - y[i]) / d[i] - d[i] * (c[i + 1] + 2.0 * c[i]);
            d[i] = (c[i + 1] - c[i]) / d[i];
            c[i] *= 3.0;
        }
        c[last] *= 3.0;
        d[last] = d[last - 1];
    }
    f.x_ = std::move(x);
    f.y_ = std::move(y);
    f.b_ = std::move(b);
    f.c_ = std::move(c);
    f.d_ = std::move(d);
    return f;
}

Function Function::multipliedBy(double scale) const {
    if (!std::isfinite(scale)) throw Error("MultiplierFunction: scale must be finite (got " + std::to_string(scale) + ")");
    Function f = *this;
    f.scale_ *= scale;
    return f;
}

double Function::calcValue(double x) const { return scale_ * evaluateUnscaled(x, 0); }

double Function::calcDerivative(double x, int order) const {
    if (order != 1 && order != 2)
        throw Error("function: derivative order must be 1 or 2 (got " + std::to_string(order) + ")");
    return scale_ * evaluateUnscaled(x, order);
}

double Function::evaluateUnscaled(double x, int order) const {
    switch (type_) {
        case Type::Constant: return order == 0 ? coefficients_[0] : 0.0;
        case Type::Linear:
            return order == 0 ? coefficients_[0] * x + coefficients_[1] : order == 1 ? coefficients_[0] : 0.0;
        case Type::Polynomial: {
            // Horner's rule carrying the first two derivatives along.
            double p = 0, dp = 0, ddp = 0;
            for (double c : coefficients_) {
                ddp = ddp * x + 2 * dp;
                dp = dp * x + p;
                p = p * x + c;
            }
            return order == 0 ? p : order == 1 ? dp : ddp;
        }
        case Type::SimmSpline:
        case Type::NaturalCubicSpline: return evaluateSpline(x, order);
    }
    return 0.0;
}

// As OpenSim's SimmSpline::calcValue/calcDerivative: linear beyond the end knots (second derivative zero),
// the end knot's own values within kRoundoff of it, otherwise the segment found by bisection.
double Function::evaluateSpline(double x, int order) const {
    const std::size_t n = x_.size();
    const std::size_t last = n - 1;
    auto endValue = [&](std::size_t k, double dx, bool outside) {
        if (order == 0) return y_[k] + dx * b_[k];
        if (order == 1) return b_[k];
        return outside ? 0.0 : 2.0 * c_[k];
    };
    if (x < x_[0]) return endValue(0, x - x_[0], true);
    if (x > x_[last]) return endValue(last, x - x_[last], true);
    if (std::abs(x - x_[0]) <= kRoundoff) return endValue(0, 0.0, false);
    if (std::abs(x - x_[last]) <= kRoundoff) return endValue(last, 0.0, false);
    std::size_t k = 0;
    if (n > 2) {
        std::size_t lo = 0, hi = n;
        for (;;) {
            k = (lo + hi) / 2;
            if (x < x_[k]) hi = k;
            else if (x > x_[k + 1]) lo = k;
            else break;
        }
    }
    const double dx = x - x_[k];
    if (order == 0) return y_[k] + dx * (b_[k] + dx * (c_[k] + dx * d_[k]));
    if (order == 1) return b_[k] + dx * (2.0 * c_[k] + 3.0 * dx * d_[k]);
    return 2.0 * c_[k] + 6.0 * dx * d_[k];
}

}  // namespace sinew

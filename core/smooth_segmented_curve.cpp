#include "sinew/core/smooth_segmented_curve.hpp"

#include <algorithm>
#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

double evaluateBezier(const double (&p)[6], double u) {
    const double v = 1 - u, u2 = u * u, v2 = v * v;
    return v2 * v2 * v * p[0] + 5 * v2 * v2 * u * p[1] + 10 * v2 * v * u2 * p[2] + 10 * v2 * u2 * u * p[3] +
           5 * v * u2 * u2 * p[4] + u2 * u2 * u * p[5];
}

double evaluateBezierDerivative(const double (&p)[6], double u) {
    const double v = 1 - u, u2 = u * u, v2 = v * v;
    return 5 * (v2 * v2 * (p[1] - p[0]) + 4 * v2 * v * u * (p[2] - p[1]) + 6 * v2 * u2 * (p[3] - p[2]) +
                4 * v * u2 * u * (p[4] - p[3]) + u2 * u2 * (p[5] - p[4]));
}

std::string describe(const std::string& name, std::size_t segment) {
    return "curve '" + name + "', segment " + std::to_string(segment + 1);
}

}  // namespace

SmoothSegmentedCurve::SmoothSegmentedCurve(std::string name, const std::vector<CurveKnot>& knots,
                                           const std::vector<double>& curviness)
    : name_(std::move(name)) {
    if (knots.size() < 2 || curviness.size() != knots.size() - 1)
        throw Error("curve '" + name_ + "': " + std::to_string(knots.size()) + " knots and " +
                    std::to_string(curviness.size()) + " curviness values, expected two knots or more and one value "
                    "per segment");
    first_ = knots.front();
    last_ = knots.back();
    double integral = 0;
    for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
        const CurveKnot& a = knots[k];
        const CurveKnot& b = knots[k + 1];
        const double c = curviness[k];
        if (!(b.x > a.x) || !std::isfinite(a.y) || !std::isfinite(b.y) || !std::isfinite(a.slope) ||
            !std::isfinite(b.slope))
            throw Error(describe(name_, k) + ": knots must be finite with x increasing");
        if (!(c >= 0 && c <= 1)) throw Error(describe(name_, k) + ": curviness must lie in [0, 1]");
        // Where the two tangent lines meet (their midpoint when parallel, as OpenSim takes it).
        const double xMeet = std::fabs(a.slope - b.slope) > std::sqrt(2.220446049250313e-16)
                                 ? (b.y - a.y - b.x * b.slope + a.x * a.slope) / (a.slope - b.slope)
                                 : 0.5 * (a.x + b.x);
        const double yMeet = (xMeet - b.x) * b.slope + b.y;
        const double toA = std::hypot(xMeet - a.x, yMeet - a.y), toB = std::hypot(xMeet - b.x, yMeet - b.y);
        const double across = std::hypot(b.x - a.x, b.y - a.y);
        if (!(across > toA && across > toB))
            throw Error(describe(name_, k) + ": the knots' tangents meet outside the corner (an S-shaped segment)");
        const double pull = 0.1 + 0.8 * c;
        Segment s;
        const double xa = a.x + pull * (xMeet - a.x), ya = a.y + pull * (yMeet - a.y);
        const double xb = b.x + pull * (xMeet - b.x), yb = b.y + pull * (yMeet - b.y);
        const double xs[6] = {a.x, xa, xa, xb, xb, b.x}, ys[6] = {a.y, ya, ya, yb, yb, b.y};
        std::copy(xs, xs + 6, s.x);
        std::copy(ys, ys + 6, s.y);
        if (!std::is_sorted(s.x, s.x + 6))
            throw Error(describe(name_, k) + ": x does not increase along the corner");
        s.integralBefore = integral;
        segments_.push_back(s);
        integral += integrateSegment(segments_.back(), 1);
    }
}

SmoothSegmentedCurve::Point SmoothSegmentedCurve::locate(double x) const {
    auto it = std::upper_bound(segments_.begin(), segments_.end(), x,
                               [](double value, const Segment& s) { return value < s.x[5]; });
    if (it == segments_.end()) --it;
    const Segment& s = *it;
    // x(u) increases on [0, 1]: Newton's steps, kept inside a shrinking bracket by bisection.
    double low = 0, high = 1, u = (x - s.x[0]) / (s.x[5] - s.x[0]);
    const double tolerance = 4 * 2.220446049250313e-16 * std::max(std::fabs(s.x[0]), std::fabs(s.x[5]));
    for (int iteration = 0; iteration < 100; ++iteration) {
        const double f = evaluateBezier(s.x, u) - x;
        if (std::fabs(f) <= tolerance) break;
        (f < 0 ? low : high) = u;
        const double slope = evaluateBezierDerivative(s.x, u);
        double next = slope > 0 ? u - f / slope : 0.5 * (low + high);
        if (!(next > low && next < high)) next = 0.5 * (low + high);
        if (high - low < 1e-16) break;
        u = next;
    }
    return {&s, u};
}

double SmoothSegmentedCurve::integrateSegment(const Segment& s, double u) const {
    // ∫_0^u y(t) x'(t) dt: degree 5 + 4 = 9 in t, exact with five Gauss-Legendre points.
    static constexpr double node[5] = {0.046910077030668, 0.2307653449471585, 0.5, 0.7692346550528415,
                                       0.953089922969332};
    static constexpr double weight[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                                         0.23931433524968324, 0.11846344252809454};
    double sum = 0;
    for (int i = 0; i < 5; ++i) {
        const double t = u * node[i];
        sum += weight[i] * evaluateBezier(s.y, t) * evaluateBezierDerivative(s.x, t);
    }
    return u * sum;
}

double SmoothSegmentedCurve::calcValue(double x) const {
    if (x <= first_.x) return first_.y + first_.slope * (x - first_.x);
    if (x >= last_.x) return last_.y + last_.slope * (x - last_.x);
    const Point p = locate(x);
    return evaluateBezier(p.segment->y, p.u);
}

double SmoothSegmentedCurve::calcSlope(double x) const {
    if (x <= first_.x) return first_.slope;
    if (x >= last_.x) return last_.slope;
    const Point p = locate(x);
    return evaluateBezierDerivative(p.segment->y, p.u) / evaluateBezierDerivative(p.segment->x, p.u);
}

double SmoothSegmentedCurve::calcIntegral(double x) const {
    if (x <= first_.x) {
        const double d = x - first_.x;
        return first_.y * d + 0.5 * first_.slope * d * d;
    }
    if (x >= last_.x) {
        const Segment& s = segments_.back();
        const double d = x - last_.x;
        return s.integralBefore + integrateSegment(s, 1) + last_.y * d + 0.5 * last_.slope * d * d;
    }
    const Point p = locate(x);
    return p.segment->integralBefore + integrateSegment(*p.segment, p.u);
}

}  // namespace sinew

// A segment over an ellipsoid, as OpenSim's WrapEllipsoid::wrapLine chooses it: the path lies in the plane
// through the two ends and a point c1 on the surface, picked by the "Frans" (axial), "fan" or hybrid method
// and moved to the quadrant's side. In that plane the path is exact: the tangents from each end to the
// section ellipse and the elliptic arc between them (OpenSim samples that arc with 1 mm chords). See
// docs/wire-paths.md, "Ellipsoid".
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "sinew/core/wrap_object.hpp"
#include "wrap_detail.hpp"

namespace sinew {
namespace {

// OpenSim's constants (WrapEllipsoid.cpp, SimmMacros.h).
constexpr double kMuBlendMin = 0.7073;   // below: the fan alone (must exceed cos 45 deg)
constexpr double kMuBlendMax = 0.9;      // above: the Frans point alone
constexpr int kFanSamples = 300;
constexpr double kSvBoundaryBlend = 0.3;
constexpr double kRoundoff = 2e-13;      // EQUAL_WITHIN_ERROR

bool nearZero(double x) { return std::abs(x) <= kRoundoff; }

// Nearest point of the ellipse (x/a)^2 + (y/b)^2 = 1 to (u, v): the Graphics Gems IV iteration, with the
// points near the axes, where it is unstable, solved directly (as OpenSim's closestPointToEllipse).
Eigen::Vector2d closestPointOnEllipse(double a, double b, double u, double v) {
    const double a2 = a * a, b2 = b * b;
    const bool nearX = nearZero(u), nearY = nearZero(v);
    if (nearX && nearY) return a < b ? Eigen::Vector2d(u < 0 ? -a : a, v) : Eigen::Vector2d(u, v < 0 ? -b : b);
    if (nearX) {
        if (a >= b || std::abs(v) >= b - a2 / b) return {u, v >= 0 ? b : -b};
        const double y = b2 * v / (b2 - a2);
        return {a * std::sqrt(std::abs(1 - (y / b) * (y / b))), y};
    }
    if (nearY) {
        if (b >= a || std::abs(u) >= a - b2 / a) return {u >= 0 ? a : -a, v};
        const double x = a2 * u / (a2 - b2);
        return {x, b * std::sqrt(std::abs(1 - (x / a) * (x / a)))};
    }
    const double a2u2 = a2 * u * u, b2v2 = b2 * v * v;
    double t = (u / a) * (u / a) + (v / b) * (v / b) < 1 ? 0.0 : std::max(a, b) * std::hypot(u, v);
    double P = t + a2, Q = t + b2;
    for (int i = 0; i < 64; ++i) {
        P = t + a2;
        Q = t + b2;
        const double f = P * P * Q * Q - a2u2 * Q * Q - b2v2 * P * P;
        if (std::abs(f) < 1e-9) break;
        t -= f / (2 * (P * Q * (P + Q) - a2u2 * Q - b2v2 * P));
    }
    return {a2 * u / P, b2 * v / Q};
}

// Nearest point of the ellipsoid with semi-axes `r` to `p` (OpenSim's findClosestPoint). A point near a
// coordinate plane (or any point when planeAxis names one) is solved in that plane's elliptic section,
// the narrowest one when several qualify; `unscaledRadii` only ranks those sections.
Eigen::Vector3d closestPointOnEllipsoid(const Eigen::Vector3d& r, const Eigen::Vector3d& p,
                                        const Eigen::Vector3d& unscaledRadii, int planeAxis = -1) {
    if (planeAxis < 0) {
        double narrowest = std::numeric_limits<double>::infinity();
        for (int i = 0; i < 3; ++i)
            if (nearZero(p[i]) && unscaledRadii.sum() - unscaledRadii[i] < narrowest) {
                planeAxis = i;
                narrowest = unscaledRadii.sum() - unscaledRadii[i];
            }
    }
    if (planeAxis >= 0) {
        // The section's two axes in OpenSim's order (y z, z x, x y).
        const int i = (planeAxis + 1) % 3, j = (planeAxis + 2) % 3;
        const Eigen::Vector2d c = closestPointOnEllipse(r[i], r[j], p[i], p[j]);
        Eigen::Vector3d q = p;
        q[i] = c[0];
        q[j] = c[1];
        return q;
    }
    const Eigen::Vector3d r2 = r.cwiseAbs2(), r2p2 = r2.cwiseProduct(p.cwiseAbs2());
    double t = p.cwiseQuotient(r).squaredNorm() < 1 ? 0.0 : r.maxCoeff() * p.norm();
    for (int i = 0; i < 64; ++i) {
        const double P = t + r2[0], Q = t + r2[1], S = t + r2[2];
        const double f = P * P * Q * Q * S * S - r2p2[0] * Q * Q * S * S - r2p2[1] * P * P * S * S - r2p2[2] * P * P * Q * Q;
        if (std::abs(f) < 1e-9) return {r2[0] * p[0] / P, r2[1] * p[1] / Q, r2[2] * p[2] / S};
        const double fp = 2 * (P * Q * S * (Q * S + P * S + P * Q) - r2p2[0] * Q * S * (Q + S) -
                               r2p2[1] * P * S * (P + S) - r2p2[2] * P * Q * (P + Q));
        t -= f / fp;
    }
    // Not converged: the nearest point along the ray from the centre, on the surface.
    return p / p.cwiseQuotient(r).norm();
}

// OpenSim's choice of c1, the surface point the wrapping plane passes through, for the segment whose
// line enters the ellipsoid at e1 and leaves it at e2 (scaled coordinates). `marksSide` is false when c1
// does not tell the side to wrap round (the axial method with its plane crossing outside the chord, where
// OpenSim starts its tangent search from e1 and e2 instead of c1).
struct WrapPlanePoint {
    Eigen::Vector3d c1;
    bool marksSide = true;
};

WrapPlanePoint chooseWrapPlanePoint(const WrapObject& ellipsoid, WrapMethod method, const Eigen::Vector3d& r,
                                     const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& e1,
                                     const Eigen::Vector3d& e2) {
    const Eigen::Vector3d& unscaled = ellipsoid.radii;
    const Eigen::Vector3d e1e2 = e2 - e1;
    const Eigen::Vector3d middle = e1 + 0.5 * e1e2;
    Eigen::Vector3d c1 = Eigen::Vector3d::Zero();
    double fanWeight = -std::numeric_limits<double>::infinity();
    // The coordinate axis most parallel to the segment, and where the chord crosses that axis's plane
    // ("Frans" point sv): the nearest surface point to sv, found in that plane's section.
    Eigen::Index best = 0;
    (p1 - p2).normalized().cwiseAbs().maxCoeff(&best);
    double mu = std::abs((p1 - p2).normalized()[best]);
    const double tBest = -e1[best] / e1e2[best];
    if (method == WrapMethod::Midpoint) {
        c1 = closestPointOnEllipsoid(r, middle, unscaled);
    } else {
        if (method == WrapMethod::Hybrid && mu > kMuBlendMin) {
            // Fade the Frans point out as sv nears the chord's ends, where it would point away from the fan.
            double s = 1;
            if (tBest < 0 || tBest > 1) s = 0;
            else if (tBest < kSvBoundaryBlend) s = tBest / kSvBoundaryBlend;
            else if (tBest > 1 - kSvBoundaryBlend) s = (1 - tBest) / kSvBoundaryBlend;
            if (s < 1) mu = kMuBlendMin + s * (mu - kMuBlendMin);
        }
        const Eigen::Vector3d frans = closestPointOnEllipsoid(r, e1 + tBest * e1e2, unscaled, static_cast<int>(best));
        if (method == WrapMethod::Axial || mu > kMuBlendMin) c1 = frans;
        if (method == WrapMethod::Hybrid && mu < kMuBlendMax) {
            // The fan: the mean direction from points along the chord to their nearest surface points.
            Eigen::Vector3d sum = Eigen::Vector3d::Zero();
            for (int i = 1; i < kFanSamples - 1; ++i) {
                const Eigen::Vector3d sv = e1 + (static_cast<double>(i) / kFanSamples) * e1e2;
                const Eigen::Vector3d blade = closestPointOnEllipsoid(r, sv, unscaled) - sv;
                if (blade.norm() > 0) sum += blade.normalized();
            }
            if (sum.norm() > 0) sum.normalize();
            const Eigen::Vector3d fan = closestPointOnEllipsoid(r, middle + sum, unscaled);
            if (mu <= kMuBlendMin) {
                c1 = fan;
                fanWeight = 1;
            } else {
                const double w = (mu - kMuBlendMin) / (kMuBlendMax - kMuBlendMin);
                c1 = closestPointOnEllipsoid(r, w * c1 + (1 - w) * fan, unscaled);
                fanWeight = 1 - w;
            }
        }
    }
    // A quadrant: a c1 on the wrong side is mirrored to the right one, and pulled back towards the
    // dividing plane by the fan's weight.
    const int axis = ellipsoid.quadrantAxis, sign = ellipsoid.quadrantSign;
    if (sign != 0 && wrap_detail::signOf(c1[axis]) != sign) {
        c1[axis] = -c1[axis];
        if (std::isinf(fanWeight)) fanWeight = 1 - (mu - kMuBlendMin) / (kMuBlendMax - kMuBlendMin);
        fanWeight = std::min(fanWeight, 1.0);
        if (fanWeight > 0) {
            c1[axis] -= fanWeight * c1[axis];
            c1 = closestPointOnEllipsoid(r, c1, unscaled);
        }
    }
    return {c1, method != WrapMethod::Axial || (tBest > 0 && tBest < 1)};
}

// Arc length of the ellipse (A cos s, B sin s) for s from s0 over `angle` in `sense`: Gauss-Legendre on
// panels of at most pi/8 (the integrand is analytic, so this is exact to roundoff).
double calcEllipseArcLength(double A, double B, double s0, double angle, int sense) {
    static const double nodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static const double weights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    const int panels = std::max(1, static_cast<int>(std::ceil(angle / (M_PI / 8))));
    const double h = angle / panels;
    double length = 0;
    for (int k = 0; k < panels; ++k) {
        const double centre = s0 + sense * (k + 0.5) * h;
        for (int i = 0; i < 4; ++i)
            for (const double side : {-1.0, 1.0}) {
                const double s = centre + sense * side * 0.5 * h * nodes[i];
                length += weights[i] * 0.5 * h * std::hypot(A * std::sin(s), B * std::cos(s));
            }
    }
    return length;
}

}  // namespace

WrapSolution calcEllipsoidWrap(const WrapObject& ellipsoid, WrapMethod method, const Eigen::Vector3d& p1_W,
                               const Eigen::Vector3d& p2_W) {
    WrapSolution solution;
    // OpenSim works in coordinates scaled so the radii are near 1 (its tolerances assume that).
    const double scale = 3 / ellipsoid.radii.sum();
    const Eigen::Vector3d r = scale * ellipsoid.radii, p1 = scale * p1_W, p2 = scale * p2_W;
    if (p1.cwiseQuotient(r).squaredNorm() - 1 < -1e-4 || p2.cwiseQuotient(r).squaredNorm() - 1 < -1e-4) {
        solution.status = WrapStatus::InsideRadius;
        return solution;
    }
    // Ends in line with the centre, or a segment that misses the ellipsoid: no wrap (quadrants included).
    if (std::abs(p1.normalized().dot(p2.normalized()) - 1) < 1e-4) return solution;
    const Eigen::Vector3d f1 = (p1 - p2).cwiseQuotient(r), f2 = p2.cwiseQuotient(r);
    const double qa = f1.squaredNorm(), qb = 2 * f1.dot(f2), qc = f2.squaredNorm() - 1;
    const double disc = qb * qb - 4 * qa * qc;
    if (disc < 0) return solution;
    const double l1 = (-qb + std::sqrt(disc)) / (2 * qa), l2 = (-qb - std::sqrt(disc)) / (2 * qa);
    if (!(l1 > 0 && l1 < 1) || !(l2 > 0 && l2 < 1)) return solution;
    const Eigen::Vector3d e1 = p2 + l1 * (p1 - p2), e2 = p2 + l2 * (p1 - p2);
    const WrapPlanePoint plane = chooseWrapPlanePoint(ellipsoid, method, r, p1, p2, e1, e2);
    const Eigen::Vector3d c1 = plane.c1 / scale;
    solution.status = WrapStatus::MandatoryWrap;

    // The section of the ellipsoid x^T D x = 1 (D = diag(1/radii^2)) by the plane through p1_W, p2_W, c1,
    // x = c1 + E s with E an orthonormal basis of the plane: (s - s0)^T M (s - s0) = k.
    const Eigen::Vector3d normal = (c1 - p1_W).cross(p2_W - p1_W).normalized();  // the path turns positively about it
    Eigen::Matrix<double, 3, 2> E;
    E.col(0) = (p2_W - p1_W).normalized();
    E.col(1) = normal.cross(E.col(0));
    const Eigen::Vector3d D = ellipsoid.radii.cwiseAbs2().cwiseInverse();
    const Eigen::Matrix2d M = E.transpose() * D.asDiagonal() * E;
    const Eigen::Vector2d g = E.transpose() * D.cwiseProduct(c1);
    const Eigen::Vector2d s0 = -M.ldlt().solve(g);
    const double k = std::max(0.0, -g.dot(s0) - (c1.dot(D.cwiseProduct(c1)) - 1));
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(M);
    Eigen::Matrix2d Q = eig.eigenvectors();
    if (Q.determinant() < 0) Q.col(1) = -Q.col(1);  // keep the turning sense
    const Eigen::Vector2d axes = (k / eig.eigenvalues().array()).sqrt();
    // Section coordinates z in which the section is the unit circle: s = s0 + Q diag(axes) z.
    auto toCircle = [&](const Eigen::Vector3d& x) -> Eigen::Vector2d {
        return (Q.transpose() * (E.transpose() * (x - c1) - s0)).cwiseQuotient(axes);
    };
    auto fromCircle = [&](double angle) -> Eigen::Vector3d {
        return c1 + E * (s0 + Q * axes.cwiseProduct(Eigen::Vector2d(std::cos(angle), std::sin(angle))));
    };
    // Tangency is affine-invariant: the circle's tangents map to the section's. The path turns
    // positively about `normal`, round c1; without c1 to go by, round the smaller side of the chord.
    const Eigen::Vector2d z1 = toCircle(p1_W), z2 = toCircle(p2_W);
    wrap_detail::CircleWrap wrap = wrap_detail::calcCircleWrap(z1, z2, 1.0, 1);
    if (!plane.marksSide) {
        const wrap_detail::CircleWrap other = wrap_detail::calcCircleWrap(z1, z2, 1.0, -1);
        if (other.angle < wrap.angle) wrap = other;
    }
    solution.r1_W = fromCircle(wrap.theta1);
    solution.r2_W = fromCircle(wrap.theta1 + wrap.sense * wrap.angle);
    solution.arcLength = calcEllipseArcLength(axes[0], axes[1], wrap.theta1, wrap.angle, wrap.sense);
    return solution;
}

}  // namespace sinew

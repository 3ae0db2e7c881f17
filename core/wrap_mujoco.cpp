// A segment over a sphere or a cylinder as MuJoCo 2.2.2 wraps a spatial tendon (mju_wrap, wrap_circle and
// wrap_inside in src/engine/engine_util_misc.c): the ends are put in a plane through the object's centre
// (the sphere's plane of centre and both ends; the cylinder's cross-section, seen along its axis), wrapped
// around the circle there, and the cylinder's rise shared in proportion to the lengths across it. Its
// choices (when to wrap, which side, the side site's pull, the side site inside the object) are MuJoCo's,
// test for test, so lengths and Jacobians match MuJoCo's; docs/wire-paths.md, "MuJoCo wrapping".
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "sinew/core/wrap_object.hpp"

namespace sinew {
namespace {

constexpr double kMinVal = 1e-15;  // MuJoCo's mjMINVAL, its floor for denominators and lengths

// MuJoCo's mju_normalize: a vector shorter than mjMINVAL becomes the first unit axis.
template <class Vector>
Vector normalizeOrFirstAxis(const Vector& v) {
    const double norm = v.norm();
    return norm < kMinVal ? Vector(Vector::Unit(0)) : Vector(v / norm);
}

// MuJoCo's is_intersect: whether the 2D segments a0-a1 and b0-b1 cross (parallel ones never do).
bool segmentsCross(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                   const Eigen::Vector2d& b1) {
    const double det = (b1.y() - b0.y()) * (a1.x() - a0.x()) - (b1.x() - b0.x()) * (a1.y() - a0.y());
    if (std::abs(det) < kMinVal) return false;
    const double s = ((b1.x() - b0.x()) * (a0.y() - b0.y()) - (b1.y() - b0.y()) * (a0.x() - b0.x())) / det;
    const double t = ((a1.x() - a0.x()) * (a0.y() - b0.y()) - (a1.y() - a0.y()) * (a0.x() - b0.x())) / det;
    return s >= 0 && s <= 1 && t >= 0 && t <= 1;
}

// A wrap in the plane: the tangent points and the arc between them (m), or length < 0 for no wrap.
struct PlaneWrap {
    Eigen::Vector2d t1 = Eigen::Vector2d::Zero(), t2 = Eigen::Vector2d::Zero();
    double length = -1;
};

// MuJoCo's length_circle: the arc from t1 to t2, the way round that tangent pair `pair` (0, 1) turns.
double calcArcLength(const Eigen::Vector2d& t1, const Eigen::Vector2d& t2, int pair, double radius) {
    // (The clamp keeps a roundoff past +-1 from turning into NaN, where MuJoCo's acos would.)
    double angle = std::acos(std::clamp(t1.normalized().dot(t2.normalized()), -1.0, 1.0));
    const double cross = t1.y() * t2.x() - t1.x() * t2.y();
    if ((cross > 0 && pair == 1) || (cross < 0 && pair == 0)) angle = 2 * M_PI - angle;
    return radius * angle;
}

// MuJoCo's wrap_circle: no wrap when an end is inside the circle, or when the segment misses it (and,
// with a side point `side` on the circle, passes on the side point's side); else, of the two tangent
// pairs, the one nearest the side point (without one: the one with the shorter chord) whose tangents do
// not cross, and no wrap if even that one's do.
PlaneWrap wrapCircle(const Eigen::Vector2d& d0, const Eigen::Vector2d& d1, const Eigen::Vector2d* side, double radius) {
    const double sqlen0 = d0.squaredNorm(), sqlen1 = d1.squaredNorm(), sqrad = radius * radius;
    if (sqlen0 < sqrad || sqlen1 < sqrad || radius < kMinVal) return {};
    const Eigen::Vector2d dif = d1 - d0;
    const double dd = dif.squaredNorm();
    if (dd < kMinVal) return {};
    const Eigen::Vector2d closest = d0 + std::clamp(-dif.dot(d0) / dd, 0.0, 1.0) * dif;
    if (closest.squaredNorm() > sqrad && (!side || side->dot(closest) >= 0)) return {};

    const double sqrt0 = std::sqrt(sqlen0 - sqrad), sqrt1 = std::sqrt(sqlen1 - sqrad);
    PlaneWrap pairs[2];
    double goodness[2];
    for (int i = 0; i < 2; ++i) {
        const double sign = i == 0 ? 1 : -1;
        pairs[i].t1 = (d0 * sqrad + sign * radius * sqrt0 * Eigen::Vector2d(d0.y(), -d0.x())) / sqlen0;
        pairs[i].t2 = (d1 * sqrad + sign * radius * sqrt1 * Eigen::Vector2d(-d1.y(), d1.x())) / sqlen1;
        goodness[i] = side ? normalizeOrFirstAxis(Eigen::Vector2d(pairs[i].t1 + pairs[i].t2)).dot(*side)
                           : -(pairs[i].t1 - pairs[i].t2).squaredNorm();
        if (segmentsCross(d0, pairs[i].t1, d1, pairs[i].t2)) goodness[i] = -10000;
    }
    const int best = goodness[0] > goodness[1] ? 0 : 1;
    PlaneWrap wrap = pairs[best];
    if (segmentsCross(d0, wrap.t1, d1, wrap.t2)) return {};
    wrap.length = calcArcLength(wrap.t1, wrap.t2, best, radius);
    return wrap;
}

// MuJoCo's wrap_inside, for a side site inside the object: unless an end is inside the circle or the
// segment passes through it, the path touches the circle at one point z (t1 = t2, no arc) where it
// reflects, found by Newton's method on asin(A z) + asin(B z) - 2 asin(z) + G = 0 from z = 1 - 1e-7 to
// |f| <= 1e-6; where that fails, MuJoCo's fallback, the circle's point towards the ends' midpoint.
PlaneWrap wrapInside(const Eigen::Vector2d& d0, const Eigen::Vector2d& d1, double radius) {
    const double len0 = d0.norm(), len1 = d1.norm();
    const Eigen::Vector2d dif = d1 - d0;
    const double dd = dif.squaredNorm();
    if (len0 <= radius || len1 <= radius || radius < kMinVal || len0 < kMinVal || len1 < kMinVal) return {};
    if (dd > kMinVal) {
        const double a = -dif.dot(d0) / dd;
        if (a > 0 && a < 1 && (d0 + a * dif).norm() <= radius) return {};
    }
    PlaneWrap wrap;
    wrap.length = 0;
    wrap.t1 = wrap.t2 = radius * normalizeOrFirstAxis(Eigen::Vector2d(0.5 * (d0 + d1)));
    const double A = radius / len0, B = radius / len1;
    const double cosG = (len0 * len0 + len1 * len1 - dd) / (2 * len0 * len1);
    if (cosG < -1 + kMinVal) return {};
    if (cosG > 1 - kMinVal) return wrap;
    const double G = std::acos(cosG);
    auto f = [&](double z) { return std::asin(A * z) + std::asin(B * z) - 2 * std::asin(z) + G; };
    double z = 1 - 1e-7, fz = f(z);
    if (fz > 0) return wrap;
    constexpr int maxIterations = 20;
    constexpr double tolerance = 1e-6;
    int iteration = 0;
    for (; iteration < maxIterations && std::abs(fz) > tolerance; ++iteration) {
        const double df = A / std::max(kMinVal, std::sqrt(1 - z * z * A * A)) +
                          B / std::max(kMinVal, std::sqrt(1 - z * z * B * B)) - 2 / std::max(kMinVal, std::sqrt(1 - z * z));
        if (df > -kMinVal) return wrap;
        const double next = z - fz / df;
        if (next > z) return wrap;
        z = next;
        fz = f(z);
        if (fz > tolerance) return wrap;
    }
    if (iteration >= maxIterations) return wrap;
    // The contact point: turned from the end the path leaves counterclockwise by asin(z) - asin(A z) (or B).
    const bool fromFirst = d0.x() * d1.y() - d0.y() * d1.x() > 0;
    const double angle = std::asin(z) - std::asin((fromFirst ? A : B) * z);
    const Eigen::Vector2d from = normalizeOrFirstAxis(fromFirst ? d0 : d1);
    wrap.t1 = wrap.t2 = radius * Eigen::Vector2d(std::cos(angle) * from.x() - std::sin(angle) * from.y(),
                                                 std::sin(angle) * from.x() + std::cos(angle) * from.y());
    return wrap;
}

// mju_wrap's plane: for a sphere, x along p1 and y in the plane of the centre and both ends (for ends in
// line with the centre, MuJoCo's substitute normal); for a cylinder, W's x and y.
void calcWrapPlane(const WrapObject& object, const Eigen::Vector3d& p1_W, const Eigen::Vector3d& p2_W,
                   Eigen::Vector3d& ex, Eigen::Vector3d& ey) {
    if (object.shape == WrapShape::Cylinder) {
        ex = Eigen::Vector3d::UnitX();
        ey = Eigen::Vector3d::UnitY();
        return;
    }
    ex = normalizeOrFirstAxis(p1_W);
    Eigen::Vector3d normal = p1_W.cross(p2_W);
    if (normal.norm() < kMinVal) {
        // MuJoCo's largest component of ex, the first of equals losing to neither strict rival.
        int largest = 0;
        const Eigen::Vector3d m = ex.cwiseAbs();
        if (m.y() > m.x() && m.y() > m.z()) largest = 1;
        if (m.z() > m.x() && m.z() > m.y()) largest = 2;
        Eigen::Vector3d other = Eigen::Vector3d::Ones();
        other[largest] = 0;
        normal = ex.cross(other);
    }
    ey = normalizeOrFirstAxis(Eigen::Vector3d(normalizeOrFirstAxis(normal).cross(ex)));
}

}  // namespace

WrapSolution calcMuJoCoWrap(const WrapObject& object, const Eigen::Vector3d* sideSite_W, const Eigen::Vector3d& p1_W,
                            const Eigen::Vector3d& p2_W) {
    const double R = object.radius;
    WrapSolution solution;
    if (p1_W.norm() < kMinVal || p2_W.norm() < kMinVal) {
        solution.status = WrapStatus::InsideRadius;
        return solution;
    }
    Eigen::Vector3d ex, ey;
    calcWrapPlane(object, p1_W, p2_W, ex, ey);
    auto inPlane = [&](const Eigen::Vector3d& v) { return Eigen::Vector2d(v.dot(ex), v.dot(ey)); };
    const Eigen::Vector2d d0 = inPlane(p1_W), d1 = inPlane(p2_W);
    // 2.2.2: a side site whose projection on the plane lies within the radius asks for the inside wrap;
    // one outside pulls the path towards its projection on the circle.
    PlaneWrap wrap;
    if (sideSite_W) {
        const Eigen::Vector2d side = inPlane(*sideSite_W);
        if (side.norm() >= R) {
            const Eigen::Vector2d sideOnCircle = R * normalizeOrFirstAxis(side);
            wrap = wrapCircle(d0, d1, &sideOnCircle, R);
        } else {
            wrap = wrapInside(d0, d1, R);
        }
    } else {
        wrap = wrapCircle(d0, d1, nullptr, R);
    }
    if (wrap.length < 0) {
        solution.status = d0.norm() <= R || d1.norm() <= R ? WrapStatus::InsideRadius : WrapStatus::NoWrap;
        return solution;
    }
    solution.r1_W = wrap.t1.x() * ex + wrap.t1.y() * ey;
    solution.r2_W = wrap.t2.x() * ex + wrap.t2.y() * ey;
    solution.arcLength = wrap.length;
    if (object.shape == WrapShape::Cylinder) {
        // Unrolled, the path is straight: the rise is shared in proportion to the lengths across the axis.
        const double across1 = (d0 - wrap.t1).norm(), across2 = (d1 - wrap.t2).norm();
        const double across = across1 + wrap.length + across2;
        if (across < kMinVal) return WrapSolution{};  // both ends on the surface, together: nothing to wrap
        const double rise = p2_W.z() - p1_W.z();
        solution.r1_W.z() = p1_W.z() + rise * across1 / across;
        solution.r2_W.z() = p1_W.z() + rise * (across1 + wrap.length) / across;
        solution.arcLength = std::hypot(wrap.length, solution.r2_W.z() - solution.r1_W.z());
    }
    solution.status = WrapStatus::Wrapped;
    return solution;
}

}  // namespace sinew

// A segment over a cylinder (axis W's z): seen along the axis the path wraps a circle; unrolled, the
// tangents and the helix between them are one straight line, so the rise along the axis is shared in
// proportion to the lengths across it (docs/wire-paths.md, "Cylinder").
#include <Eigen/Geometry>
#include <cmath>

#include "sinew/core/wrap_object.hpp"
#include "wrap_detail.hpp"

namespace sinew {

WrapSolution calcCylinderWrap(const WrapObject& cylinder, const Eigen::Vector3d& p1_W, const Eigen::Vector3d& p2_W) {
    using namespace wrap_detail;
    const double R = cylinder.radius;
    WrapSolution solution;
    const Eigen::Vector2d a = p1_W.head<2>(), b = p2_W.head<2>();
    if (a.norm() < R || b.norm() < R) {
        solution.status = WrapStatus::InsideRadius;
        return solution;
    }
    // The segment's point nearest the axis: nearest the centre in the projection. A segment along the
    // axis never passes through (OpenSim's line intersection fails for it).
    const Eigen::Vector2d d = b - a;
    const bool alongAxis = d.squaredNorm() <= 1e-24 * (p2_W - p1_W).squaredNorm();
    const double t = alongAxis ? 0.0 : -a.dot(d) / d.squaredNorm();
    const Eigen::Vector3d closest = p1_W + t * (p2_W - p1_W);
    const bool intersects = !alongAxis && t > 0 && t < 1 && closest.head<2>().norm() < R;
    solution.status = decideWrap(cylinder, p1_W, p2_W, closest, intersects);
    if (solution.status == WrapStatus::NoWrap) return solution;

    Eigen::Vector2d side = closest.head<2>();
    if (cylinder.quadrantSign != 0) side = cylinder.quadrantSign * Eigen::Vector2d::Unit(cylinder.quadrantAxis);
    const CircleWrap wrap = calcCircleWrapTowards(a, b, R, side);
    const double across = wrap.tangent1 + R * wrap.angle + wrap.tangent2;
    const double rise = p2_W.z() - p1_W.z();
    // (across is 0 only for two ends on the surface with nothing between them: no rise to share.)
    const double share1 = across > 0 ? wrap.tangent1 / across : 0, share2 = across > 0 ? (wrap.tangent1 + R * wrap.angle) / across : 0;
    const double z1 = p1_W.z() + rise * share1, z2 = p1_W.z() + rise * share2;
    const double theta2 = wrap.theta1 + wrap.sense * wrap.angle;
    solution.r1_W << R * std::cos(wrap.theta1), R * std::sin(wrap.theta1), z1;
    solution.r2_W << R * std::cos(theta2), R * std::sin(theta2), z2;
    // OpenSim's finite cylinder: no wrap when both tangent points lie beyond its ends.
    const double half = 0.5 * cylinder.length;
    if (std::abs(z1) > half && std::abs(z2) > half) return WrapSolution{};
    solution.arcLength = std::hypot(R * wrap.angle, z2 - z1);
    return solution;
}

}  // namespace sinew

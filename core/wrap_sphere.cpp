// A segment over a sphere: the shortest path runs in the plane of the two ends and the centre, along a
// great circle between the tangents from each end (docs/wire-paths.md, "Sphere").
#include <Eigen/Geometry>
#include <cmath>

#include "sinew/core/wrap_object.hpp"
#include "wrap_detail.hpp"

namespace sinew {

WrapSolution calcSphereWrap(const WrapObject& sphere, const Eigen::Vector3d& p1_W, const Eigen::Vector3d& p2_W) {
    using namespace wrap_detail;
    const double R = sphere.radius;
    WrapSolution solution;
    if (p1_W.norm() < R || p2_W.norm() < R) {
        solution.status = WrapStatus::InsideRadius;
        return solution;
    }
    const Eigen::Vector3d d = p2_W - p1_W;
    const double t = d.squaredNorm() > 0 ? -p1_W.dot(d) / d.squaredNorm() : 0.0;
    const Eigen::Vector3d closest = p1_W + t * d;
    solution.status = decideWrap(sphere, p1_W, p2_W, closest, t > 0 && t < 1 && closest.norm() < R);
    if (solution.status == WrapStatus::NoWrap) return solution;

    // The plane through both ends and the centre; when they are in line, any plane holding the segment
    // (with a quadrant, the one holding its axis too).
    Eigen::Vector3d normal = p1_W.cross(p2_W);
    if (normal.norm() <= 1e-12 * p1_W.norm() * p2_W.norm()) {
        Eigen::Vector3d axis = Eigen::Vector3d::Zero();
        if (sphere.quadrantSign != 0) axis[sphere.quadrantAxis] = 1;
        if (sphere.quadrantSign == 0 || d.cross(axis).norm() <= 1e-12 * d.norm()) {
            Eigen::Index least = 0;
            d.cwiseAbs().minCoeff(&least);
            axis = Eigen::Vector3d::Unit(least);
        }
        normal = d.cross(axis);
    }
    normal.normalize();
    const Eigen::Vector3d ex = p1_W.normalized(), ey = normal.cross(ex);
    auto inPlane = [&](const Eigen::Vector3d& v) { return Eigen::Vector2d(v.dot(ex), v.dot(ey)); };

    Eigen::Vector2d side = inPlane(closest);
    if (sphere.quadrantSign != 0) {
        const Eigen::Vector2d active = inPlane(sphere.quadrantSign * Eigen::Vector3d::Unit(sphere.quadrantAxis));
        if (active.norm() > 1e-9) side = active;
    }
    const CircleWrap wrap = calcCircleWrapTowards(inPlane(p1_W), inPlane(p2_W), R, side);
    const double theta2 = wrap.theta1 + wrap.sense * wrap.angle;
    solution.r1_W = R * (std::cos(wrap.theta1) * ex + std::sin(wrap.theta1) * ey);
    solution.r2_W = R * (std::cos(theta2) * ex + std::sin(theta2) * ey);
    solution.arcLength = R * wrap.angle;
    return solution;
}

}  // namespace sinew

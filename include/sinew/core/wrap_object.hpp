#pragma once
// Wrapping one straight segment of a wire over a wrap object (sphere, cylinder, ellipsoid), in the object's
// frame W. OpenSim's decisions of whether to wrap and on which side (WrapSphere, WrapCylinder and
// WrapEllipsoid::wrapLine, with their quadrants); exact shortest paths over spheres and cylinders, and
// OpenSim's plane-section path over ellipsoids; and MuJoCo's spatial-tendon wrapping (mju_wrap) over
// spheres and infinite cylinders. docs/wire-paths.md derives them.
#include <Eigen/Core>

#include "sinew/core/model.hpp"

namespace sinew {

// OpenSim's outcomes: no wrap; a segment end inside the object (no wrap either); a wrap the quadrant asks
// for although the segment misses the object; a wrap because the segment passes through it.
enum class WrapStatus { NoWrap, InsideRadius, Wrapped, MandatoryWrap };

struct WrapSolution {
    WrapStatus status = WrapStatus::NoWrap;
    // With Wrapped or MandatoryWrap: where the path meets the surface coming from p1 and leaves it towards
    // p2 (m, in W), and the length over the surface between them (m).
    Eigen::Vector3d r1_W = Eigen::Vector3d::Zero();
    Eigen::Vector3d r2_W = Eigen::Vector3d::Zero();
    double arcLength = 0;

    // With a wrap: the length from p1 over the object to p2, |r1 - p1| + arcLength + |p2 - r2| (m; p1, p2 in W).
    double calcLength(const Eigen::Vector3d& p1_W, const Eigen::Vector3d& p2_W) const {
        return (r1_W - p1_W).norm() + arcLength + (p2_W - r2_W).norm();
    }
};

// The segment from p1_W to p2_W (m, in W) over `object` by `method`: MuJoCo's, with its side site
// `sideSite_W` (m, in W at this pose; nullptr for none, and ignored by the other methods), else the
// object's shape picks OpenSim's (the method matters for ellipsoids only). Allocates nothing.
WrapSolution calcWrap(const WrapObject& object, WrapMethod method, const Eigen::Vector3d* sideSite_W,
                      const Eigen::Vector3d& p1_W, const Eigen::Vector3d& p2_W);

// The shapes one by one (calcWrap picks by WrapObject::shape).
WrapSolution calcSphereWrap(const WrapObject& sphere, const Eigen::Vector3d& p1_W, const Eigen::Vector3d& p2_W);
WrapSolution calcCylinderWrap(const WrapObject& cylinder, const Eigen::Vector3d& p1_W, const Eigen::Vector3d& p2_W);
WrapSolution calcEllipsoidWrap(const WrapObject& ellipsoid, WrapMethod method, const Eigen::Vector3d& p1_W,
                               const Eigen::Vector3d& p2_W);

// MuJoCo 2.2.2's mju_wrap over a sphere or a cylinder (infinite: its length is ignored; quadrants too),
// with MuJoCo's side site `sideSite_W` (m, in W) or nullptr for none. Wrapped, with the tangent points
// and the arc (for a cylinder the helix) as MuJoCo places them, or: NoWrap, or InsideRadius where an end
// lies within the radius (in the wrapping plane). docs/wire-paths.md, "MuJoCo wrapping".
WrapSolution calcMuJoCoWrap(const WrapObject& object, const Eigen::Vector3d* sideSite_W, const Eigen::Vector3d& p1_W,
                            const Eigen::Vector3d& p2_W);

}  // namespace sinew

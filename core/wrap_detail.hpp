#pragma once
// Pieces the sphere, cylinder and ellipsoid wraps share (private to core/).
#include <Eigen/Core>

#include "sinew/core/wrap_object.hpp"

namespace sinew::wrap_detail {

// OpenSim's DSIGN: +1 for x >= 0, else -1.
inline int signOf(double x) { return x >= 0 ? 1 : -1; }

// OpenSim's decision for a sphere or a cylinder. `closest` is the point of the segment's line nearest the
// centre (sphere) or the axis (cylinder), at parameter t along p1 -> p2; `intersects` says whether the
// segment passes through the object. Unconstrained: wrap only through the object. With a quadrant: a
// segment with an end on the active side wraps when it passes through the object, or when its ends lie
// on both sides and it passes by on the inactive side; one with both ends inactive always wraps (around
// the active side).
WrapStatus decideWrap(const WrapObject& object, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                      const Eigen::Vector3d& closest, bool intersects);

// The shortest path around a circle of radius R about the plane's origin, from a to b (2D, both outside
// it), turning about the plane's normal with `sense` (+1 counterclockwise, -1 clockwise): it touches the
// circle at polar angle theta1, sweeps `angle` (rad, 0 <= angle < 2 pi) in that sense, and leaves it.
struct CircleWrap {
    int sense = 1;
    double theta1 = 0;
    double angle = 0;
    double tangent1 = 0, tangent2 = 0;  // lengths of the straight parts, a to the circle and circle to b
};
CircleWrap calcCircleWrap(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius, int sense);

// Of the two senses, the one whose arc passes furthest along the direction `side` (2D).
CircleWrap calcCircleWrapTowards(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius,
                                 const Eigen::Vector2d& side);

}  // namespace sinew::wrap_detail

#include "sinew/core/wrap_object.hpp"

#include <cmath>

#include "wrap_detail.hpp"

namespace sinew {

WrapSolution calcWrap(const WrapObject& object, WrapMethod method, const Eigen::Vector3d* sideSite_W,
                      const Eigen::Vector3d& p1_W, const Eigen::Vector3d& p2_W) {
    if (method == WrapMethod::MuJoCo) return calcMuJoCoWrap(object, sideSite_W, p1_W, p2_W);
    switch (object.shape) {
        case WrapShape::Sphere: return calcSphereWrap(object, p1_W, p2_W);
        case WrapShape::Cylinder: return calcCylinderWrap(object, p1_W, p2_W);
        case WrapShape::Ellipsoid: return calcEllipsoidWrap(object, method, p1_W, p2_W);
    }
    return {};
}

namespace wrap_detail {

WrapStatus decideWrap(const WrapObject& object, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                      const Eigen::Vector3d& closest, bool intersects) {
    if (object.quadrantSign == 0) return intersects ? WrapStatus::MandatoryWrap : WrapStatus::NoWrap;
    const int axis = object.quadrantAxis, sign = object.quadrantSign;
    if (signOf(p1[axis]) != sign && signOf(p2[axis]) != sign) return WrapStatus::Wrapped;
    if (intersects) return WrapStatus::MandatoryWrap;
    if (signOf(p1[axis]) != signOf(p2[axis]) && signOf(closest[axis]) != sign) return WrapStatus::Wrapped;
    return WrapStatus::NoWrap;
}

CircleWrap calcCircleWrap(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius, int sense) {
    // From a point at distance d the tangents touch at +-acos(R/d) about its polar angle; turning
    // counterclockwise the path touches at the + one coming in and leaves at the - one going out.
    const double da = a.norm(), db = b.norm();
    const double alphaA = std::acos(std::min(1.0, radius / da)), alphaB = std::acos(std::min(1.0, radius / db));
    CircleWrap wrap;
    wrap.sense = sense;
    wrap.theta1 = std::atan2(a.y(), a.x()) + sense * alphaA;
    const double theta2 = std::atan2(b.y(), b.x()) - sense * alphaB;
    constexpr double twoPi = 2 * M_PI;
    double angle = std::fmod(sense * (theta2 - wrap.theta1), twoPi);
    if (angle < 0) angle += twoPi;
    // A grazing segment sweeps nothing; roundoff must not turn that into a full turn.
    wrap.angle = angle > twoPi - 1e-12 ? 0.0 : angle;
    wrap.tangent1 = std::sqrt(std::max(0.0, da * da - radius * radius));
    wrap.tangent2 = std::sqrt(std::max(0.0, db * db - radius * radius));
    return wrap;
}

CircleWrap calcCircleWrapTowards(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius,
                                 const Eigen::Vector2d& side) {
    const CircleWrap ccw = calcCircleWrap(a, b, radius, 1), cw = calcCircleWrap(a, b, radius, -1);
    auto reach = [&](const CircleWrap& w) {
        const double middle = w.theta1 + w.sense * 0.5 * w.angle;
        return side.dot(Eigen::Vector2d(std::cos(middle), std::sin(middle)));
    };
    return reach(ccw) >= reach(cw) ? ccw : cw;
}

}  // namespace wrap_detail
}  // namespace sinew

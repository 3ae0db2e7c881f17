// Cylinder wrapping against closed forms: seen along the axis the path wraps a circle; unrolled, tangents
// and helix are one straight line, so the length is sqrt(H^2 + rise^2) with H the length across the axis.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "sinew/core/wrap_object.hpp"

namespace sinew {
namespace {

WrapObject makeCylinder(double radius, double length, int quadrantAxis = 0, int quadrantSign = 0) {
    WrapObject cylinder;
    cylinder.shape = WrapShape::Cylinder;
    cylinder.radius = radius;
    cylinder.length = length;
    cylinder.quadrantAxis = quadrantAxis;
    cylinder.quadrantSign = quadrantSign;
    return cylinder;
}

TEST(WrapCylinder, HelixMatchesClosedForm) {
    // Ends (-+2, 0.1, -+1) round a unit cylinder: across the axis as the sphere case in its plane, H =
    // 2 sqrt(D^2 - 1) + arc, and the rise of 2 is shared in proportion.
    const Eigen::Vector3d p1(-2, 0.1, -1), p2(2, 0.1, 1);
    const WrapSolution s = calcCylinderWrap(makeCylinder(1, 10), p1, p2);
    ASSERT_EQ(s.status, WrapStatus::MandatoryWrap);
    const double D = std::sqrt(4.01), tangent = std::sqrt(D * D - 1);
    const double arc = M_PI - 2 * std::atan(0.05) - 2 * std::acos(1 / D);
    const double H = 2 * tangent + arc;
    EXPECT_NEAR(s.calcLength(p1, p2), std::hypot(H, 2.0), 1e-14);
    EXPECT_NEAR(s.arcLength, std::hypot(arc, 2 * arc / H), 1e-14);
    EXPECT_NEAR(s.r1_W.z(), -1 + 2 * tangent / H, 1e-14);
    EXPECT_NEAR(s.r2_W.z(), 1 - 2 * tangent / H, 1e-14);
    EXPECT_NEAR(s.r1_W.head<2>().norm(), 1, 1e-14);
    // The straight parts are tangent to the surface and continue the helix's direction.
    const Eigen::Vector3d in = (s.r1_W - p1).normalized();
    EXPECT_NEAR(in.dot(Eigen::Vector3d(s.r1_W.x(), s.r1_W.y(), 0)), 0, 1e-14);
    EXPECT_NEAR(in.z(), 2 / std::hypot(H, 2.0), 1e-14);
}

TEST(WrapCylinder, QuadrantAndLengthDecideTheWrap) {
    const Eigen::Vector3d p1(-2, -0.5, 0), p2(2, -0.5, 0);
    const double D = std::sqrt(4.25), alpha = std::acos(1 / D);
    const WrapSolution under = calcCylinderWrap(makeCylinder(1, 1), p1, p2);
    ASSERT_EQ(under.status, WrapStatus::MandatoryWrap);
    EXPECT_NEAR(under.arcLength, M_PI - 2 * std::atan(0.25) - 2 * alpha, 1e-14);
    // Kept to +y, with both ends at y < 0: forced over the top.
    const WrapSolution over = calcCylinderWrap(makeCylinder(1, 1, 1, 1), p1, p2);
    ASSERT_EQ(over.status, WrapStatus::Wrapped);
    EXPECT_NEAR(over.arcLength, M_PI + 2 * std::atan(0.25) - 2 * alpha, 1e-14);
    EXPECT_GT(over.r1_W.y(), 0);
    // Both tangent points beyond the cylinder's ends: no wrap (OpenSim's finite cylinder).
    EXPECT_EQ(calcCylinderWrap(makeCylinder(1, 1), Eigen::Vector3d(-2, -0.5, 3), Eigen::Vector3d(2, -0.5, 3)).status,
              WrapStatus::NoWrap);
    // Along the axis, or missing it: no wrap; an end inside: none either.
    EXPECT_EQ(calcCylinderWrap(makeCylinder(1, 1), Eigen::Vector3d(2, 0, -1), Eigen::Vector3d(2, 0, 1)).status,
              WrapStatus::NoWrap);
    EXPECT_EQ(calcCylinderWrap(makeCylinder(1, 1), Eigen::Vector3d(-2, 1.2, 0), Eigen::Vector3d(2, 1.2, 0)).status,
              WrapStatus::NoWrap);
    EXPECT_EQ(calcCylinderWrap(makeCylinder(1, 1), Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d(2, 1.2, 0)).status,
              WrapStatus::InsideRadius);
}

}  // namespace
}  // namespace sinew

// Sphere wrapping against geometry worked by hand: a segment passing through a unit sphere in the plane
// z = 0, where the tangents and the arc have closed forms, and general segments against the conditions a
// shortest path over a sphere meets (tangency, the great-circle plane, the arc).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "sinew/core/wrap_object.hpp"

namespace sinew {
namespace {

WrapObject makeSphere(double radius, int quadrantAxis = 0, int quadrantSign = 0) {
    WrapObject sphere;
    sphere.shape = WrapShape::Sphere;
    sphere.radius = radius;
    sphere.quadrantAxis = quadrantAxis;
    sphere.quadrantSign = quadrantSign;
    return sphere;
}

TEST(WrapSphere, SymmetricSegmentMatchesClosedForm) {
    // Ends (-+2, 0.1, 0): each tangent is sqrt(D^2 - 1) long, D^2 = 4.01, and touches at acos(1/D) from
    // the end's polar angle; the arc over the top spans pi - 2 atan(0.05) - 2 acos(1/D).
    const Eigen::Vector3d p1(-2, 0.1, 0), p2(2, 0.1, 0);
    const WrapSolution s = calcSphereWrap(makeSphere(1), p1, p2);
    ASSERT_EQ(s.status, WrapStatus::MandatoryWrap);
    const double D = std::sqrt(4.01), alpha = std::acos(1 / D);
    const double arc = M_PI - 2 * std::atan(0.05) - 2 * alpha;
    EXPECT_NEAR(s.arcLength, arc, 1e-14);
    EXPECT_NEAR(s.calcLength(p1, p2), 2 * std::sqrt(D * D - 1) + arc, 1e-14);
    const double theta1 = M_PI - std::atan(0.05) - alpha;
    EXPECT_LE((s.r1_W - Eigen::Vector3d(std::cos(theta1), std::sin(theta1), 0)).norm(), 1e-14);
    EXPECT_LE((s.r2_W - Eigen::Vector3d(-std::cos(theta1), std::sin(theta1), 0)).norm(), 1e-14);
}

TEST(WrapSphere, QuadrantSendsThePathRoundItsSide) {
    // The same segment with the wrap kept to -y: both ends are on the inactive side (y > 0), so the path
    // goes round the bottom, pi + 2 atan(0.05) - 2 acos(1/D); with +y it stays on top.
    const Eigen::Vector3d p1(-2, 0.1, 0), p2(2, 0.1, 0);
    const double D = std::sqrt(4.01), alpha = std::acos(1 / D);
    const WrapSolution below = calcSphereWrap(makeSphere(1, 1, -1), p1, p2);
    EXPECT_EQ(below.status, WrapStatus::Wrapped);
    EXPECT_NEAR(below.arcLength, M_PI + 2 * std::atan(0.05) - 2 * alpha, 1e-14);
    EXPECT_LT(below.r1_W.y(), 0);
    const WrapSolution above = calcSphereWrap(makeSphere(1, 1, 1), p1, p2);
    EXPECT_EQ(above.status, WrapStatus::MandatoryWrap);
    EXPECT_NEAR(above.arcLength, M_PI - 2 * std::atan(0.05) - 2 * alpha, 1e-14);
    // A segment that misses the sphere on the active side does not wrap; one whose ends straddle the
    // dividing plane and that passes on the inactive side does.
    EXPECT_EQ(calcSphereWrap(makeSphere(1, 1, 1), Eigen::Vector3d(-2, 1.5, 0), Eigen::Vector3d(2, 1.5, 0)).status,
              WrapStatus::NoWrap);
    EXPECT_EQ(calcSphereWrap(makeSphere(1, 1, 1), Eigen::Vector3d(-4, 0.2, 0), Eigen::Vector3d(4, -3, 0)).status,
              WrapStatus::Wrapped);
}

TEST(WrapSphere, MissesAndInsideEndsDoNotWrap) {
    EXPECT_EQ(calcSphereWrap(makeSphere(1), Eigen::Vector3d(-2, 1.5, 0), Eigen::Vector3d(2, 1.5, 0)).status,
              WrapStatus::NoWrap);
    EXPECT_EQ(calcSphereWrap(makeSphere(1), Eigen::Vector3d(-2, 0, 0.1), Eigen::Vector3d(-1.5, 0, 0.1)).status,
              WrapStatus::NoWrap);  // the line would cross, the segment stops short
    EXPECT_EQ(calcSphereWrap(makeSphere(1), Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d(2, 0, 0)).status,
              WrapStatus::InsideRadius);
}

TEST(WrapSphere, GeneralSegmentsMeetTheShortestPathConditions) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uniform(-3, 3);
    const double R = 0.7;
    int wrapped = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Eigen::Vector3d p1(uniform(rng), uniform(rng), uniform(rng)), p2(uniform(rng), uniform(rng), uniform(rng));
        const WrapSolution s = calcSphereWrap(makeSphere(R), p1, p2);
        if (s.status != WrapStatus::MandatoryWrap) continue;
        ++wrapped;
        const Eigen::Vector3d n = p1.cross(p2).normalized();
        for (const Eigen::Vector3d& r : {s.r1_W, s.r2_W}) {
            EXPECT_NEAR(r.norm(), R, 1e-12);
            EXPECT_NEAR(r.dot(n), 0, 1e-12);  // on the great circle through both ends
        }
        EXPECT_NEAR((s.r1_W - p1).dot(s.r1_W), 0, 1e-12);  // tangent at both ends
        EXPECT_NEAR((s.r2_W - p2).dot(s.r2_W), 0, 1e-12);
        EXPECT_NEAR(s.arcLength, R * std::acos(std::clamp(s.r1_W.dot(s.r2_W) / (R * R), -1.0, 1.0)), 1e-9);
        // Leaving r1 along the arc continues the incoming tangent (no kink): the path turns one way.
        EXPECT_GT((s.r1_W - p1).cross(s.r2_W - s.r1_W).dot((s.r2_W - s.r1_W).cross(p2 - s.r2_W)), -1e-12);
    }
    EXPECT_GT(wrapped, 10);
}

}  // namespace
}  // namespace sinew

// Ellipsoid wrapping: with equal radii it is the sphere's exact wrap; otherwise the path lies in one plane
// through both ends, touches the surface tangentially, and its arc is the section ellipse's (checked
// against a fine polyline along that ellipse).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "sinew/core/wrap_object.hpp"

namespace sinew {
namespace {

WrapObject makeEllipsoid(const Eigen::Vector3d& radii, int quadrantAxis = 0, int quadrantSign = 0) {
    WrapObject ellipsoid;
    ellipsoid.shape = WrapShape::Ellipsoid;
    ellipsoid.radii = radii;
    ellipsoid.quadrantAxis = quadrantAxis;
    ellipsoid.quadrantSign = quadrantSign;
    return ellipsoid;
}

// Length along the section of the ellipsoid by the plane with normal n, from r1 (entered coming from p1)
// to r2: small steps along the curve's tangent, each pulled back onto the surface within the plane.
double walkSection(const Eigen::Vector3d& radii, const Eigen::Vector3d& n, const Eigen::Vector3d& p1,
                   const Eigen::Vector3d& r1, const Eigen::Vector3d& r2) {
    const Eigen::Vector3d D = radii.cwiseAbs2().cwiseInverse();
    const double h = 2e-6;
    Eigen::Vector3d x = r1, direction = (r1 - p1).normalized();
    double length = 0;
    for (int step = 0; step < 1000000 && (x - r2).norm() > h; ++step) {
        Eigen::Vector3d t = n.cross(D.cwiseProduct(x)).normalized();
        if (t.dot(direction) < 0) t = -t;
        Eigen::Vector3d next = x + h * t;
        for (int i = 0; i < 4; ++i) {
            Eigen::Vector3d g = D.cwiseProduct(next);
            g -= g.dot(n) * n;
            next -= (next.dot(D.cwiseProduct(next)) - 1) / (2 * D.cwiseProduct(next).dot(g)) * g;
        }
        length += (next - x).norm();
        direction = t;
        x = next;
    }
    return length + (r2 - x).norm();
}

TEST(WrapEllipsoid, EqualRadiiGiveTheSphere) {
    WrapObject sphere;
    sphere.shape = WrapShape::Sphere;
    sphere.radius = 0.02;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> uniform(-0.06, 0.06);
    int compared = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const Eigen::Vector3d p1(uniform(rng), uniform(rng), uniform(rng)), p2(uniform(rng), uniform(rng), uniform(rng));
        const WrapSolution s = calcSphereWrap(sphere, p1, p2);
        for (const WrapMethod method : {WrapMethod::Hybrid, WrapMethod::Midpoint, WrapMethod::Axial}) {
            const WrapSolution e = calcEllipsoidWrap(makeEllipsoid(Eigen::Vector3d::Constant(0.02)), method, p1, p2);
            ASSERT_EQ(e.status == WrapStatus::MandatoryWrap, s.status == WrapStatus::MandatoryWrap) << trial;
            if (s.status != WrapStatus::MandatoryWrap) continue;
            ++compared;
            EXPECT_NEAR(e.arcLength, s.arcLength, 1e-12) << trial << " method " << toString(method);
            EXPECT_LE((e.r1_W - s.r1_W).norm(), 1e-12) << trial;
            EXPECT_LE((e.r2_W - s.r2_W).norm(), 1e-12) << trial;
        }
    }
    EXPECT_GT(compared, 30);
}

TEST(WrapEllipsoid, PathIsPlanarTangentAndItsArcIsTheSections) {
    const Eigen::Vector3d radii(0.035, 0.02, 0.025);
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> uniform(-0.08, 0.08);
    int wrapped = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Eigen::Vector3d p1(uniform(rng), uniform(rng), uniform(rng)), p2(uniform(rng), uniform(rng), uniform(rng));
        for (const int sign : {0, 1, -1}) {
            const WrapSolution e = calcEllipsoidWrap(makeEllipsoid(radii, 2, sign), WrapMethod::Hybrid, p1, p2);
            if (e.status != WrapStatus::MandatoryWrap) continue;
            ++wrapped;
            const Eigen::Vector3d n = (e.r1_W - p1).cross(p2 - p1).normalized();
            for (const auto& [r, p] : {std::pair(e.r1_W, p1), std::pair(e.r2_W, p2)}) {
                EXPECT_NEAR(r.cwiseQuotient(radii).squaredNorm(), 1, 1e-12);                     // on the surface
                EXPECT_NEAR((r - p1).dot(n), 0, 1e-12);                                          // in the plane
                EXPECT_NEAR(r.cwiseQuotient(radii.cwiseAbs2()).normalized().dot((p - r).normalized()), 0, 1e-9);  // tangent
            }
            EXPECT_NEAR(e.arcLength, walkSection(radii, n, p1, e.r1_W, e.r2_W), 1e-8 * e.arcLength + 1e-12) << trial;
        }
    }
    EXPECT_GT(wrapped, 20);
}

}  // namespace
}  // namespace sinew

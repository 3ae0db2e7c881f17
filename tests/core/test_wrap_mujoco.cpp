// MuJoCo's wrapping (core/wrap_mujoco.cpp) against geometry worked by hand: segments in the plane z = 0
// round a unit sphere and across a unit cylinder, where tangents, arcs and helices have closed forms; the
// side site choosing the side, pulling a passing segment round, and (inside the object) making the path
// touch it where it reflects, against a dense search for the shortest touching path, and, moving with a
// link of its own, picking the other side; and, on a random leg with such wraps, the Jacobian against
// central differences of the lengths, and tau = -J^T f. The comparison with libmujoco itself is
// tests/core/test_wrap_mujoco_vs_mujoco.cpp.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/core/wrap_object.hpp"
#include "support/allocation_counter.hpp"
#include "support/error_assertions.hpp"
#include "support/mujoco_wrap_model.hpp"

namespace sinew {
namespace {

WrapObject makeObject(WrapShape shape, double radius, double length = 0) {
    WrapObject object;
    object.shape = shape;
    object.radius = radius;
    object.length = length;
    return object;
}

// The wrap of ends (-2, y, z1) and (2, y, z2) round a unit circle about the origin in z = 0, over the top
// (+y) or under it: tangents sqrt(D^2 - 1) long touching acos(1/D) from each end's polar angle.
struct SymmetricWrap {
    double tangent = 0, arc = 0, theta1 = 0, theta2 = 0;
};
SymmetricWrap calcSymmetricWrap(double y, bool overTheTop) {
    const double D = std::hypot(2.0, y), alpha = std::acos(1 / D), phi = std::atan2(y, 2.0);
    SymmetricWrap w;
    w.tangent = std::sqrt(D * D - 1);
    w.arc = overTheTop ? M_PI - 2 * phi - 2 * alpha : M_PI + 2 * phi - 2 * alpha;
    w.theta1 = overTheTop ? M_PI - phi - alpha : M_PI - phi + alpha;
    w.theta2 = overTheTop ? phi + alpha : phi - alpha;
    return w;
}

Eigen::Vector3d onUnitCircle(double theta, double z = 0) { return Eigen::Vector3d(std::cos(theta), std::sin(theta), z); }

TEST(WrapMuJoCo, SphereMatchesClosedForm) {
    const SymmetricWrap w = calcSymmetricWrap(0.5, true);
    const Eigen::Vector3d p1(-2, 0.5, 0), p2(2, 0.5, 0);
    // In the sphere's frame and turned by a random rotation: the sphere's plane is that of its centre and
    // both ends, wherever they are.
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -0.7, 0.2).normalized()).toRotationMatrix();
    for (const Eigen::Matrix3d& Q : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), turn}) {
        const WrapSolution s = calcMuJoCoWrap(makeObject(WrapShape::Sphere, 1), nullptr, Q * p1, Q * p2);
        ASSERT_EQ(s.status, WrapStatus::Wrapped);
        EXPECT_NEAR(s.arcLength, w.arc, 1e-14);
        EXPECT_NEAR(s.calcLength(Q * p1, Q * p2), 2 * w.tangent + w.arc, 1e-14);
        EXPECT_LE((s.r1_W - Q * onUnitCircle(w.theta1)).norm(), 1e-14);
        EXPECT_LE((s.r2_W - Q * onUnitCircle(w.theta2)).norm(), 1e-14);
    }
}

TEST(WrapMuJoCo, CylinderIsInfiniteAndWindsAHelix) {
    // Ends (-+2, 0.5, -+1): across the axis as the sphere case, H = 2 tangent + arc, and the rise of 2
    // shared in proportion. The cylinder is 0.1 long and both tangent points lie beyond its ends, where
    // OpenSim's finite cylinder lets the segment go; MuJoCo's wrapping cylinder has no ends.
    const SymmetricWrap w = calcSymmetricWrap(0.5, true);
    const Eigen::Vector3d p1(-2, 0.5, -1), p2(2, 0.5, 1);
    const WrapObject cylinder = makeObject(WrapShape::Cylinder, 1, 0.1);
    const WrapSolution s = calcMuJoCoWrap(cylinder, nullptr, p1, p2);
    ASSERT_EQ(s.status, WrapStatus::Wrapped);
    const double H = 2 * w.tangent + w.arc;
    EXPECT_NEAR(s.calcLength(p1, p2), std::hypot(H, 2.0), 1e-14);
    EXPECT_NEAR(s.arcLength, std::hypot(w.arc, 2 * w.arc / H), 1e-14);
    EXPECT_LE((s.r1_W - onUnitCircle(w.theta1, -1 + 2 * w.tangent / H)).norm(), 1e-14);
    EXPECT_LE((s.r2_W - onUnitCircle(w.theta2, 1 - 2 * w.tangent / H)).norm(), 1e-14);
    EXPECT_EQ(calcCylinderWrap(cylinder, p1, p2).status, WrapStatus::NoWrap);
}

TEST(WrapMuJoCo, SegmentThatMissesOrEndsInsideDoesNotWrap) {
    for (const WrapShape shape : {WrapShape::Sphere, WrapShape::Cylinder}) {
        const WrapObject object = makeObject(shape, 1, 0.1);
        EXPECT_EQ(calcMuJoCoWrap(object, nullptr, {-2, 1.5, 0}, {2, 1.5, 0.3}).status, WrapStatus::NoWrap);
        // A segment through the object that stops short of it, and one from inside it.
        EXPECT_EQ(calcMuJoCoWrap(object, nullptr, {-3, 0.5, 0}, {-1.5, 0.5, 0}).status, WrapStatus::NoWrap);
        EXPECT_EQ(calcMuJoCoWrap(object, nullptr, {-0.5, 0.5, 0}, {2, 0.5, 0}).status, WrapStatus::InsideRadius);
    }
    // Within the radius of the (infinite) cylinder's axis, far beyond its length, is inside.
    EXPECT_EQ(calcMuJoCoWrap(makeObject(WrapShape::Cylinder, 1, 0.1), nullptr, {-0.5, 0.5, 4}, {2, 0.5, 0}).status,
              WrapStatus::InsideRadius);
}

TEST(WrapMuJoCo, SideSiteChoosesTheSide) {
    const Eigen::Vector3d p1(-2, 0.5, 0), p2(2, 0.5, 0);
    for (const WrapShape shape : {WrapShape::Sphere, WrapShape::Cylinder}) {
        const WrapObject object = makeObject(shape, 1, 0.1);
        for (const bool over : {true, false}) {
            // (The side site's height above the plane does not matter: it is projected on it.)
            const Eigen::Vector3d side(0.2, over ? 3 : -3, 0.7);
            const SymmetricWrap w = calcSymmetricWrap(0.5, over);
            const WrapSolution s = calcMuJoCoWrap(object, &side, p1, p2);
            ASSERT_EQ(s.status, WrapStatus::Wrapped);
            EXPECT_NEAR(s.arcLength, w.arc, 1e-14);
            EXPECT_NEAR(s.calcLength(p1, p2), 2 * w.tangent + w.arc, 1e-14);
            EXPECT_LE((s.r1_W - onUnitCircle(w.theta1)).norm(), 1e-14);
            EXPECT_LE((s.r2_W - onUnitCircle(w.theta2)).norm(), 1e-14);
        }
    }
}

TEST(WrapMuJoCo, SideSitePullsAPassingSegmentRound) {
    // The segment at y = 1.5 misses the unit circle: a side site beyond it (-y) pulls it round the far
    // side, one on its own side leaves it straight.
    const Eigen::Vector3d p1(-2, 1.5, 0), p2(2, 1.5, 0), far(0, -3, 0), near(0, 3, 0);
    const SymmetricWrap w = calcSymmetricWrap(1.5, false);
    for (const WrapShape shape : {WrapShape::Sphere, WrapShape::Cylinder}) {
        const WrapObject object = makeObject(shape, 1, 0.1);
        const WrapSolution s = calcMuJoCoWrap(object, &far, p1, p2);
        ASSERT_EQ(s.status, WrapStatus::Wrapped);
        EXPECT_NEAR(s.arcLength, w.arc, 1e-14);
        EXPECT_LE((s.r1_W - onUnitCircle(w.theta1)).norm(), 1e-14);
        EXPECT_LE((s.r2_W - onUnitCircle(w.theta2)).norm(), 1e-14);
        EXPECT_EQ(calcMuJoCoWrap(object, &near, p1, p2).status, WrapStatus::NoWrap);
    }
}

// A unit sphere on a welded base with a wire from (-2, 0.5, 0) to (2, 0.5, 0) on the base over it, and the
// wrap's side site (0.2, 3, 0.7) on `sideSiteLink`: the base, or a rotor pinned to it about x through the
// sphere's centre, which carries nothing else.
Model buildSphereWithSideSiteOn(const std::string& sideSiteLink) {
    ModelBuilder builder("side_site_on_a_rotor");
    builder.addLink({"base", 0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero(), ""});
    builder.addLink({"rotor", 1, Eigen::Vector3d::Zero(), 0.01 * Eigen::Matrix3d::Identity(), ""});
    JointSpec weld, pin;
    weld.name = "mount", weld.type = JointType::Weld, weld.parent = "ground", weld.child = "base";
    pin.name = "turn", pin.type = JointType::Pin, pin.parent = "base", pin.child = "rotor", pin.axis = Eigen::Vector3d::UnitX();
    builder.addJoint(weld);
    builder.addJoint(pin);
    WrapObjectSpec sphere;
    sphere.name = "ball", sphere.shape = WrapShape::Sphere, sphere.link = "base", sphere.radius = 1;
    builder.addWrapObject(sphere);
    WireSpec wire;
    wire.name = "over_the_ball", wire.kind = WireKind::Tendon;
    wire.law.type = "prescribed_tension";
    wire.law.parameters.set("tension", {10});
    wire.points = {{"base", Eigen::Vector3d(-2, 0.5, 0), ""}, {"base", Eigen::Vector3d(2, 0.5, 0), ""}};
    WireWrapSpec wrap;
    wrap.object = "ball", wrap.method = WrapMethod::MuJoCo, wrap.firstPoint = 0, wrap.lastPoint = 1;
    wrap.sideSite = Eigen::Vector3d(0.2, 3, 0.7);
    wrap.sideSiteLink = sideSiteLink;
    wire.wraps.push_back(wrap);
    builder.addWire(wire);
    return builder.build();
}

TEST(WrapMuJoCo, SideSiteMovesWithItsOwnLink) {
    // Turning the rotor by pi about x takes the side site to (0.2, -3, -0.7): the wire goes under the
    // sphere; fixed on the base it stays over. The side site only picks the side, so dL/dq is 0 along the
    // rotor's angle wherever the side holds, as central differences of the length say.
    const Model onRotor = buildSphereWithSideSiteOn("rotor"), onBase = buildSphereWithSideSiteOn("");
    const int rotor = onRotor.findLinkIndex("rotor");
    EXPECT_EQ(onRotor.getWire(0).wraps[0].sideSiteLink, rotor);
    EXPECT_EQ(onBase.getWire(0).wraps[0].sideSiteLink, onBase.findLinkIndex("base"));
    EXPECT_EQ(onRotor.getSupportLinks(onRotor.getWire(0)), (std::vector<int>{rotor, onRotor.findLinkIndex("base")}));
    const SymmetricWrap over = calcSymmetricWrap(0.5, true), under = calcSymmetricWrap(0.5, false);
    Data data(onRotor), fixed(onBase);
    Eigen::MatrixXd J(1, 1);
    constexpr double h = 1e-6;
    const std::vector<std::pair<double, SymmetricWrap>> poses = {{0.0, over}, {0.3, over}, {M_PI, under}, {2.9, under}};
    for (const auto& [angle, wrap] : poses) {
        SCOPED_TRACE("rotor angle " + std::to_string(angle));
        const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, angle);
        calcPositionKinematics(onBase, fixed, q);
        calcWirePaths(onBase, fixed);
        EXPECT_NEAR(fixed.wireLength[0], 2 * over.tangent + over.arc, 1e-14);
        double length[2];
        for (int side = 0; side < 2; ++side) {
            calcPositionKinematics(onRotor, data, q + Eigen::VectorXd::Constant(1, side == 0 ? h : -h));
            calcWirePaths(onRotor, data);
            length[side] = data.wireLength[0];
        }
        calcPositionKinematics(onRotor, data, q);
        calcWirePaths(onRotor, data);
        calcWireJacobian(onRotor, data, J);
        EXPECT_NEAR(data.wireLength[0], 2 * wrap.tangent + wrap.arc, 1e-14);
        EXPECT_NEAR(J(0, 0), (length[0] - length[1]) / (2 * h), 1e-9);
    }
}

// The shortest path from a to b (2D, outside the unit circle) that touches the circle, by a dense search
// over the point of contact refined by golden sections: its length and contact point.
std::pair<double, Eigen::Vector2d> findShortestTouchingPath(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    auto length = [&](double t) {
        const Eigen::Vector2d c(std::cos(t), std::sin(t));
        return (c - a).norm() + (b - c).norm();
    };
    double best = 0;
    for (int i = 1; i < 20000; ++i)
        if (length(2 * M_PI * i / 20000) < length(best)) best = 2 * M_PI * i / 20000;
    double lo = best - 2 * M_PI / 20000, hi = best + 2 * M_PI / 20000;
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int i = 0; i < 100; ++i) {
        const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        (length(x1) < length(x2) ? hi : lo) = length(x1) < length(x2) ? x2 : x1;
    }
    const double t = 0.5 * (lo + hi);
    return {length(t), Eigen::Vector2d(std::cos(t), std::sin(t))};
}

TEST(WrapMuJoCo, SideSiteInsideTouchesWhereThePathReflects) {
    // A side site within the radius: a segment passing the object is bent onto it, touching it at one point
    // (no arc), the shortest such path; a segment through it goes straight. 2.2.2 judges "within" in the
    // wrapping plane: (0, 0.2, 5) is outside the sphere but projects inside it (MuJoCo >= 3.2.3 asks |s| < R).
    const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> ends = {
        {{-2, 1.5, 0}, {2, 1.5, 0}}, {{-2, 1.5, 0}, {1, 2.5, 0}}, {{1.3, -1.1, 0}, {-0.4, -2.2, 0}}};
    for (const WrapShape shape : {WrapShape::Sphere, WrapShape::Cylinder}) {
        const WrapObject object = makeObject(shape, 1, 0.1);
        for (const Eigen::Vector3d& side : {Eigen::Vector3d(0, 0.2, 0), Eigen::Vector3d(0, 0.2, 5)}) {
            for (const auto& [p1, p2] : ends) {
                const WrapSolution s = calcMuJoCoWrap(object, &side, p1, p2);
                ASSERT_EQ(s.status, WrapStatus::Wrapped);
                const auto [shortest, contact] = findShortestTouchingPath(p1.head<2>(), p2.head<2>());
                EXPECT_EQ(s.r1_W, s.r2_W);
                EXPECT_EQ(s.arcLength, 0);
                EXPECT_NEAR(s.calcLength(p1, p2), shortest, 1e-11);
                // Newton's stop at |f| <= 1e-6 leaves the contact that close, the length second order in it.
                EXPECT_LE((s.r1_W - Eigen::Vector3d(contact.x(), contact.y(), 0)).norm(), 1e-6);
            }
            EXPECT_EQ(calcMuJoCoWrap(object, &side, {-2, 0.5, 0}, {2, 0.5, 0}).status, WrapStatus::NoWrap);
        }
    }
}

// Which points and tangent points a wire's path has: a finite difference is only taken where it keeps it.
std::vector<std::pair<int, int>> describePath(const Data& data, int w) {
    std::vector<std::pair<int, int>> path;
    for (int i = 0; i < data.wirePathSize[static_cast<std::size_t>(w)]; ++i) {
        const Data::WirePathPoint& p = data.wirePath[static_cast<std::size_t>(data.wirePathStart[static_cast<std::size_t>(w)] + i)];
        path.emplace_back(p.point, p.wrap);
    }
    return path;
}

TEST(WrapMuJoCo, JacobianMatchesCentralDifferencesOfLength) {
    // The Jacobian holds tangent points on their objects (as MuJoCo's ten_J does); for the exact tangents
    // of the circle wrap, and the contact of the inside wrap, that is the length's derivative.
    constexpr double h = 1e-6;
    double worst = 0;
    int wrapped = 0, straight = 0, compared = 0;
    for (unsigned seed = 1; seed <= 3; ++seed) {
        std::mt19937 rng(seed);
        const Model model = test::buildMujocoLegModel(test::generateMujocoLeg(rng));
        Data data(model), moved(model);
        Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
        std::uniform_real_distribution<double> angle(-1.5, 1.5);
        for (int pose = 0; pose < 20; ++pose) {
            Eigen::VectorXd q(model.getNumQ()), u(model.getNumU());
            for (int i = 0; i < q.size(); ++i) q[i] = angle(rng);
            for (int i = 0; i < u.size(); ++i) u[i] = angle(rng);
            calcPositionKinematics(model, data, q);
            calcWirePaths(model, data);
            calcWireJacobian(model, data, J);
            calcVelocityKinematics(model, data, u);
            calcWireSpeeds(model, data);
            for (int w = 0; w < model.getNumWires(); ++w) {
                const std::vector<std::pair<int, int>> path = describePath(data, w);
                ++(static_cast<int>(path.size()) > model.getWire(w).numPoints ? wrapped : straight);
                EXPECT_NEAR(data.wireSpeed[w], J.row(w).dot(u), 1e-13);
                for (int i = 0; i < model.getNumU(); ++i) {
                    double length[2];
                    bool sameTopology = true;
                    for (int side = 0; side < 2; ++side) {
                        Eigen::VectorXd qs = q;
                        qs[i] += side == 0 ? h : -h;
                        calcPositionKinematics(model, moved, qs);
                        calcWirePaths(model, moved);
                        length[side] = moved.wireLength[w];
                        sameTopology = sameTopology && describePath(moved, w) == path;
                    }
                    if (!sameTopology) continue;  // a wrap starting or ending inside the step
                    worst = std::max(worst, std::abs(J(w, i) - (length[0] - length[1]) / (2 * h)));
                    ++compared;
                }
            }
        }
    }
    std::cout << "MuJoCo wraps: worst |J - dL/dq| " << worst << " over " << compared << " entries (" << wrapped
              << " wrapped paths, " << straight << " straight)\n";
    EXPECT_LT(worst, 1e-7);
    EXPECT_GT(wrapped, 100);
    EXPECT_GT(straight, 20);
}

TEST(WrapMuJoCo, BuilderRefusesANonFiniteSideSite) {
    std::mt19937 rng(3);
    test::MujocoLeg leg = test::generateMujocoLeg(rng);
    for (test::MujocoLegFrameItem& site : leg.sites)
        if (site.name == "knee_side_out") site.pos.y() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { test::buildMujocoLegModel(leg); }, "",
                                                {"wire 'knee_side'", "wrap over 'knee_ball'", "side site", "finite"}, ""));
}

TEST(WrapMuJoCo, ForcesAreMinusJTransposeTensionsWithoutAllocating) {
    std::mt19937 rng(7);
    const Model model = test::buildMujocoLegModel(test::generateMujocoLeg(rng));
    Data data(model);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    Eigen::VectorXd tau(model.getNumU()), tensions(model.getNumWires());
    for (int w = 0; w < tensions.size(); ++w) tensions[w] = 10 + w;
    const Eigen::VectorXd q = Eigen::Vector3d(0.9, -1.2, 0.7);
    const long long before = test::getAllocationCount();
    calcPositionKinematics(model, data, q);
    calcWirePaths(model, data);
    calcWireJacobian(model, data, J);
    calcWireGeneralizedForces(model, data, tensions, tau);
    const long long allocations = test::getAllocationCount() - before;
    EXPECT_LE((tau + J.transpose() * tensions).norm(), 1e-13 * tensions.norm());
    if (test::isCountingAllocations()) {
        EXPECT_EQ(allocations, 0);
    }
}

}  // namespace
}  // namespace sinew

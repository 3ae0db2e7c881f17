// Virtual links in quasi-static equilibrium: the solved pose against a hand-worked case, the stiffness and
// the quasi-static twist against finite differences, and the equilibrated forces on the bones against the
// virtual work of the wires' potential energy (dV/dq by finite differences, the equilibrium re-solved).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/model_builder.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "support/allocation_counter.hpp"
#include "support/forked_model.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

// Bone kinematics and wire paths at (q, u), then the equilibrium warm-started from q's virtual-link pose.
const VirtualLinkEquilibriumStatus& solveAt(const Model& model, Data& data, VirtualLinkEquilibriumData& eq,
                                            const Eigen::VectorXd& q, const Eigen::VectorXd& u, double time = 0) {
    calcPositionKinematics(model, data, q);
    calcVelocityKinematics(model, data, u);
    calcWirePaths(model, data);
    calcWireSpeeds(model, data);
    return calcVirtualLinkEquilibrium(model, data, time, eq);
}

// Chains with three forks whose branches stay taut (support/forked_model.hpp).
Model makeForkedModel(unsigned seed, double damping, bool loop = false) {
    test::ForkedModelOptions o;
    o.numForks = 3;
    o.loop = loop;
    o.damping = damping;
    o.seed = seed;
    return test::makeForkedModel(o);
}

// A pose of the bones near the default one, so that the forks stay taut.
Eigen::VectorXd perturbedPose(const Model& model, std::mt19937& rng) {
    return integrateCoordinates(model, model.getDefaultQ(), generateRandomSpeeds(model, rng), 0.1);
}

Eigen::VectorXd withVirtualLinks(const Model& model, const Data& data, const VirtualLinkEquilibriumData& eq,
                                 Eigen::VectorXd q) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(model.getNumU());
    getVirtualLinkCoordinates(model, data, eq, q, u);
    return q;
}

// A point-like virtual link (all wire points at its origin) held by three springs from a frame welded to
// ground: one from A1 = (-D, 0, 0), two to A2,3 = (D, +-h, 0).
constexpr double kD = 0.3, kH = 0.1;
Model makePointNodeModel(double k1, double L1, double k2, double L2) {
    ModelBuilder builder("node");
    LinkSpec frame;
    frame.name = "frame";
    frame.mass = 1.0;
    frame.inertia_Bcom = Eigen::Matrix3d::Identity() * 0.01;
    builder.addLink(frame);
    JointSpec weld;
    weld.name = "weld";
    weld.type = JointType::Weld;
    weld.parent = "ground";
    weld.child = "frame";
    builder.addJoint(weld);
    VirtualLinkSpec node;
    node.name = "node";
    node.initialPosition = Eigen::Vector3d(0.05, 0.04, -0.03);
    builder.addVirtualLink(node);
    auto addSpring = [&](const std::string& name, const std::string& fromLink, const Eigen::Vector3d& from,
                         const std::string& toLink, const Eigen::Vector3d& to, double k, double rest) {
        WireSpec wire;
        wire.name = name;
        for (const auto& [link, p_B] : {std::pair(fromLink, from), std::pair(toLink, to)}) {
            WirePointSpec point;
            point.link = link;
            point.p_B = p_B;
            wire.points.push_back(point);
        }
        wire.law.type = "spring_damper";
        wire.law.parameters.set("stiffness", {k});
        wire.law.parameters.set("rest_length", {rest});
        builder.addWire(wire);
    };
    const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    addSpring("w1", "frame", Eigen::Vector3d(-kD, 0, 0), "node", origin, k1, L1);
    addSpring("w2", "node", origin, "frame", Eigen::Vector3d(kD, kH, 0), k2, L2);
    addSpring("w3", "node", origin, "frame", Eigen::Vector3d(kD, -kH, 0), k2, L2);
    return builder.build();
}

// By symmetry the point node sits on the x axis, where the x-balance k1 (x + D - L1) = 2 k2 (s - L2) (D - x) / s,
// s = sqrt((D - x)^2 + h^2), is solved here by bisection.
TEST(VirtualLinkEquilibrium, PointNodeMatchesHandSolvedBalance) {
    const double D = kD, h = kH, k1 = 800, L1 = 0.2, k2 = 500, L2 = 0.25;
    const Model model = makePointNodeModel(k1, L1, k2, L2);

    auto balance = [&](double x) {
        const double s = std::hypot(D - x, h);
        return k1 * (x + D - L1) - 2 * k2 * (s - L2) * (D - x) / s;
    };
    double lo = -D + L1, hi = D;  // balance < 0 at lo (w1 slack), > 0 at hi
    ASSERT_LT(balance(lo), 0);
    ASSERT_GT(balance(hi), 0);
    for (int i = 0; i < 200; ++i) (balance(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
    const double x = 0.5 * (lo + hi);

    Data data(model);
    VirtualLinkEquilibriumData eq(model);
    const VirtualLinkEquilibriumStatus& status =
        solveAt(model, data, eq, model.getDefaultQ(), Eigen::VectorXd::Zero(model.getNumU()));
    EXPECT_TRUE(status.converged);
    const std::size_t node = static_cast<std::size_t>(model.findLinkIndex("node"));
    EXPECT_NEAR(data.p_GB[node].x(), x, 1e-12);
    EXPECT_NEAR(data.p_GB[node].y(), 0, 1e-12);
    EXPECT_NEAR(data.p_GB[node].z(), 0, 1e-12);
    // No wire point off the origin: nothing turns the node, and the regularised solve leaves it unrotated.
    EXPECT_TRUE(data.R_GB[node].isApprox(Eigen::Matrix3d::Identity(), 1e-15));
    EXPECT_NEAR(eq.tension[0], k1 * (x + D - L1), 1e-9);
    EXPECT_NEAR(eq.tension[1], k2 * (std::hypot(D - x, h) - L2), 1e-9);
    EXPECT_LE(status.residual, 1e-11 * status.forceScale);
    std::printf("point node: x = %.15f (bisection %.15f), %d Newton iterations, residual %.2e N of %.1f N\n",
                data.p_GB[node].x(), x, status.iterations, status.residual, status.forceScale);
}

// The stiffness is -d(residual)/d(scaled pose) at frozen wire speeds: checked against central differences
// with the bones at rest and the virtual links still (speeds zero whatever the pose), damping on.
TEST(VirtualLinkEquilibrium, StiffnessMatchesFiniteDifferences) {
    std::mt19937 rng(3);
    double worst = 0;
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const Model model = makeForkedModel(seed, 1.0);
        const Eigen::VectorXd u = Eigen::VectorXd::Zero(model.getNumU());
        Data data(model);
        VirtualLinkEquilibriumData eq(model);
        // Off equilibrium (a random step away from it), where the stiffness's asymmetric part shows too.
        const Eigen::VectorXd bones = perturbedPose(model, rng);
        solveAt(model, data, eq, bones, u);
        Eigen::VectorXd q = withVirtualLinks(model, data, eq, bones);
        Eigen::VectorXd away = Eigen::VectorXd::Zero(model.getNumU());
        for (int v : eq.links) away.segment<6>(model.getJoint(v).uStart) = generateRandomSpeeds(model, rng, 0.02).head<6>();
        q = integrateCoordinates(model, q, away, 1.0);
        auto residualAt = [&](const Eigen::VectorXd& qq) {
            calcPositionKinematics(model, data, qq);
            calcVelocityKinematics(model, data, u);
            calcWirePaths(model, data);
            calcWireSpeeds(model, data);
            calcVirtualLinkResidual(model, data, 0.0, eq);
            return Eigen::VectorXd(eq.residual);
        };
        residualAt(q);
        calcVirtualLinkStiffness(model, data, eq);
        const Eigen::MatrixXd K = eq.stiffness;
        const double step = 1e-6;
        for (std::size_t s = 0; s < eq.links.size(); ++s)
            for (int j = 0; j < 6; ++j) {
                // A unit scaled displacement: rotation (about the origin, in ground) of 1 / lengthScale rad.
                Eigen::VectorXd direction = Eigen::VectorXd::Zero(model.getNumU());
                direction[model.getJoint(eq.links[s]).uStart + j] = j < 3 ? 1 / eq.lengthScale[s] : 1.0;
                const Eigen::VectorXd column =
                    -(residualAt(integrateCoordinates(model, q, direction, step)) -
                      residualAt(integrateCoordinates(model, q, direction, -step))) / (2 * step);
                const Eigen::Index c = 6 * static_cast<Eigen::Index>(s) + j;
                worst = std::max(worst, (K.col(c) - column).norm() / K.norm());
                EXPECT_LE((K.col(c) - column).norm(), 1e-6 * K.norm())
                    << "seed " << seed << " column " << c << "\n" << K.col(c).transpose() << "\n" << column.transpose();
            }
    }
    std::printf("stiffness vs central differences, 6 models x 3 virtual links: worst column error %.2e of |K|\n", worst);
}

// With conservative wires the equilibrium pose minimises their potential energy V over the virtual links'
// poses, so dV/d(pose) vanishes; and the generalized forces on the bones, -J^T f with the equilibrated
// tensions, are -dV/dq with the equilibrium re-solved at every displaced q (virtual work: the virtual links'
// own terms drop out because they are at equilibrium). Both by central differences. With and without loops.
TEST(VirtualLinkEquilibrium, BoneForcesAreTheGradientOfTheWirePotential) {
    std::mt19937 rng(5);
    double worstBone = 0, worstVirtual = 0;
    for (unsigned seed = 1; seed <= 8; ++seed) {
        const Model model = makeForkedModel(seed, 0.0, seed % 2 == 1);
        const int nu = model.getNumU();
        const Eigen::VectorXd u = Eigen::VectorXd::Zero(nu);
        Data data(model);
        VirtualLinkEquilibriumData eq(model);
        const Eigen::VectorXd bones = perturbedPose(model, rng);
        ASSERT_TRUE(solveAt(model, data, eq, bones, u).converged) << "seed " << seed;
        ASSERT_EQ(eq.status.slackLinks, 0) << "seed " << seed;
        const Eigen::VectorXd q = withVirtualLinks(model, data, eq, bones);
        Eigen::VectorXd tensions(model.getNumWires()), tau(nu);
        calcWireTensions(model, data, 0.0, tensions);
        calcWireGeneralizedForces(model, data, tensions, tau);

        // V at qq, with the equilibrium re-solved (warm-started from q's) or the virtual links held at qq's pose.
        auto potentialAt = [&](const Eigen::VectorXd& qq, bool resolve) {
            if (resolve) {
                EXPECT_TRUE(solveAt(model, data, eq, qq, u).converged);
            } else {
                calcPositionKinematics(model, data, qq);
                calcWirePaths(model, data);
            }
            return calcWirePotentialEnergy(model, data);
        };
        const double step = 1e-6;
        double scale = 0;
        for (int i = 0; i < nu; ++i) scale = std::max(scale, std::abs(tau[i]));
        ASSERT_GT(scale, 0);
        for (int i = 0; i < nu; ++i) {
            const Eigen::VectorXd e = Eigen::VectorXd::Unit(nu, i);
            int link = 0;
            while (!(model.getJoint(link).uStart <= i && i < model.getJoint(link).uStart + model.getJoint(link).nu)) ++link;
            const bool virtualCoordinate = model.getLink(link).isVirtual;
            // For a virtual link's coordinate: V along its own pose at fixed bones (should be stationary).
            const double dV = (potentialAt(integrateCoordinates(model, q, e, step), !virtualCoordinate) -
                               potentialAt(integrateCoordinates(model, q, e, -step), !virtualCoordinate)) / (2 * step);
            (virtualCoordinate ? worstVirtual : worstBone) =
                std::max(virtualCoordinate ? worstVirtual : worstBone, std::abs(virtualCoordinate ? dV : tau[i] + dV) / scale);
            if (virtualCoordinate)
                EXPECT_LE(std::abs(dV), 1e-7 * scale) << "seed " << seed << " virtual coordinate " << i;
            else
                EXPECT_LE(std::abs(tau[i] + dV), 1e-7 * scale)
                    << "seed " << seed << " coordinate " << i << ": tau " << tau[i] << ", -dV/dq " << -dV;
        }
    }
    std::printf("virtual work, 8 models: |tau + dV/dq| <= %.2e, |dV/d(virtual pose)| <= %.2e of max |tau|\n",
                worstBone, worstVirtual);
}

// The quasi-static twist is the rate of the equilibrium pose as the bones move: against central differences
// of the re-solved pose along u, with conservative wires (for which it is exact).
TEST(VirtualLinkEquilibrium, TwistIsTheRateOfTheEquilibriumPose) {
    std::mt19937 rng(8);
    double worst = 0;
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const Model model = makeForkedModel(seed, 0.0);
        Data data(model);
        VirtualLinkEquilibriumData eq(model);
        const Eigen::VectorXd u = generateRandomSpeeds(model, rng);
        const Eigen::VectorXd bones = perturbedPose(model, rng);
        ASSERT_TRUE(solveAt(model, data, eq, bones, u).converged);
        const Eigen::VectorXd q = withVirtualLinks(model, data, eq, bones);
        std::vector<Eigen::Vector3d> w, v;
        for (int l : eq.links) {
            w.push_back(data.w_GB[static_cast<std::size_t>(l)]);
            v.push_back(data.v_GB[static_cast<std::size_t>(l)]);
        }
        const double dt = 1e-6;
        auto poseAt = [&](double t, std::vector<Eigen::Matrix3d>& R, std::vector<Eigen::Vector3d>& p) {
            EXPECT_TRUE(solveAt(model, data, eq, integrateCoordinates(model, q, u, t), u).converged);
            R.clear();
            p.clear();
            for (int l : eq.links) {
                R.push_back(data.R_GB[static_cast<std::size_t>(l)]);
                p.push_back(data.p_GB[static_cast<std::size_t>(l)]);
            }
        };
        std::vector<Eigen::Matrix3d> Rplus, Rminus;
        std::vector<Eigen::Vector3d> pplus, pminus;
        poseAt(dt, Rplus, pplus);
        poseAt(-dt, Rminus, pminus);
        for (std::size_t s = 0; s < eq.links.size(); ++s) {
            const Eigen::AngleAxisd turn(Rplus[s] * Rminus[s].transpose());
            const Eigen::Vector3d wFD = turn.angle() * turn.axis() / (2 * dt);
            const Eigen::Vector3d vFD = (pplus[s] - pminus[s]) / (2 * dt);
            const double scale = std::max(v[s].norm(), eq.lengthScale[s] * w[s].norm());
            worst = std::max({worst, (v[s] - vFD).norm() / scale, eq.lengthScale[s] * (w[s] - wFD).norm() / scale});
            ASSERT_GT(scale, 0);
            EXPECT_LE((v[s] - vFD).norm(), 1e-6 * scale) << "seed " << seed << " link " << s;
            EXPECT_LE(eq.lengthScale[s] * (w[s] - wFD).norm(), 1e-6 * scale) << "seed " << seed << " link " << s;
        }
    }
    std::printf("quasi-static twist vs central differences of the pose, 6 models: worst %.2e relative\n", worst);
}

// All wires of a virtual link slack: nothing pulls, the link stays where it was, and nothing is NaN.
TEST(VirtualLinkEquilibrium, SlackLinkStaysPutWithoutNaN) {
    const Model model = makePointNodeModel(800, 2.0, 500, 2.0);  // rest lengths beyond any reach
    Data data(model);
    VirtualLinkEquilibriumData eq(model);
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(model.getNumU(), 0.3);
    const VirtualLinkEquilibriumStatus& status = solveAt(model, data, eq, model.getDefaultQ(), u);
    EXPECT_TRUE(status.converged);
    EXPECT_EQ(status.slackLinks, 1);
    EXPECT_EQ(status.forceScale, 0);
    const std::size_t node = static_cast<std::size_t>(model.findLinkIndex("node"));
    EXPECT_EQ(data.p_GB[node], Eigen::Vector3d(0.05, 0.04, -0.03));
    EXPECT_TRUE(data.w_GB[node].isZero(0));
    EXPECT_TRUE(data.v_GB[node].isZero(0));
    EXPECT_TRUE(eq.tension.isZero(0));
    EXPECT_TRUE(data.wireLength.allFinite() && data.wireSpeed.allFinite());
}

TEST(VirtualLinkEquilibrium, CalcAllocatesNothing) {
    if (!test::isCountingAllocations()) GTEST_SKIP() << "allocations are not counted under AddressSanitizer";
    const Model model = makeForkedModel(1, 1.0, true);
    std::mt19937 rng(2);
    const Eigen::VectorXd q = perturbedPose(model, rng), u = generateRandomSpeeds(model, rng);
    Data data(model);
    VirtualLinkEquilibriumData eq(model);
    solveAt(model, data, eq, model.getDefaultQ(), u);  // warm-up from afar
    const long long before = test::getAllocationCount();
    const VirtualLinkEquilibriumStatus& status = solveAt(model, data, eq, q, u);
    EXPECT_EQ(test::getAllocationCount() - before, 0);
    EXPECT_TRUE(status.converged);
    EXPECT_GT(status.iterations, 0);
}

}  // namespace
}  // namespace sinew

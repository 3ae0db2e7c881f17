// Paths with OpenSim's features (wraps over cylinders, spheres with a quadrant, ellipsoids, two wraps on one
// wire, conditional and moving points): the Jacobian against central differences of the length, the
// speeds it predicts, tau = -J^T f, the sparse J^T, and no allocation while evaluating.
#include <gtest/gtest.h>

#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "support/allocation_counter.hpp"
#include "support/wrap_test_model.hpp"

namespace sinew {
namespace {

// Which points and tangent points a wire's path has: a finite difference is only taken where it keeps it.
std::vector<std::pair<int, int>> describePath(const Data& data, int w) {
    std::vector<std::pair<int, int>> path;
    for (int i = 0; i < data.wirePathSize[static_cast<std::size_t>(w)]; ++i) {
        const Data::WirePathPoint& p = data.wirePath[static_cast<std::size_t>(data.wirePathStart[static_cast<std::size_t>(w)] + i)];
        path.emplace_back(p.point, p.wrap);
    }
    return path;
}

struct Difference {
    double length = 0;
    bool sameTopology = true;
};

// dL_w/du_i by central differences, q moved on its manifold.
Difference differentiate(const Model& model, const Eigen::VectorXd& q, int w, int i, double h) {
    Data data(model);
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(model.getNumU(), i);
    auto evaluate = [&](double step) {
        calcPositionKinematics(model, data, integrateCoordinates(model, q, e, step));
        calcWirePaths(model, data);
        return std::pair(data.wireLength[w], describePath(data, w));
    };
    const auto [centre, path] = evaluate(0);
    const auto [plus, pathPlus] = evaluate(h);
    const auto [minus, pathMinus] = evaluate(-h);
    (void)centre;
    return {(plus - minus) / (2 * h), pathPlus == path && pathMinus == path};
}

TEST(WirePathFeatures, JacobianMatchesCentralDifferences) {
    const Model model = test::loadWrapArm();
    std::mt19937 rng(21);
    Data data(model);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    std::vector<int> wrappedPoses(static_cast<std::size_t>(model.getNumWires()), 0), straightPoses = wrappedPoses;
    int tangentAcrossQuadrant = 0, conditionalOff = 0, conditionalOn = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const Eigen::VectorXd q = test::randomWrapArmPose(model, rng);
        calcPositionKinematics(model, data, q);
        calcWirePaths(model, data);
        calcWireJacobian(model, data, J);
        for (int w = 0; w < model.getNumWires(); ++w) {
            const Wire& wire = model.getWire(w);
            const std::vector<std::pair<int, int>> path = describePath(data, w);
            const bool wrapped = static_cast<int>(path.size()) > wire.numPoints;
            ++(wrapped ? wrappedPoses : straightPoses)[static_cast<std::size_t>(w)];
            if (wire.name == "over_sphere" && wrapped) {
                // The sphere is kept to +x of its frame (= upper's); count tangent points on the other side.
                const Data::WirePathPoint& r1 = data.wirePath[static_cast<std::size_t>(data.wirePathStart[static_cast<std::size_t>(w)] + 1)];
                const Eigen::Vector3d r1_B = data.R_GB[1].transpose() * (r1.p_G - data.p_GB[1]);
                if (r1_B.x() < 0) ++tangentAcrossQuadrant;
            }
            if (wire.name == "conditional_and_moving") ++(path.size() == 2 ? conditionalOff : conditionalOn);
            double error = 0, scale = 1e-3;
            for (int i = 0; i < model.getNumU(); ++i) {
                const Difference d = differentiate(model, q, w, i, 1e-6);
                if (!d.sameTopology) continue;  // a wrap or point switching inside the step
                error = std::max(error, std::abs(J(w, i) - d.length));
                scale = std::max(scale, std::abs(d.length));
            }
            EXPECT_LE(error / scale, 1e-6) << wire.name << " trial " << trial;
        }
    }
    for (int w = 0; w < model.getNumWires(); ++w) {
        if (!model.getWire(w).wraps.empty()) {
            EXPECT_GT(wrappedPoses[static_cast<std::size_t>(w)], 0) << model.getWire(w).name;
        }
    }
    EXPECT_GT(straightPoses[static_cast<std::size_t>(model.findWireIndex("over_cylinder"))], 0);  // on and off
    EXPECT_GT(tangentAcrossQuadrant, 0);
    EXPECT_GT(conditionalOn, 0);
    EXPECT_GT(conditionalOff, 0);
}

// OpenSim's ellipsoid path lies in a plane its heuristics turn with the ends, so the envelope derivative
// (tangent points held on the ellipsoid's link, which OpenSim's moment arms use) is not dL/du; sinew's J,
// differentiated through the whole path, is. Measured here too: how far the envelope is from dL/du, which
// is how far the test above would miss without the whole-path derivative.
TEST(WirePathFeatures, EllipsoidJacobianIsTheLengthDerivativeNotTheEnvelope) {
    const Model model = test::loadWrapArm();
    const int w = model.findWireIndex("over_ellipsoid"), upper = model.findLinkIndex("upper");
    std::mt19937 rng(24);
    Data data(model), moved(model);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    int wrapped = 0;
    double worstEnvelope = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const Eigen::VectorXd q = test::randomWrapArmPose(model, rng);
        calcPositionKinematics(model, data, q);
        calcWirePaths(model, data);
        calcWireJacobian(model, data, J);
        if (data.wirePathSize[static_cast<std::size_t>(w)] != 4) continue;
        ++wrapped;
        // Path: origin (base), r1, r2 (upper), insertion (upper); hold r1, r2 in upper's frame.
        const Data::WirePathPoint* path = data.wirePath.data() + data.wirePathStart[static_cast<std::size_t>(w)];
        const Eigen::Vector3d r1_B = data.R_GB[upper].transpose() * (path[1].p_G - data.p_GB[upper]);
        const Eigen::Vector3d r2_B = data.R_GB[upper].transpose() * (path[2].p_G - data.p_GB[upper]);
        auto frozenLength = [&](const Eigen::VectorXd& qq) {
            calcPositionKinematics(model, moved, qq);
            calcWirePaths(model, moved);
            const Eigen::Vector3d r1 = moved.p_GB[upper] + moved.R_GB[upper] * r1_B;
            const Eigen::Vector3d r2 = moved.p_GB[upper] + moved.R_GB[upper] * r2_B;
            const std::size_t first = static_cast<std::size_t>(model.getWire(w).firstPoint);
            return (r1 - moved.p_GP[first]).norm() + path[2].arcLength + (moved.p_GP[first + 1] - r2).norm();
        };
        for (int i = 0; i < model.getNumU(); ++i) {
            const Eigen::VectorXd e = Eigen::VectorXd::Unit(model.getNumU(), i);
            const double envelope =
                (frozenLength(integrateCoordinates(model, q, e, 1e-6)) - frozenLength(integrateCoordinates(model, q, e, -1e-6))) / 2e-6;
            const Difference d = differentiate(model, q, w, i, 1e-6);
            if (!d.sameTopology) continue;
            EXPECT_NEAR(J(w, i), d.length, 1e-6 * std::max(1.0, std::abs(d.length))) << trial;
            worstEnvelope = std::max(worstEnvelope, std::abs(envelope - d.length));
        }
    }
    EXPECT_GT(wrapped, 5);
    std::cout << "over_ellipsoid: the envelope derivative alone differs from dL/du by up to " << worstEnvelope << " m\n";
    EXPECT_GT(worstEnvelope, 1e-4);
}

TEST(WirePathFeatures, JacobianPredictsSpeedsAndGivesTheGeneralizedForces) {
    const Model model = test::loadWrapArm();
    std::mt19937 rng(22);
    std::normal_distribution<double> normal;
    Data data(model);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    Eigen::SparseMatrix<double> Jt = makeWireJacobianTransposePattern(model);
    Eigen::VectorXd tau(model.getNumU()), tensions(model.getNumWires());
    for (int trial = 0; trial < 30; ++trial) {
        Eigen::VectorXd u(model.getNumU());
        for (int i = 0; i < u.size(); ++i) u[i] = normal(rng);
        for (int w = 0; w < tensions.size(); ++w) tensions[w] = 100 * std::abs(normal(rng));
        calcPositionKinematics(model, data, test::randomWrapArmPose(model, rng));
        calcVelocityKinematics(model, data, u);
        calcWirePaths(model, data);
        calcWireSpeeds(model, data);
        calcWireJacobian(model, data, J);
        EXPECT_LE((J * u - data.wireSpeed).lpNorm<Eigen::Infinity>(), 1e-14) << trial;
        // The sparse J^T's pattern holds the moving points' coordinates and the ellipsoid wires' gradients.
        calcWireJacobianTranspose(model, data, Jt);
        EXPECT_EQ((Eigen::MatrixXd(Jt.transpose()) - J).cwiseAbs().maxCoeff(), 0.0) << trial;
        calcWireGeneralizedForces(model, data, tensions, tau);
        EXPECT_LE((tau + J.transpose() * tensions).lpNorm<Eigen::Infinity>(), 1e-12 * tensions.sum()) << trial;
    }
}

TEST(WirePathFeatures, EvaluationAllocatesNothing) {
    if (!test::isCountingAllocations()) GTEST_SKIP() << "allocations are not counted under AddressSanitizer";
    const Model model = test::loadWrapArm();
    std::mt19937 rng(23);
    const Eigen::VectorXd q = test::randomWrapArmPose(model, rng), u = Eigen::VectorXd::Ones(model.getNumU());
    Data data(model);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    Eigen::SparseMatrix<double> Jt = makeWireJacobianTransposePattern(model);
    Eigen::VectorXd tau(model.getNumU()), tensions = Eigen::VectorXd::Ones(model.getNumWires());
    const long long before = test::getAllocationCount();
    calcPositionKinematics(model, data, q);
    calcVelocityKinematics(model, data, u);
    calcWirePaths(model, data);
    calcWireSpeeds(model, data);
    calcWireJacobian(model, data, J);
    calcWireJacobianTranspose(model, data, Jt);
    calcWireGeneralizedForces(model, data, tensions, tau);
    EXPECT_EQ(test::getAllocationCount() - before, 0);
}

}  // namespace
}  // namespace sinew

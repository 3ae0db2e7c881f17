// Force elements against what defines them independently of their code: the generalized forces of the
// springs, bushing, limit and contact at rest are minus the gradient of their energy (central differences
// of calcForceElementPotentialEnergy along every speed), OpenSim's CoordinateLimitForce written out by hand,
// and the model file keeps every element through a write and a read.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sinew/core/data.hpp"
#include "sinew/core/force_elements.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/io/model_file.hpp"
#include "support/force_element_model.hpp"

namespace sinew {
namespace {

// The generalized forces of every element at (q, u): link forces through the tree, plus the limits'.
Eigen::VectorXd calcElementForces(const Model& model, Data& data, const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
    calcPositionKinematics(model, data, q);
    calcVelocityKinematics(model, data, u);
    std::vector<SpatialVector> linkForces(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    Eigen::VectorXd tau = Eigen::VectorXd::Zero(model.getNumU());
    addForceElementForces(model, data, linkForces, tau);
    data.scratchF_G = linkForces;
    Eigen::VectorXd fromLinks(model.getNumU());
    calcGeneralizedForcesFromLinkForces(model, data, fromLinks);
    return tau + fromLinks;
}

double calcEnergy(const Model& model, Data& data, const Eigen::VectorXd& q) {
    calcPositionKinematics(model, data, q);
    return calcForceElementPotentialEnergy(model, data);
}

TEST(ForceElements, ForcesAtRestAreMinusTheEnergyGradient) {
    const Model model = test::makeForceElementModel();
    Data data(model);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(-0.03, 0.03);
    int touching = 0;
    for (int trial = 0; trial < 20; ++trial) {
        Eigen::VectorXd q = test::placeHeelInFloor(model, 0.01 + 0.0005 * trial);
        // Bend the knee past its limit on some trials, and turn the block a little.
        for (int i = 0; i < model.getNumU(); ++i) q = integrateCoordinates(model, q, Eigen::VectorXd::Unit(model.getNumU(), i) * angle(rng), 0.1);
        const Eigen::VectorXd tau = calcElementForces(model, data, q, Eigen::VectorXd::Zero(model.getNumU()));
        touching += calcEnergy(model, data, q) > 0;
        Eigen::VectorXd gradient(model.getNumU());
        for (int i = 0; i < model.getNumU(); ++i) {
            const double h = 1e-6;
            const Eigen::VectorXd e = Eigen::VectorXd::Unit(model.getNumU(), i);
            gradient[i] = (calcEnergy(model, data, integrateCoordinates(model, q, e, h)) -
                           calcEnergy(model, data, integrateCoordinates(model, q, e, -h))) / (2 * h);
        }
        const double scale = std::max(1.0, tau.lpNorm<Eigen::Infinity>());
        EXPECT_LE((tau + gradient).lpNorm<Eigen::Infinity>() / scale, 1e-6)
            << "trial " << trial << "\ntau " << tau.transpose() << "\n-dV/dq " << -gradient.transpose();
    }
    EXPECT_GT(touching, 10);  // the contact took part
}

// OpenSim's CoordinateLimitForce::calcLimitForce with its quintic step, by hand.
TEST(ForceElements, CoordinateLimitIsOpenSimsFormula) {
    CoordinateLimitForce limit;
    limit.upperStiffness = 30, limit.upperLimit = 0.5, limit.lowerStiffness = 10, limit.lowerLimit = -1;
    limit.damping = 2, limit.transition = 0.1;
    const auto smoothStep = [](double t) { t = std::clamp(t, 0.0, 1.0); return t * t * t * (10 - 15 * t + 6 * t * t); };
    for (double q : {-1.3, -1.05, -0.97, 0.0, 0.52, 0.58, 0.7}) {
        for (double qdot : {-0.4, 0.0, 0.9}) {
            const double kUp = 30 * smoothStep((q - 0.5) / 0.1), kLow = 10 * (1 - smoothStep((q + 1.1) / 0.1));
            const double expected = -kUp * (q - 0.5) + kLow * (-1 - q) - 2 * (kUp / 30 + kLow / 10) * qdot;
            EXPECT_NEAR(calcCoordinateLimitForce(limit, q, qdot), expected, 1e-12) << q << " " << qdot;
        }
        const double h = 1e-6;
        const double slope = (calcCoordinateLimitEnergy(limit, q + h) - calcCoordinateLimitEnergy(limit, q - h)) / (2 * h);
        EXPECT_NEAR(-slope, calcCoordinateLimitForce(limit, q, 0), 1e-6) << q;
    }
    // A limit without stiffness on one side adds no damping there (OpenSim divides 0 by 0).
    limit.lowerStiffness = 0;
    EXPECT_TRUE(std::isfinite(calcCoordinateLimitForce(limit, -1.2, 1.0)));
    EXPECT_EQ(calcCoordinateLimitForce(limit, -1.2, 1.0), 0);
}

TEST(ForceElements, BodyFixedXYZAnglesInvertTheRotation) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> angle(-1.4, 1.4);
    for (int i = 0; i < 100; ++i) {
        const Eigen::Vector3d a(angle(rng), angle(rng), angle(rng));
        EXPECT_LE((calcBodyFixedXYZ(calcRotationFromBodyFixedXYZ(a)) - a).norm(), 1e-12) << a.transpose();
    }
}

TEST(ForceElements, TheModelFileKeepsEveryElement) {
    const Model model = test::makeForceElementModel();
    const std::string text = writeModelText(model);
    const Model again = readModelText(text, "written.yaml");
    EXPECT_EQ(writeModelText(again), text);
    const ForceElements& e = again.getForceElements();
    ASSERT_EQ(e.coordinateLimits.size(), 1u);
    ASSERT_EQ(e.springs.size(), 1u);
    ASSERT_EQ(e.bushings.size(), 1u);
    ASSERT_EQ(e.huntCrossley.size(), 1u);
    ASSERT_EQ(e.contactGeometry.size(), 2u);
    EXPECT_EQ(e.huntCrossley[0].surfaces.size(), 2u);
    Data a(model), b(again);
    const Eigen::VectorXd q = test::placeHeelInFloor(model, 0.003);
    EXPECT_DOUBLE_EQ(calcEnergy(model, a, q), calcEnergy(again, b, q));
}

TEST(ForceElements, BadElementsAreRefusedAtTheirLine) {
    const std::string base = test::kForceElementModelText;
    const auto expectError = [&](const std::string& from, const std::string& to, const std::string& text) {
        std::string broken = base;
        const std::size_t at = broken.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        broken.replace(at, from.size(), to);
        try {
            readModelText(broken, "bad.yaml");
            ADD_FAILURE() << "no error; expected one mentioning '" << text << "'";
        } catch (const std::exception& e) {
            EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("bad.yaml:"), std::string::npos) << e.what();
        }
    };
    expectError("coordinate: pin2", "coordinate: elbow", "unknown coordinate 'elbow'");
    expectError("transition: 0.09", "transition: 0", "transition");
    expectError("link_b: foot, point_b", "link_b: hand, point_b", "unknown link 'hand'");
    expectError("geometry: heel, stiffness: 2e7", "geometry: toe, stiffness: 2e7", "unknown contact geometry 'toe'");
    expectError("stiffness: 2e7", "stiffness: 0", "stiffness");
    expectError("shape: sphere", "shape: box", "unknown shape 'box'");
    expectError("type: bushing", "type: magnet", "unknown force element type 'magnet'");
    expectError("rotational_stiffness: [10, 12, 14]", "rotational_stiffness: [10, -12, 14]", "rotational stiffness");
}

}  // namespace
}  // namespace sinew

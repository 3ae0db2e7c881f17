// The speeds of a motion known by its coordinates' rates (coordinate_rates.hpp), checked against the
// engine's own kinematics: each link's angular and linear velocity from u must be the finite-difference
// rate of its pose along q(t).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "sinew/core/coordinate_rates.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "support/random_model.hpp"

namespace sinew {
namespace {

// q(t) = a + b t + c t² per coordinate: quaternions off unit length on purpose (rates.hpp takes q/|q|).
struct PolynomialMotion {
    Eigen::VectorXd a, b, c;
    Eigen::VectorXd q(double t) const { return a + t * b + t * t * c; }
    Eigen::VectorXd qdot(double t) const { return b + 2 * t * c; }
    Eigen::VectorXd qddot() const { return 2 * c; }
};

PolynomialMotion makeMotion(const Model& model, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(-1, 1);
    PolynomialMotion motion;
    motion.a = generateRandomCoordinates(model, rng) * 1.1;
    motion.b = Eigen::VectorXd::NullaryExpr(model.getNumQ(), [&] { return uniform(rng); });
    motion.c = Eigen::VectorXd::NullaryExpr(model.getNumQ(), [&] { return uniform(rng); });
    return motion;
}

Model makeModel(JointType root) {
    RandomModelOptions options;
    options.numLinks = 6;
    options.rootJoint = root;
    options.pinFraction = 0.3;
    options.numWires = 0;
    options.seed = 7;
    return generateRandomModel(options);
}

// Angular velocity in ground from R(t ± h): log(R(t+h) R(t-h)ᵀ) / 2h, exact to O(h²).
Eigen::Vector3d rateOfRotation(const Eigen::Matrix3d& before, const Eigen::Matrix3d& after, double h) {
    const Eigen::AngleAxisd turn(after * before.transpose());
    return turn.axis() * turn.angle() / (2 * h);
}

class CoordinateRates : public ::testing::TestWithParam<JointType> {};

TEST_P(CoordinateRates, GiveTheLinkVelocitiesOfTheCoordinatesMotion) {
    const Model model = makeModel(GetParam());
    ASSERT_TRUE(hasQuaternionJoints(model));
    const PolynomialMotion motion = makeMotion(model, 11);
    const double t = 0.3, h = 1e-5;
    Eigen::VectorXd u, udot;
    calcSpeedsFromCoordinateRates(model, motion.q(t), motion.qdot(t), motion.qddot(), u, udot);
    Data data(model), before(model), after(model);
    calcPositionKinematics(model, data, motion.q(t));
    calcVelocityKinematics(model, data, u);
    calcPositionKinematics(model, before, motion.q(t - h));
    calcPositionKinematics(model, after, motion.q(t + h));
    for (int b = 0; b < model.getNumLinks(); ++b) {
        const std::size_t i = static_cast<std::size_t>(b);
        const Eigen::Vector3d w = rateOfRotation(before.R_GB[i], after.R_GB[i], h);
        const Eigen::Vector3d v = (after.p_GB[i] - before.p_GB[i]) / (2 * h);
        EXPECT_LT((data.w_GB[i] - w).norm(), 1e-7 * (1 + w.norm())) << model.getJoint(b).name;
        EXPECT_LT((data.v_GB[i] - v).norm(), 1e-7 * (1 + v.norm())) << model.getJoint(b).name;
    }
}

TEST_P(CoordinateRates, GiveTheRatesOfTheSpeedsTheyGive) {
    const Model model = makeModel(GetParam());
    const PolynomialMotion motion = makeMotion(model, 12);
    const double t = -0.2, h = 1e-4;
    Eigen::VectorXd u, udot, uBefore, uAfter, unused;
    calcSpeedsFromCoordinateRates(model, motion.q(t), motion.qdot(t), motion.qddot(), u, udot);
    calcSpeedsFromCoordinateRates(model, motion.q(t - h), motion.qdot(t - h), motion.qddot(), uBefore, unused);
    calcSpeedsFromCoordinateRates(model, motion.q(t + h), motion.qdot(t + h), motion.qddot(), uAfter, unused);
    const Eigen::VectorXd rate = (uAfter - uBefore) / (2 * h);
    EXPECT_LT((udot - rate).lpNorm<Eigen::Infinity>(), 1e-6 * (1 + rate.lpNorm<Eigen::Infinity>()));
}

INSTANTIATE_TEST_SUITE_P(RootJoints, CoordinateRates, ::testing::Values(JointType::Free, JointType::Ball),
                         [](const ::testing::TestParamInfo<JointType>& root) { return std::string(toString(root.param)); });

TEST(CoordinateRatesErrors, NameTheJointOfAZeroQuaternion) {
    const Model model = makeModel(JointType::Free);
    Eigen::VectorXd q = model.getDefaultQ(), u, udot;
    const Eigen::VectorXd rates = Eigen::VectorXd::Zero(model.getNumQ());
    q.head<4>().setZero();
    try {
        calcSpeedsFromCoordinateRates(model, q, rates, rates, u, udot);
        FAIL() << "a zero quaternion was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("joint '" + model.getJoint(0).name + "'"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sinew

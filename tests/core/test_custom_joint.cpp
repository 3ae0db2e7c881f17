// Custom joints (OpenSim's CustomJoint) in the core: the motion subspace and its bias against finite
// differences of the joint transform on unrestricted layouts, link accelerations of inverse dynamics
// against finite differences of link velocities, the wire Jacobian against finite differences, a pin as a
// custom joint, OpenSim's coordinate order and motion types, and the builder's errors.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "sinew/core/custom_joint.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/model_builder.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "support/error_assertions.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

Eigen::Vector3d unskew(const Eigen::Matrix3d& m) { return 0.5 * Eigen::Vector3d(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1)); }

CoordinateSpec named(const std::string& name) {
    CoordinateSpec coordinate;
    coordinate.name = name;
    return coordinate;
}

// A custom joint from ground to link "b", its axes and coordinates left to the caller.
JointSpec customJointOnGround(const std::string& name) {
    JointSpec joint;
    joint.name = name;
    joint.type = JointType::Custom;
    joint.parent = "ground";
    joint.child = "b";
    return joint;
}

LinkSpec makeLink(const std::string& name) {
    LinkSpec link;
    link.name = name;
    link.mass = 1.5;
    link.com_B = Eigen::Vector3d(0.05, -0.2, 0.02);
    link.inertia_Bcom = Eigen::Vector3d(0.02, 0.025, 0.03).asDiagonal();
    return link;
}

// A one-joint model whose custom joint has any layout: every axis driven by a random coordinate or a
// random non-zero constant, so also the layouts the random models leave out for Simbody's sake.
Model makeUnrestrictedCustomJoint(std::mt19937& rng) {
    std::uniform_real_distribution<double> r(-1, 1);
    JointSpec joint = customJointOnGround("j");
    joint.coordinates = {named("qa"), named("qb"), named("qc")};
    joint.transformAxes.resize(6);
    const char* names[] = {"qa", "qb", "qc"};
    for (int k = 0; k < 6; ++k) {
        TransformAxisSpec& axis = joint.transformAxes[static_cast<std::size_t>(k)];
        axis.axis = Eigen::Vector3d(r(rng), r(rng), r(rng));
        if (k < 3) axis.coordinate = names[std::uniform_int_distribution<int>(0, 2)(rng)];
        else if (r(rng) > -0.3) axis.coordinate = names[std::uniform_int_distribution<int>(0, 2)(rng)];
        axis.function = r(rng) > 0 ? Function::polynomial({r(rng), r(rng), r(rng), r(rng)})
                                   : Function::simmSpline({-3, -1, 0.5, 3}, {r(rng), r(rng), r(rng), r(rng)}).multipliedBy(2);
        if (axis.coordinate.empty()) axis.function = Function::constant(r(rng));
    }
    for (int c = 0; c < 3; ++c) joint.transformAxes[static_cast<std::size_t>(c + 3)].coordinate = names[c];  // all used
    ModelBuilder builder("unrestricted");
    builder.addLink(makeLink("b"));
    builder.addJoint(joint);
    return builder.build();
}

// Also Hdot as a matrix (Simbody's custom mobilizer applies it to any vector), on layouts where one
// coordinate drives several rotations through splines, as Rajagopal's knee does.
TEST(CustomJoint, MotionSubspaceAndBiasMatchFiniteDifferencesOfTheTransform) {
    std::mt19937 rng(21);
    for (int trial = 0; trial < 50; ++trial) {
        const Model model = makeUnrestrictedCustomJoint(rng);
        const Joint& joint = model.getJoint(0);
        const Eigen::VectorXd q = Eigen::VectorXd::Random(3) * 2, u = Eigen::VectorXd::Random(3) * 2;
        Eigen::Matrix3d R;
        Eigen::Vector3d p;
        JointMotion H = JointMotion::Zero(6, 3);
        calcCustomJointTransform(joint, q.data(), R, p, H);
        const double h = 1e-6;
        for (int c = 0; c < 3; ++c) {
            Eigen::Matrix3d Rp, Rm;
            Eigen::Vector3d pp, pm;
            JointMotion scratch = JointMotion::Zero(6, 3);
            const Eigen::VectorXd e = Eigen::VectorXd::Unit(3, c);
            calcCustomJointTransform(joint, Eigen::VectorXd(q + h * e).data(), Rp, pp, scratch);
            calcCustomJointTransform(joint, Eigen::VectorXd(q - h * e).data(), Rm, pm, scratch);
            const Eigen::Vector3d w = unskew((Rp - Rm) / (2 * h) * R.transpose());  // dR/dq R^T = [w]x, in F
            EXPECT_LT((w - H.col(c).head<3>()).norm(), 1e-8) << "trial " << trial << " coordinate " << c;
            EXPECT_LT(((pp - pm) / (2 * h) - H.col(c).tail<3>()).norm(), 1e-8) << "trial " << trial;
        }
        // Hdot u = d/dt (H(q + u t) u) at t = 0.
        JointMotion Hp = JointMotion::Zero(6, 3), Hm = JointMotion::Zero(6, 3);
        calcCustomJointTransform(joint, Eigen::VectorXd(q + h * u).data(), R, p, Hp);
        calcCustomJointTransform(joint, Eigen::VectorXd(q - h * u).data(), R, p, Hm);
        const JointMotion HDotExpected = (Hp - Hm) / (2 * h);
        JointMotion HDot;
        calcCustomJointHDot(joint, q.data(), u.data(), HDot);
        EXPECT_LT((HDot - HDotExpected).norm(), 1e-7 * (1 + HDotExpected.norm())) << "trial " << trial;
        const SpatialVector expected = HDotExpected * u;
        EXPECT_LT((calcCustomJointBias(joint, q.data(), u.data()) - expected).norm(), 1e-7 * (1 + expected.norm()))
            << "trial " << trial;
    }
}

// Link accelerations of inverse dynamics are the time derivatives of the link velocities along
// q(t) = q + u t + udot t^2 / 2 (q' = u for custom and pin joints).
TEST(CustomJoint, InverseDynamicsAccelerationsMatchFiniteDifferencesOfVelocities) {
    std::mt19937 rng(22);
    for (int seed = 0; seed < 10; ++seed) {
        RandomModelOptions o;
        o.seed = 500 + static_cast<unsigned>(seed);
        o.numLinks = 12;
        o.rootJoint = JointType::Custom;
        o.customJointFraction = 0.8;
        o.pinFraction = 1.0;  // the rest pins: q' = u everywhere
        o.numWires = 0;
        const Model model = generateRandomModel(o);
        const Eigen::VectorXd q = generateRandomCoordinates(model, rng), u = generateRandomSpeeds(model, rng, 2);
        const Eigen::VectorXd udot = generateRandomSpeeds(model, rng, 3);
        Data data(model), moved(model);
        Eigen::VectorXd tau(model.getNumU());
        calcInverseDynamics(model, data, q, u, udot, std::vector<SpatialVector>(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero()), tau);
        const double h = 1e-5;
        auto velocities = [&](double t) {
            calcPositionKinematics(model, moved, q + u * t + 0.5 * udot * t * t);
            calcVelocityKinematics(model, moved, u + udot * t);
            return std::make_pair(moved.w_GB, moved.v_GB);
        };
        const auto plus = velocities(h), minus = velocities(-h);
        for (std::size_t b = 0; b < static_cast<std::size_t>(model.getNumLinks()); ++b) {
            EXPECT_LT(((plus.first[b] - minus.first[b]) / (2 * h) - data.alpha_GB[b]).norm(), 1e-6) << test::describe(o) << " link " << b;
            EXPECT_LT(((plus.second[b] - minus.second[b]) / (2 * h) - data.a_GB[b]).norm(), 1e-6) << test::describe(o) << " link " << b;
        }
    }
}

TEST(CustomJoint, WireJacobianMatchesFiniteDifferences) {
    std::mt19937 rng(23);
    for (int seed = 0; seed < 8; ++seed) {
        RandomModelOptions o;
        o.seed = 600 + static_cast<unsigned>(seed);
        o.numLinks = 10;
        o.rootJoint = seed % 2 ? JointType::Custom : JointType::Free;
        o.customJointFraction = 0.7;
        o.numWires = 25;
        const Model model = generateRandomModel(o);
        const Eigen::VectorXd q = generateRandomCoordinates(model, rng);
        Data data(model);
        calcPositionKinematics(model, data, q);
        calcWirePaths(model, data);
        Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
        calcWireJacobian(model, data, J);
        const double h = 1e-6;
        for (int i = 0; i < model.getNumU(); ++i) {
            const Eigen::VectorXd e = Eigen::VectorXd::Unit(model.getNumU(), i);
            calcPositionKinematics(model, data, integrateCoordinates(model, q, e, h));
            calcWirePaths(model, data);
            const Eigen::VectorXd plus = data.wireLength;
            calcPositionKinematics(model, data, integrateCoordinates(model, q, e, -h));
            calcWirePaths(model, data);
            EXPECT_LT(((plus - data.wireLength) / (2 * h) - J.col(i)).lpNorm<Eigen::Infinity>(), 1e-7)
                << test::describe(o) << " speed " << i;
        }
    }
}

TEST(CustomJoint, OneLinearRotationIsAPin) {
    const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
    auto build = [&](bool custom) {
        ModelBuilder builder("pin");
        builder.addLink(makeLink("b"));
        JointSpec joint;
        joint.name = "hinge";
        joint.parent = "ground";
        joint.child = "b";
        joint.p_BM = Eigen::Vector3d(0.01, 0.2, 0);
        if (custom) {
            joint.type = JointType::Custom;
            joint.coordinates = {named("hinge")};
            joint.transformAxes = {{axis, "hinge", {}}, {Eigen::Vector3d::UnitY(), "", {}}, {Eigen::Vector3d::UnitZ(), "", {}},
                                   {Eigen::Vector3d::UnitX(), "", {}}, {Eigen::Vector3d::UnitY(), "", {}}, {Eigen::Vector3d::UnitZ(), "", {}}};
        } else {
            joint.type = JointType::Pin;
            joint.axis = axis;
        }
        builder.addJoint(joint);
        return builder.build();
    };
    const Model pin = build(false), custom = build(true);
    EXPECT_EQ(getCoordinateNames(custom), getCoordinateNames(pin));
    EXPECT_EQ(getSpeedNames(custom), getSpeedNames(pin));
    EXPECT_EQ(custom.getCoordinates()[0].motionType, MotionType::Rotational);
    Data a(pin), b(custom);
    Eigen::VectorXd q(1), u(1), udot(1), tauPin(1), tauCustom(1);
    q << 0.8;
    u << -1.3;
    udot << 2.1;
    const std::vector<SpatialVector> none(1, SpatialVector::Zero());
    calcInverseDynamics(pin, a, q, u, udot, none, tauPin);
    calcInverseDynamics(custom, b, q, u, udot, none, tauCustom);
    EXPECT_LT((a.R_GB[0] - b.R_GB[0]).norm(), 1e-15);
    EXPECT_LT((a.p_GB[0] - b.p_GB[0]).norm(), 1e-15);
    EXPECT_LT((a.w_GB[0] - b.w_GB[0]).norm(), 1e-15);
    EXPECT_NEAR(tauPin[0], tauCustom[0], 1e-13);
}

TEST(CustomJoint, CoordinatesInOpenSimsOrderWithTheirMotionTypes) {
    ModelBuilder builder("order");
    builder.addLink(makeLink("b"));
    JointSpec joint = customJointOnGround("knee");
    CoordinateSpec slide{"slide", 0.01, -0.1, 0.1, true, false, ""};
    CoordinateSpec flexion{"flexion", -0.5, -2, 0.2, false, true, ""};
    joint.coordinates = {slide, flexion};  // declared out of axis order
    joint.transformAxes.assign(6, TransformAxisSpec{});
    joint.transformAxes[0] = {Eigen::Vector3d::UnitZ(), "flexion", Function::linear(-1, 0)};
    joint.transformAxes[1] = {Eigen::Vector3d::UnitY(), "", {}};
    joint.transformAxes[2] = {Eigen::Vector3d::UnitX(), "", {}};
    joint.transformAxes[3] = {Eigen::Vector3d::UnitX(), "flexion", Function::simmSpline({-2, 0, 1}, {0, 0.01, 0.02})};
    joint.transformAxes[4] = {Eigen::Vector3d::UnitY(), "slide", Function::linear(0.5, 0)};
    joint.transformAxes[5] = {Eigen::Vector3d(0, 0, 2), "", Function::constant(0.03)};
    builder.addJoint(joint);
    const Model model = builder.build();
    ASSERT_EQ(model.getNumQ(), 2);
    EXPECT_EQ(getCoordinateNames(model), (std::vector<std::string>{"flexion", "slide"}));
    EXPECT_EQ(model.getCoordinates()[0].motionType, MotionType::Rotational);  // slope -1 on a rotation
    EXPECT_EQ(model.getCoordinates()[1].motionType, MotionType::Coupled);     // slope 0.5
    EXPECT_EQ(model.getDefaultQ(), Eigen::Vector2d(-0.5, 0.01));
    EXPECT_TRUE(model.getCoordinates()[0].locked);
    EXPECT_EQ(model.getCoordinates()[1].rangeMax, 0.1);
    EXPECT_EQ(model.getJoint(0).transformAxes[3].coordinate, 0);
    EXPECT_EQ(model.getJoint(0).transformAxes[4].coordinate, 1);
    EXPECT_EQ(model.getJoint(0).transformAxes[5].axis, Eigen::Vector3d::UnitZ());  // normalised
}

TEST(CustomJoint, BuilderRefusesBadJoints) {
    auto attempt = [](auto edit) {
        ModelBuilder builder("bad");
        builder.addLink(makeLink("b"));
        JointSpec joint = customJointOnGround("j");
        joint.where = "bad.yaml:7";
        joint.coordinates = {named("q")};
        joint.transformAxes = {{Eigen::Vector3d::UnitX(), "q", {}}, {Eigen::Vector3d::UnitY(), "", {}}, {Eigen::Vector3d::UnitZ(), "", {}},
                               {Eigen::Vector3d::UnitX(), "", {}}, {Eigen::Vector3d::UnitY(), "", {}}, {Eigen::Vector3d::UnitZ(), "", {}}};
        edit(joint);
        builder.addJoint(joint);
        builder.build();
    };
    const std::string at = "bad.yaml:7";
    EXPECT_TRUE(test::throwsErrorAt([&] { attempt([](JointSpec& j) { j.transformAxes.pop_back(); }); }, at, {"6 transform axes"}, "5 axes"));
    EXPECT_TRUE(test::throwsErrorAt([&] { attempt([](JointSpec& j) { j.transformAxes[1].axis = Eigen::Vector3d(2, 0, 1e-7); }); },
                                    at, {"rotation1", "rotation2", "collinear"}, "collinear"));
    EXPECT_TRUE(test::throwsErrorAt([&] { attempt([](JointSpec& j) { j.transformAxes[4].coordinate = "z"; }); }, at,
                                    {"translation2", "'z'", "does not declare"}, "undeclared"));
    EXPECT_TRUE(test::throwsErrorAt([&] { attempt([](JointSpec& j) { j.coordinates.push_back(named("idle")); }); }, at,
                                    {"'idle'", "drives none"}, "unused"));
    EXPECT_TRUE(test::throwsErrorAt([&] { attempt([](JointSpec& j) { j.coordinates.clear(); j.transformAxes[0].coordinate.clear(); }); },
                                    at, {"at least one coordinate"}, "none"));
    EXPECT_TRUE(test::throwsErrorAt([&] { attempt([](JointSpec& j) { j.transformAxes[3].axis = Eigen::Vector3d(NAN, 0, 0); }); },
                                    at, {"translation1", "finite, non-zero"}, "nan axis"));
    EXPECT_TRUE(test::throwsErrorAt([&] { attempt([](JointSpec& j) { j.R_PF = Eigen::Matrix3d::Identity() * 2; }); }, at,
                                    {"rotation matrix"}, "scaled"));
    EXPECT_TRUE(test::throwsErrorAt([&] { attempt([](JointSpec& j) { j.type = JointType::Ball; }); }, at,
                                    {"only custom joints take transform axes"}, "ball with axes"));
    EXPECT_TRUE(test::throwsErrorAt([&] { attempt([](JointSpec& j) { j.coordinates[0].name = "b_qw"; j.transformAxes[0].coordinate = "b_qw"; j.coordinates[0].rangeMin = 1; j.coordinates[0].rangeMax = 0; }); },
                                    at, {"range"}, "range"));
}


// MuJoCo's knees slide twice along one axis, each slide coupled to the knee angle: the translations add up.
// Two such slides left free would make the joint's inertia singular, so the builder asks for a coupler.
TEST(CustomJoint, CollinearTranslationsAddUpWhenACouplerDrivesOne) {
    auto build = [](bool coupled) {
        ModelBuilder builder("collinear");
        builder.addLink(makeLink("b"));
        JointSpec joint = customJointOnGround("knee");
        joint.where = "knee.xml:4";
        joint.coordinates = {named("angle"), named("slide_a"), named("slide_b")};
        const Eigen::Vector3d along = Eigen::Vector3d(1, 2, -0.5).normalized();
        joint.transformAxes = {{Eigen::Vector3d::UnitZ(), "angle", {}}, {Eigen::Vector3d::UnitX(), "", {}},
                               {Eigen::Vector3d::UnitY(), "", {}},      {along, "slide_a", {}},
                               {Eigen::Vector3d::UnitZ(), "", {}},      {-2 * along, "slide_b", {}}};
        builder.addJoint(joint);
        if (coupled)
            builder.addCoupler({"slide_b_of_angle", "slide_b", "angle", Function::linear(0.01, 0.002), 1, "knee.xml:9"});
        return builder.build();
    };
    EXPECT_TRUE(test::throwsErrorAt([&] { build(false); }, "knee.xml:4",
                                    {"translation1", "translation3", "collinear", "coupler"}, "free collinear slides"));
    const Model model = build(true);
    Data data(model);
    const Eigen::VectorXd q = Eigen::Vector3d(0.7, 0.03, -0.011);
    calcPositionKinematics(model, data, q);
    const Eigen::Vector3d along = Eigen::Vector3d(1, 2, -0.5).normalized();
    EXPECT_LE((data.p_GB[0] - (q[1] - q[2]) * along).norm(), 1e-15);  // the second axis points back, unit length
}

}  // namespace
}  // namespace sinew

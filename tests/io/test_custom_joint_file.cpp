// Custom joints in the model file: a gait2354-style knee read and checked against its transform computed
// here by hand, write-read round trips (hand-written and random models), and errors at their lines.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "sinew/core/kinematics.hpp"
#include "sinew/io/model_file.hpp"
#include "support/error_assertions.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

// OpenSim gait2354's right knee (subject01_simbody.osim): flexion about z, the tibia sliding along x and y
// by scaled SimmSplines of the flexion; the femur's joint frame turned by OpenSim-style x-y-z angles.
const std::string kKnee = R"(sinew_model: 1
name: knee
links:
  - {name: femur, mass: 7.8, com: [0, -0.17, 0], inertia: [0.11, 0.03, 0.12, 0, 0, 0]}
  - {name: tibia, mass: 3.1, com: [0, -0.18, 0], inertia: [0.04, 0.004, 0.04, 0, 0, 0]}
joints:
  - {name: hip, type: weld, parent: ground, child: femur, parent_orientation: [0.1, -0.2, 0.3]}
  - name: knee_r
    type: custom
    parent: femur
    child: tibia
    parent_point: [0, -0.05, 0]
    parent_orientation: [0.05, 0.1, -0.02]
    coordinates:
      - {name: knee_angle_r, default: -0.3, range: [-2.0943951, 0.17453293], clamped: true}
    transform:
      rotation1: {axis: [0, 0, 1], coordinate: knee_angle_r, function: {type: linear, coefficients: [1, 0]}}
      rotation2: {axis: [0, 1, 0]}
      rotation3: {axis: [1, 0, 0]}
      translation1:
        axis: [1, 0, 0]
        coordinate: knee_angle_r
        function: {type: simm_spline, scale: 1.14724,
                   x: [-2.0944, -1.74533, -1.39626, -1.0472, -0.698132, -0.349066, -0.174533, 0.197344, 0.337395, 0.490178, 1.52146, 2.0944],
                   y: [-0.0032, 0.00179, 0.00411, 0.0041, 0.00212, -0.001, -0.0031, -0.005227, -0.005435, -0.005574, -0.005435, -0.00525]}
      translation2:
        axis: [0, 1, 0]
        coordinate: knee_angle_r
        function: {type: simm_spline, scale: 1.14724,
                   x: [-2.0944, -1.22173, -0.523599, -0.349066, -0.174533, 0.159149, 2.0944],
                   y: [-0.4226, -0.4082, -0.399, -0.3976, -0.3966, -0.395264, -0.396]}
      translation3: {axis: [0, 0, 1], function: {type: constant, value: 0, scale: 1.14724}}
)";

Eigen::Matrix3d bodyFixedXYZ(double x, double y, double z) {
    return (Eigen::AngleAxisd(x, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(y, Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(z, Eigen::Vector3d::UnitZ())).toRotationMatrix();
}

TEST(CustomJointFile, KneeReadsAsItsTransform) {
    const Model model = readModelText(kKnee, "knee.yaml");
    ASSERT_EQ(model.getNumQ(), 1);
    const Coordinate& knee = model.getCoordinates()[0];
    EXPECT_EQ(knee.name, "knee_angle_r");
    EXPECT_EQ(knee.defaultValue, -0.3);
    EXPECT_TRUE(knee.clamped);
    EXPECT_EQ(knee.rangeMin, -2.0943951);
    EXPECT_EQ(knee.motionType, MotionType::Rotational);
    Data data(model);
    const double q = -1.2;
    calcPositionKinematics(model, data, Eigen::VectorXd::Constant(1, q));
    // The femur (welded), then the tibia: F turned on the femur, R_FM = Rz(q), p_FM = scaled splines in F.
    const Eigen::Matrix3d R_GF = bodyFixedXYZ(0.1, -0.2, 0.3) * bodyFixedXYZ(0.05, 0.1, -0.02);
    const Function tx = Function::simmSpline({-2.0944, -1.74533, -1.39626, -1.0472, -0.698132, -0.349066, -0.174533, 0.197344,
                                              0.337395, 0.490178, 1.52146, 2.0944},
                                             {-0.0032, 0.00179, 0.00411, 0.0041, 0.00212, -0.001, -0.0031, -0.005227, -0.005435,
                                              -0.005574, -0.005435, -0.00525}).multipliedBy(1.14724);
    const Function ty = Function::simmSpline({-2.0944, -1.22173, -0.523599, -0.349066, -0.174533, 0.159149, 2.0944},
                                             {-0.4226, -0.4082, -0.399, -0.3976, -0.3966, -0.395264, -0.396}).multipliedBy(1.14724);
    const Eigen::Vector3d p_FM(tx.calcValue(q), ty.calcValue(q), 0);
    const Eigen::Vector3d p_GF = bodyFixedXYZ(0.1, -0.2, 0.3) * Eigen::Vector3d(0, -0.05, 0);
    const int tibia = model.findLinkIndex("tibia");
    EXPECT_LT((data.R_GB[static_cast<std::size_t>(tibia)] - R_GF * Eigen::AngleAxisd(q, Eigen::Vector3d::UnitZ()).toRotationMatrix()).norm(), 1e-15);
    EXPECT_LT((data.p_GB[static_cast<std::size_t>(tibia)] - (p_GF + R_GF * p_FM)).norm(), 1e-15);
}

TEST(CustomJointFile, WriteReadRoundTripsExactly) {
    const Model knee = readModelText(kKnee, "knee.yaml");
    RandomModelOptions o;
    o.numLinks = 15;
    o.rootJoint = JointType::Custom;
    o.customJointFraction = 0.6;
    o.numWires = 10;
    o.seed = 77;
    for (const Model& model : {knee, generateRandomModel(o)}) {
        const std::string text = writeModelText(model);
        const Model back = readModelText(text, "written.yaml");
        EXPECT_EQ(writeModelText(back), text);
        ASSERT_EQ(back.getNumQ(), model.getNumQ());
        EXPECT_EQ(back.getDefaultQ(), model.getDefaultQ());
        EXPECT_EQ(getCoordinateNames(back), getCoordinateNames(model));
        std::mt19937 rng(3);
        const Eigen::VectorXd q = generateRandomCoordinates(model, rng);
        Data a(model), b(back);
        calcPositionKinematics(model, a, q);
        calcPositionKinematics(back, b, q);
        for (std::size_t i = 0; i < a.R_GB.size(); ++i) {
            EXPECT_EQ(a.R_GB[i], b.R_GB[i]) << model.getName() << " link " << i;
            EXPECT_EQ(a.p_GB[i], b.p_GB[i]) << model.getName() << " link " << i;
        }
    }
}

::testing::AssertionResult rejects(const std::string& from, const std::string& to, int line,
                                   const std::vector<std::string>& words) {
    std::string text = kKnee;
    const std::size_t at = text.find(from);
    if (at == std::string::npos) return ::testing::AssertionFailure() << "'" << from << "' is not in the knee";
    text.replace(at, from.size(), to);
    return test::throwsErrorAt<ModelError>([&] { readModelText(text, "bad.yaml"); }, "bad.yaml:" + std::to_string(line) + ": ",
                                           words, text);
}

TEST(CustomJointFile, ErrorsNameTheirLine) {
    EXPECT_TRUE(rejects("type: linear, coefficients: [1, 0]", "type: cosine", 17, {"rotation1", "unknown function type 'cosine'"}));
    EXPECT_TRUE(rejects("coefficients: [1, 0]", "coefficients: [1]", 17, {"slope, intercept"}));
    EXPECT_TRUE(rejects("x: [-2.0944, -1.22173", "x: [-1.22173, -2.0944", 29, {"translation2", "strictly increasing"}));
    EXPECT_TRUE(rejects("rotation2: {axis: [0, 1, 0]}", "rotation2: {axis: [0, 0, 3]}", 8, {"knee_r", "collinear"}));
    EXPECT_TRUE(rejects("rotation3: {axis: [1, 0, 0]}", "rotation4: {axis: [1, 0, 0]}", 19, {"unknown field 'rotation4'"}));
    EXPECT_TRUE(rejects("clamped: true", "clamped: maybe", 15, {"'clamped' must be true or false"}));
    EXPECT_TRUE(rejects("parent_orientation: [0.05, 0.1, -0.02]", "parent_orientation: [1, 2]", 13, {"parent_orientation"}));
    EXPECT_TRUE(rejects("type: weld, parent: ground", "type: ball, parent: ground", 7, {"only custom and weld joints"}));
}

}  // namespace
}  // namespace sinew

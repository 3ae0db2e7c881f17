// OpenSim's CoordinateCouplerConstraint through the importer and sinew's model file: a knee whose two
// translations are coupled to its angle (a SimmSpline with a scale factor, and a LinearFunction), with
// muscles crossing it. Checked: the couplers are imported (not listed as left out) and reproduce their
// knots; the model file round trip is identical; moment arms equal minus the derivative of the length
// along the constraint by central differences; bad input is refused at its file:line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/moment_arms.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/osim_model.hpp"
#include "sinew/io/osim_model_converter.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

// knee_tx = 2 * spline(knee_angle) and knee_ty = 0.01 knee_angle + 0.002, both driving the shank's
// translations; vasti crosses the knee only, hamstring the hip and the knee.
const std::string kKneeModel = R"(<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="40000">
  <Model name="coupled_knee">
    <Ground name="ground"/>
    <gravity>0 -9.80665 0</gravity>
    <BodySet name="bodyset"><objects>
      <Body name="pelvis"><mass>10</mass><inertia>0.1 0.1 0.1 0 0 0</inertia></Body>
      <Body name="thigh"><mass>8</mass><mass_center>0 -0.17 0</mass_center><inertia>0.11 0.03 0.11 0 0 0</inertia></Body>
      <Body name="shank"><mass>3.5</mass><mass_center>0 -0.18 0</mass_center><inertia>0.05 0.005 0.05 0 0 0</inertia></Body>
    </objects></BodySet>
    <JointSet name="jointset"><objects>
      <WeldJoint name="ground_pelvis"><socket_parent_frame>pelvis_site</socket_parent_frame><socket_child_frame>/bodyset/pelvis</socket_child_frame>
        <frames><PhysicalOffsetFrame name="pelvis_site"><socket_parent>/ground</socket_parent><translation>0 1 0</translation></PhysicalOffsetFrame></frames>
      </WeldJoint>
      <PinJoint name="hip"><socket_parent_frame>/bodyset/pelvis</socket_parent_frame><socket_child_frame>thigh_offset</socket_child_frame>
        <coordinates><Coordinate name="hip_flexion"><default_value>0.3</default_value><range>-1 2</range></Coordinate></coordinates>
        <frames>
          <PhysicalOffsetFrame name="thigh_offset"><socket_parent>/bodyset/thigh</socket_parent></PhysicalOffsetFrame>
        </frames>
      </PinJoint>
      <CustomJoint name="knee"><socket_parent_frame>thigh_offset</socket_parent_frame><socket_child_frame>shank_offset</socket_child_frame>
        <coordinates>
          <Coordinate name="knee_angle"><default_value>-0.5</default_value><range>-2.0944 0.1745</range></Coordinate>
          <Coordinate name="knee_tx"><range>-0.1 0.1</range></Coordinate>
          <Coordinate name="knee_ty"><range>-0.1 0.1</range></Coordinate>
        </coordinates>
        <SpatialTransform>
          <TransformAxis name="rotation1"><coordinates>knee_angle</coordinates><axis>0 0 1</axis><LinearFunction name="function"><coefficients>1 0</coefficients></LinearFunction></TransformAxis>
          <TransformAxis name="rotation2"><axis>1 0 0</axis></TransformAxis>
          <TransformAxis name="rotation3"><axis>0 1 0</axis></TransformAxis>
          <TransformAxis name="translation1"><coordinates>knee_tx</coordinates><axis>1 0 0</axis><LinearFunction name="function"><coefficients>1 0</coefficients></LinearFunction></TransformAxis>
          <TransformAxis name="translation2"><coordinates>knee_ty</coordinates><axis>0 1 0</axis><LinearFunction name="function"><coefficients>1 0</coefficients></LinearFunction></TransformAxis>
          <TransformAxis name="translation3"><axis>0 0 1</axis></TransformAxis>
        </SpatialTransform>
        <frames>
          <PhysicalOffsetFrame name="thigh_offset"><socket_parent>/bodyset/thigh</socket_parent><translation>0 -0.4 0</translation></PhysicalOffsetFrame>
          <PhysicalOffsetFrame name="shank_offset"><socket_parent>/bodyset/shank</socket_parent></PhysicalOffsetFrame>
        </frames>
      </CustomJoint>
    </objects></JointSet>
    <ConstraintSet name="constraintset"><objects>
      <CoordinateCouplerConstraint name="knee_tx_coupler"><isEnforced>true</isEnforced>
        <coupled_coordinates_function><SimmSpline name="f"><x>-2.0944 -1.74533 -1.39626 -1.0472 -0.698132 -0.349066 -0.174533 0.197344 0.337395</x><y>-0.0032 0.00179 0.00411 0.0041 0.00212 -0.001 -0.0031 -0.005227 -0.005435</y></SimmSpline></coupled_coordinates_function>
        <independent_coordinate_names>knee_angle</independent_coordinate_names>
        <dependent_coordinate_name>knee_tx</dependent_coordinate_name>
        <scale_factor>2</scale_factor>
      </CoordinateCouplerConstraint>
      <CoordinateCouplerConstraint name="knee_ty_coupler">
        <coupled_coordinates_function><LinearFunction><coefficients>0.01 0.002</coefficients></LinearFunction></coupled_coordinates_function>
        <independent_coordinate_names>knee_angle</independent_coordinate_names>
        <dependent_coordinate_name>knee_ty</dependent_coordinate_name>
      </CoordinateCouplerConstraint>
    </objects></ConstraintSet>
    <ForceSet name="forceset"><objects>
      <Thelen2003Muscle name="vasti">
        <GeometryPath name="geometrypath"><PathPointSet><objects>
          <PathPoint name="v1"><socket_parent_frame>/bodyset/thigh</socket_parent_frame><location>0.03 -0.2 0</location></PathPoint>
          <PathPoint name="v2"><socket_parent_frame>/bodyset/thigh</socket_parent_frame><location>0.045 -0.38 0</location></PathPoint>
          <PathPoint name="v3"><socket_parent_frame>/bodyset/shank</socket_parent_frame><location>0.05 -0.06 0.01</location></PathPoint>
        </objects></PathPointSet></GeometryPath>
        <max_isometric_force>5000</max_isometric_force><optimal_fiber_length>0.09</optimal_fiber_length><tendon_slack_length>0.2</tendon_slack_length>
      </Thelen2003Muscle>
      <Thelen2003Muscle name="hamstring">
        <GeometryPath name="geometrypath"><PathPointSet><objects>
          <PathPoint name="h1"><socket_parent_frame>/bodyset/pelvis</socket_parent_frame><location>-0.06 -0.02 0.02</location></PathPoint>
          <PathPoint name="h2"><socket_parent_frame>/bodyset/shank</socket_parent_frame><location>-0.03 -0.05 0</location></PathPoint>
        </objects></PathPointSet></GeometryPath>
        <max_isometric_force>2000</max_isometric_force><optimal_fiber_length>0.1</optimal_fiber_length><tendon_slack_length>0.3</tendon_slack_length>
      </Thelen2003Muscle>
    </objects></ForceSet>
  </Model>
</OpenSimDocument>
)";

// A file private to the running test, since ctest may run this file's tests in parallel.
std::string writeTestFile(const std::string& text, const std::string& extension = ".osim") {
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sinew_osim_coupler";
    std::filesystem::create_directories(dir);
    const std::string path =
        (dir / (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + extension)).string();
    std::ofstream(path) << text;
    return path;
}

int lineOf(const std::string& text, const std::string& needle) {
    const std::size_t at = text.find(needle);
    EXPECT_NE(at, std::string::npos) << needle;
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

OsimConversion importText(const std::string& text) { return convertOsimModel(readOsimModel(writeTestFile(text))); }

// Wire lengths at q put on the constraint manifold first.
Eigen::VectorXd calcLengthsOnManifold(const Model& model, Data& data, Eigen::VectorXd q) {
    applyCoordinateCouplers(model, q);
    calcPositionKinematics(model, data, q);
    calcWirePaths(model, data);
    return data.wireLength;
}

TEST(OsimCoupler, ImportsCouplersInsteadOfListingThem) {
    const OsimConversion conversion = importText(kKneeModel);
    const Model& model = conversion.model;
    for (const std::string& line : conversion.notImported)
        EXPECT_EQ(line.find("CoordinateCoupler"), std::string::npos) << line;
    ASSERT_EQ(model.getNumCouplers(), 2);
    const CoordinateCoupler& tx = model.getCouplers()[0];
    const CoordinateCoupler& ty = model.getCouplers()[1];
    EXPECT_EQ(tx.name, "knee_tx_coupler");
    EXPECT_EQ(tx.dependentQ, model.findCoordinateIndex("knee_tx"));
    EXPECT_EQ(tx.independentQ, model.findCoordinateIndex("knee_angle"));
    EXPECT_EQ(tx.scaleFactor, 2);
    EXPECT_EQ(ty.dependentQ, model.findCoordinateIndex("knee_ty"));
    EXPECT_EQ(ty.scaleFactor, 1);  // OpenSim's default when <scale_factor> is absent
    // The spline goes through OpenSim's knots; the linear function is the file's.
    const std::vector<double> x{-2.0944, -1.74533, -1.39626, -1.0472, -0.698132, -0.349066, -0.174533, 0.197344, 0.337395};
    const std::vector<double> y{-0.0032, 0.00179, 0.00411, 0.0041, 0.00212, -0.001, -0.0031, -0.005227, -0.005435};
    for (std::size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(tx.function.calcValue(x[k]), y[k], 1e-15);
    EXPECT_NEAR(ty.function.calcValue(-1.3), 0.01 * -1.3 + 0.002, 1e-16);

    Eigen::VectorXd q = model.getDefaultQ();
    applyCoordinateCouplers(model, q);
    const double knee = q[tx.independentQ];
    EXPECT_EQ(knee, -0.5);  // the independent coordinates are left as they were
    EXPECT_EQ(q[tx.dependentQ], 2 * tx.function.calcValue(knee));
    EXPECT_NEAR(q[ty.dependentQ], 0.01 * knee + 0.002, 1e-16);
}

TEST(OsimCoupler, ModelFileRoundTripIsIdentical) {
    const Model model = importText(kKneeModel).model;
    const std::string text = writeModelText(model);
    EXPECT_NE(text.find("couplers:"), std::string::npos);
    const Model reread = readModelText(text, "coupled_knee.yaml");
    EXPECT_EQ(writeModelText(reread), text);
    ASSERT_EQ(reread.getNumCouplers(), model.getNumCouplers());
    Data data(model), rereadData(reread);
    Eigen::MatrixXd R(model.getNumWires(), model.getNumU()), rereadR(reread.getNumWires(), reread.getNumU());
    for (double knee : {-1.9, -0.8, 0.1}) {
        Eigen::VectorXd q = model.getDefaultQ();
        q[model.findCoordinateIndex("knee_angle")] = knee;
        const Eigen::VectorXd L = calcLengthsOnManifold(model, data, q);
        const Eigen::VectorXd rereadL = calcLengthsOnManifold(reread, rereadData, q);
        EXPECT_EQ(L, rereadL);
        calcMomentArms(model, data, R);
        calcMomentArms(reread, rereadData, rereadR);
        EXPECT_EQ(R, rereadR);
    }
}

// OpenSim's MomentArmSolver: the independent column is -dL/dq along the constraint (the chain rule
// through each coupler's f'), the dependent column -dL/dq_dep along it.
TEST(OsimCoupler, MomentArmsAreMinusLengthDerivativesAlongTheCouplers) {
    const Model model = importText(kKneeModel).model;
    const int hip = model.findCoordinateIndex("hip_flexion"), knee = model.findCoordinateIndex("knee_angle");
    const std::vector<int> dependents{model.findCoordinateIndex("knee_tx"), model.findCoordinateIndex("knee_ty")};
    Data data(model);
    Eigen::MatrixXd R(model.getNumWires(), model.getNumU()), J(model.getNumWires(), model.getNumU());
    const double h = 1e-5;
    double worst = 0, coupling = 0;
    for (double hipAngle : {-0.4, 0.3, 1.1})
        for (double kneeAngle : {-2.0, -1.5, -0.9, -0.45, -0.1, 0.15}) {
            Eigen::VectorXd q = model.getDefaultQ();
            q[hip] = hipAngle;
            q[knee] = kneeAngle;
            calcLengthsOnManifold(model, data, q);
            calcMomentArms(model, data, R);
            calcWireJacobian(model, data, J);
            // Coordinates are custom or pin ones here, so u index = q index.
            auto lengthsAt = [&](int coordinate, double delta) {
                Eigen::VectorXd shifted = q;
                shifted[coordinate] += delta;
                return calcLengthsOnManifold(model, data, shifted);
            };
            for (int c : {hip, knee}) {
                const Eigen::VectorXd expected = -(lengthsAt(c, h) - lengthsAt(c, -h)) / (2 * h);
                worst = std::max(worst, (R.col(c) - expected).lpNorm<Eigen::Infinity>());
            }
            // The dependent columns, by the dependent coordinate's own change along the constraint; the
            // error is scaled by dq_dep/dq_indep, which divides the independent column's into it.
            Eigen::VectorXd qPlus = q, qMinus = q;
            qPlus[knee] += h;
            qMinus[knee] -= h;
            applyCoordinateCouplers(model, qPlus);
            applyCoordinateCouplers(model, qMinus);
            const Eigen::VectorXd dL = lengthsAt(knee, h) - lengthsAt(knee, -h);
            for (int d : dependents) {
                const double dq = qPlus[d] - qMinus[d];
                if (std::abs(dq) < 1e-3 * 2 * h) continue;  // f' ~ 0: the column is 0 by convention
                worst = std::max(worst, (R.col(d) - (-dL / dq)).lpNorm<Eigen::Infinity>() * std::abs(dq) / (2 * h));
            }
            coupling = std::max(coupling, (R.col(knee) + J.col(knee)).lpNorm<Eigen::Infinity>());
        }
    EXPECT_LT(worst, 1e-6) << "m";
    // The couplers change the knee's moment arms measurably, so the comparison above tests the chain rule.
    EXPECT_GT(coupling, 1e-4) << "m";
    std::ostringstream text;
    text << worst;
    RecordProperty("worst_moment_arm_error_m", text.str());
}

// Each refusal starts at the offending element's file:line and names what is wrong.
TEST(OsimCoupler, BadInputIsRefusedAtItsLine) {
    auto expectRefused = [](const std::string& text, const std::string& lineOfText, const std::vector<std::string>& words) {
        const std::string path = writeTestFile(text);
        EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { convertOsimModel(readOsimModel(path)); },
                                                    path + ":" + std::to_string(lineOf(text, lineOfText)), words, text));
    };
    const std::string unknownIndependent = replaced(
        kKneeModel, "<independent_coordinate_names>knee_angle</independent_coordinate_names>\n        <dependent_coordinate_name>knee_tx",
        "<independent_coordinate_names>knee_flexion</independent_coordinate_names>\n        <dependent_coordinate_name>knee_tx");
    expectRefused(unknownIndependent, "<independent_coordinate_names>knee_flexion", {"knee_flexion", "no coordinate"});
    const std::string unknownDependent =
        replaced(kKneeModel, "<dependent_coordinate_name>knee_ty</dependent_coordinate_name>",
                 "<dependent_coordinate_name>knee_tz</dependent_coordinate_name>");
    expectRefused(unknownDependent, "<dependent_coordinate_name>knee_tz", {"knee_tz", "no coordinate"});
    const std::string noFunction = replaced(
        kKneeModel, "<coupled_coordinates_function><LinearFunction><coefficients>0.01 0.002</coefficients></LinearFunction></coupled_coordinates_function>",
        "");
    expectRefused(noFunction, "name=\"knee_ty_coupler\"", {"missing <coupled_coordinates_function>"});
    const std::string twoIndependents =
        replaced(kKneeModel, "<independent_coordinate_names>knee_angle</independent_coordinate_names>\n        <dependent_coordinate_name>knee_ty",
                 "<independent_coordinate_names>knee_angle hip_flexion</independent_coordinate_names>\n        "
                 "<dependent_coordinate_name>knee_ty");
    expectRefused(twoIndependents, "name=\"knee_ty_coupler\"", {"knee_ty_coupler", "2 independent coordinates"});
    const std::string piecewise = replaced(
        kKneeModel, "<LinearFunction><coefficients>0.01 0.002</coefficients></LinearFunction></coupled",
        "<PiecewiseLinearFunction><x>-3 1</x><y>0 0.01</y></PiecewiseLinearFunction></coupled");
    expectRefused(piecewise, "<PiecewiseLinearFunction>", {"PiecewiseLinearFunction", "not supported"});
    const std::string itself = replaced(kKneeModel, "<dependent_coordinate_name>knee_ty</dependent_coordinate_name>",
                                        "<dependent_coordinate_name>knee_angle</dependent_coordinate_name>");
    expectRefused(itself, "name=\"knee_ty_coupler\"", {"knee_ty_coupler", "knee_angle", "itself"});
    const std::string twice = replaced(kKneeModel, "<dependent_coordinate_name>knee_ty</dependent_coordinate_name>",
                                       "<dependent_coordinate_name>knee_tx</dependent_coordinate_name>");
    expectRefused(twice, "name=\"knee_ty_coupler\"", {"knee_ty_coupler", "knee_tx", "already", "knee_tx_coupler"});
}

// A coupler OpenSim does not enforce leaves its dependent coordinate free there too: listed, not imported.
TEST(OsimCoupler, DisabledCouplerIsListed) {
    const std::string text =
        replaced(kKneeModel, "<isEnforced>true</isEnforced>", "<isEnforced>false</isEnforced>");
    const OsimConversion conversion = importText(text);
    ASSERT_EQ(conversion.model.getNumCouplers(), 1);
    EXPECT_EQ(conversion.model.getCouplers()[0].name, "knee_ty_coupler");
    const auto listed = std::find_if(conversion.notImported.begin(), conversion.notImported.end(),
                                     [](const std::string& line) { return line.find("'knee_tx_coupler'") != std::string::npos; });
    ASSERT_NE(listed, conversion.notImported.end());
    EXPECT_NE(listed->find(":" + std::to_string(lineOf(text, "name=\"knee_tx_coupler\""))), std::string::npos) << *listed;
    EXPECT_NE(listed->find("disabled"), std::string::npos) << *listed;
}

// The model file's couplers: errors at the entry's line naming the coupler and the field.
TEST(OsimCoupler, ModelFileCouplerErrors) {
    const std::string text = writeModelText(importText(kKneeModel).model);
    const std::string entry = "{name: knee_ty_coupler, dependent: knee_ty, independent: knee_angle";
    ASSERT_NE(text.find(entry), std::string::npos) << text;
    auto expectRefused = [&](const std::string& changed, const std::vector<std::string>& words) {
        EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { readModelText(changed, "m.yaml"); },
                                                    "m.yaml:" + std::to_string(lineOf(text, entry)), words, changed));
    };
    expectRefused(replaced(text, entry, "{name: knee_ty_coupler, dependent: knee_tz, independent: knee_angle"),
                  {"coupler 'knee_ty_coupler'", "unknown coordinate 'knee_tz'"});
    expectRefused(replaced(text, entry, "{name: knee_ty_coupler, dependent: knee_ty, independent: knee_tx"),
                  {"knee_ty_coupler", "knee_tx_coupler", "chain"});
    expectRefused(replaced(text, entry, "{name: knee_ty_coupler, dependent: knee_ty, independent: knee_angle, "
                                        "scale_factor: .nan"),
                  {"scale_factor", "finite"});
    expectRefused(replaced(text, entry, "{name: knee_ty_coupler, dependent: knee_ty, independent: knee_angle, color: red"),
                  {"unknown field 'color'", "coupler"});
    const std::size_t function = text.find(", function:", text.find(entry));
    std::string noFunction = text;
    noFunction.erase(function, text.find('}', function) + 1 - function);  // ", function: {...}"
    expectRefused(noFunction, {"coupler 'knee_ty_coupler'", "missing field 'function'"});
}

}  // namespace
}  // namespace sinew

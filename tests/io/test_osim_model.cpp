// The .osim reader: OpenSim's two shipped models read with the counts and numbers their XML holds (counted
// here by plain text search, and checked against OpenSim's own output files), a small model using every
// element the reader knows, and one refusal at the right "file:line" per kind of bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/osim_model.hpp"
#include "sinew/io/storage_file.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

const std::string kOpenSimDir = std::string(SINEW_SHARED_DIR) + "/data/opensim";

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

int count(const std::string& text, const std::string& needle) {
    int n = 0;
    for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
    return n;
}

// The 1-based line of the first occurrence of `needle` in `text`.
int lineOf(const std::string& text, const std::string& needle) {
    const std::size_t at = text.find(needle);
    EXPECT_NE(at, std::string::npos) << needle;
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

// A file private to the running test, since ctest may run this file's tests in parallel.
std::string writeTestFile(const std::string& text) {
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sinew_osim_model";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".osim")).string();
    std::ofstream(path) << text;
    return path;
}

// Rx(a) Ry(b) Rz(c) written out element by element, independent of Eigen's AngleAxis.
Eigen::Matrix3d bodyFixedXYZ(double a, double b, double c) {
    Eigen::Matrix3d x, y, z;
    x << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
    y << std::cos(b), 0, std::sin(b), 0, 1, 0, -std::sin(b), 0, std::cos(b);
    z << std::cos(c), -std::sin(c), 0, std::sin(c), std::cos(c), 0, 0, 0, 1;
    return x * y * z;
}

TEST(OsimModel, BodyFixedXYZMatchesTheProductOfAxisRotations) {
    for (const Eigen::Vector3d& angles : {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(-2.0, 1.4, 3.0)})
        EXPECT_LT((calcRotationFromBodyFixedXYZ(angles) - bodyFixedXYZ(angles[0], angles[1], angles[2])).norm(), 1e-15);
}

// OpenSim names inverse-dynamics outputs <coordinate>_moment for rotational coordinates and _force for the
// others: OpenSim's own result file checks the motion types the reader inferred.
void expectMotionTypesMatch(const OsimModel& model, const std::string& inverseDynamicsFile) {
    const StorageTable results = readStorageFile(inverseDynamicsFile);
    ASSERT_EQ(results.columns.size(), model.coordinates.size());
    for (const OsimCoordinate& coordinate : model.coordinates) {
        const std::string suffix = coordinate.motionType == OsimMotionType::Rotational ? "_moment" : "_force";
        EXPECT_EQ(std::count(results.columns.begin(), results.columns.end(), coordinate.name + suffix), 1)
            << coordinate.name + suffix;
    }
}

int countPathPoints(const OsimModel& model, OsimPathPoint::Type type) {
    int n = 0;
    for (const OsimPathForce& force : model.pathForces)
        for (const OsimPathPoint& point : force.path.points) n += point.type == type;
    return n;
}

TEST(OsimModel, Arm26) {
    const std::string path = kOpenSimDir + "/arm26/arm26.osim";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "OpenSim data not found at " << kOpenSimDir;
    const std::string xml = readText(path);
    const OsimModel model = readOsimModel(path);

    EXPECT_EQ(model.name, "arm26");
    EXPECT_EQ(model.version, 40000);
    EXPECT_EQ(model.gravity, Eigen::Vector3d(0, -9.8065999999999995, 0));
    EXPECT_EQ(static_cast<int>(model.bodies.size()), count(xml, "<Body name="));
    EXPECT_EQ(static_cast<int>(model.joints.size()), count(xml, "<CustomJoint name=") + count(xml, "<WeldJoint name="));
    EXPECT_EQ(static_cast<int>(model.coordinates.size()), count(xml, "<Coordinate name="));
    EXPECT_EQ(static_cast<int>(model.pathForces.size()), count(xml, "<Thelen2003Muscle name="));
    EXPECT_EQ(countPathPoints(model, OsimPathPoint::Type::Fixed), count(xml, "<PathPoint name="));
    EXPECT_EQ(static_cast<int>(model.frames.size()), count(xml, "<PhysicalOffsetFrame name="));
    EXPECT_EQ(static_cast<int>(model.markers.size()), count(xml, "<Marker name="));
    EXPECT_TRUE(model.unsupported.empty()) << model.unsupported.front().type;

    const OsimBody* humerus = findBody(model, "r_humerus");
    ASSERT_NE(humerus, nullptr);
    EXPECT_EQ(humerus->mass, 1.8645719999999999);
    EXPECT_EQ(humerus->massCenter, Eigen::Vector3d(0, -0.18049599999999999, 0));
    EXPECT_EQ(humerus->inertia[1], 0.0045510000000000004);
    ASSERT_EQ(humerus->wrapObjects.size(), 3u);
    EXPECT_EQ(humerus->wrapObjects[0].shape, OsimWrapObject::Shape::Ellipsoid);
    EXPECT_EQ(humerus->wrapObjects[0].dimensions, Eigen::Vector3d(0.035000000000000003, 0.02, 0.02));
    EXPECT_EQ(humerus->wrapObjects[0].quadrant, "z");
    EXPECT_EQ(humerus->wrapObjects[2].shape, OsimWrapObject::Shape::Cylinder);
    EXPECT_EQ(humerus->wrapObjects[2].length, 0.050000000000000003);

    const OsimJoint* elbow = findJoint(model, "r_elbow");
    ASSERT_NE(elbow, nullptr);
    EXPECT_EQ(elbow->type, OsimJointType::Custom);
    EXPECT_EQ(elbow->parent.body, "r_humerus");
    EXPECT_EQ(elbow->parent.p_BF, Eigen::Vector3d(0.0061000000000000004, -0.29039999999999999, -0.0123));
    EXPECT_EQ(elbow->child.body, "r_ulna_radius_hand");
    EXPECT_EQ(elbow->spatialTransform[0].axis,
              Eigen::Vector3d(0.049400010000000001, 0.036600010000000002, 0.99810825000000003));
    EXPECT_EQ(elbow->spatialTransform[0].function.type, OsimFunctionType::Linear);
    EXPECT_EQ(elbow->spatialTransform[1].function.type, OsimFunctionType::Constant);
    ASSERT_EQ(elbow->numCoordinates, 1);
    const OsimCoordinate& flexion = model.coordinates[elbow->firstCoordinate];
    EXPECT_EQ(flexion.name, "r_elbow_flex");
    EXPECT_EQ(flexion.rangeMax, 2.2689280300000001);
    EXPECT_EQ(findJoint(model, "offset")->parent.p_BF, Eigen::Vector3d(0, 0.80000000000000004, 0));

    const OsimPathForce* tri = findPathForce(model, "TRIlong");
    ASSERT_NE(tri, nullptr);
    EXPECT_EQ(tri->type, "Thelen2003Muscle");
    EXPECT_EQ(tri->maxIsometricForce, 798.51999999999998);
    EXPECT_EQ(tri->tendonSlackLength, 0.14299999999999999);
    EXPECT_EQ(tri->limits.minControl, 0.01);  // Thelen2003Muscle's default, which OpenSim 4.4.1 holds SO to
    EXPECT_EQ(tri->properties.at("FmaxTendonStrain"), "0.033000000000000002");
    ASSERT_EQ(tri->path.points.size(), 5u);
    EXPECT_EQ(tri->path.points[0].frame.body, "base");
    EXPECT_EQ(tri->path.points[0].location, Eigen::Vector3d(-0.053650000000000003, -0.013729999999999999, 0.14723));
    ASSERT_EQ(tri->path.wraps.size(), 3u);
    EXPECT_EQ(tri->path.wraps[2].wrapObject, "TRIlongglen");
    EXPECT_EQ(tri->path.wraps[2].body, "base");

    expectMotionTypesMatch(model, kOpenSimDir + "/arm26/opensim-4.4.1/arm26_InverseDynamics.sto");
}

TEST(OsimModel, Gait2354) {
    const std::string path = kOpenSimDir + "/gait2354/subject01_simbody.osim";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "OpenSim data not found at " << kOpenSimDir;
    const std::string xml = readText(path);
    const OsimModel model = readOsimModel(path);

    EXPECT_EQ(static_cast<int>(model.bodies.size()), count(xml, "<Body name="));
    EXPECT_EQ(static_cast<int>(model.joints.size()), count(xml, "<CustomJoint name="));
    EXPECT_EQ(static_cast<int>(model.pathForces.size()), count(xml, "<Thelen2003Muscle name="));
    EXPECT_EQ(countPathPoints(model, OsimPathPoint::Type::Fixed), count(xml, "<PathPoint name="));
    EXPECT_EQ(countPathPoints(model, OsimPathPoint::Type::Conditional), count(xml, "<ConditionalPathPoint name="));
    EXPECT_EQ(countPathPoints(model, OsimPathPoint::Type::Moving), count(xml, "<MovingPathPoint name="));
    EXPECT_TRUE(model.unsupported.empty());

    // The coordinates are those OpenSim's inverse kinematics wrote.
    std::vector<std::string> names;
    for (const OsimCoordinate& coordinate : model.coordinates) names.push_back(coordinate.name);
    std::vector<std::string> motion = readStorageFile(kOpenSimDir + "/gait2354/subject01_walk1_ik.mot").columns;
    std::sort(names.begin(), names.end());
    std::sort(motion.begin(), motion.end());
    EXPECT_EQ(names, motion);
    expectMotionTypesMatch(model, kOpenSimDir + "/gait2354/opensim-4.4.1/inverse_dynamics.sto");

    const OsimJoint* pelvis = findJoint(model, "ground_pelvis");
    ASSERT_EQ(pelvis->numCoordinates, 6);
    EXPECT_EQ(model.coordinates[pelvis->firstCoordinate + 4].name, "pelvis_ty");
    EXPECT_EQ(model.coordinates[pelvis->firstCoordinate + 4].defaultValue, 1.0149999999999999);
    EXPECT_EQ(findJoint(model, "hip_r")->parent.p_BF,
              Eigen::Vector3d(-0.072437600000000005, -0.067724500000000007, 0.085552199999999995));
    EXPECT_EQ(findBody(model, "pelvis")->mass, 11.3751712907406);

    // The knee's tibia translation: a SimmSpline of the knee angle, scaled.
    const OsimTransformAxis& knee = findJoint(model, "knee_r")->spatialTransform[3];
    EXPECT_EQ(knee.coordinates, std::vector<std::string>{"knee_angle_r"});
    ASSERT_EQ(knee.function.type, OsimFunctionType::Multiplier);
    EXPECT_EQ(knee.function.scale, 1.14724);
    ASSERT_EQ(knee.function.inner.size(), 1u);
    EXPECT_EQ(knee.function.inner[0].type, OsimFunctionType::SimmSpline);
    EXPECT_EQ(knee.function.inner[0].x.size(), 12u);
    EXPECT_EQ(knee.function.inner[0].y.back(), -0.00525);

    const OsimPathForce* gracilis = findPathForce(model, "grac_r");
    ASSERT_NE(gracilis, nullptr);
    const OsimPathPoint& conditional = gracilis->path.points[1];
    EXPECT_EQ(conditional.type, OsimPathPoint::Type::Conditional);
    EXPECT_EQ(conditional.coordinate, "knee_angle_r");
    EXPECT_EQ(conditional.rangeMin, -0.436332);
    EXPECT_EQ(conditional.rangeMax, 0.17453299999999999);
    EXPECT_EQ(conditional.frame.body, "tibia_r");

    const OsimPathForce* rectus = findPathForce(model, "rect_fem_r");
    ASSERT_NE(rectus, nullptr);
    const auto moving = std::find_if(rectus->path.points.begin(), rectus->path.points.end(),
                                     [](const OsimPathPoint& p) { return p.type == OsimPathPoint::Type::Moving; });
    ASSERT_NE(moving, rectus->path.points.end());
    EXPECT_EQ(moving->name, "rect_fem_r-P3");
    for (int i = 0; i < 3; ++i) EXPECT_EQ(moving->locationCoordinates[i], "knee_angle_r");
    EXPECT_EQ(moving->locationFunctions[0].scale, 0.98852300000000004);
    EXPECT_EQ(moving->locationFunctions[0].inner[0].x.size(), 17u);
    EXPECT_EQ(moving->locationFunctions[2].inner[0].y, (std::vector<double>{0.0014, 0.0014}));
}

// A small model with every element the reader knows, and some it does not. Lines are found by searching
// the text, so the expectations do not depend on counting lines by hand.
const std::string kSmallModel = R"(<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="40000">
  <Model name="small">
    <Ground name="ground">
      <WrapObjectSet><objects>
        <WrapSphere name="ball"><radius>0.1</radius><translation>0 1 0</translation></WrapSphere>
      </objects></WrapObjectSet>
    </Ground>
    <gravity>0 0 -9.81</gravity>
    <BodySet name="bodyset"><objects>
      <Body name="a"><mass>2</mass><mass_center>0 -0.1 0</mass_center><inertia>0.1 0.2 0.3 0.01 0.02 0.03</inertia>
        <components>
          <PhysicalOffsetFrame name="a_site"><socket_parent>..</socket_parent><translation>0 -0.5 0</translation><orientation>0.1 0.2 0.3</orientation></PhysicalOffsetFrame>
          <PhysicalOffsetFrame name="a_tip"><socket_parent>../a_site</socket_parent><translation>0.2 0 0</translation><orientation>-0.3 0.4 0.5</orientation></PhysicalOffsetFrame>
        </components>
      </Body>
      <Body name="b"><mass>1</mass>
        <WrapObjectSet><objects>
          <WrapCylinder name="cyl"><radius>0.02</radius><length>0.1</length><quadrant>-y</quadrant><active>false</active></WrapCylinder>
          <WrapTorus name="ring"><inner_radius>0.01</inner_radius><outer_radius>0.04</outer_radius></WrapTorus>
          <WrapDoubleCylinderObst name="obst"/>
        </objects></WrapObjectSet>
      </Body>
      <Body name="c"><mass>1</mass></Body>
      <Body name="d"><mass>1</mass></Body>
      <Body name="e"><mass>1</mass></Body>
      <Body name="f"><mass>1</mass></Body>
    </objects></BodySet>
    <JointSet name="jointset"><objects>
      <FreeJoint name="j_free"><socket_parent_frame>/ground</socket_parent_frame><socket_child_frame>/bodyset/a</socket_child_frame>
        <coordinates><Coordinate name="f1"/><Coordinate name="f2"/><Coordinate name="f3"/><Coordinate name="f4"/><Coordinate name="f5"/><Coordinate name="f6"/></coordinates>
      </FreeJoint>
      <PinJoint name="j_pin"><socket_parent_frame>a_tip</socket_parent_frame><socket_child_frame>b_offset</socket_child_frame>
        <coordinates><Coordinate name="pin_q"><default_value>0.5</default_value><range>-1 2</range><clamped>true</clamped><locked>true</locked></Coordinate></coordinates>
        <frames><PhysicalOffsetFrame name="b_offset"><socket_parent>/bodyset/b</socket_parent><translation>0 0.1 0</translation></PhysicalOffsetFrame></frames>
      </PinJoint>
      <BallJoint name="j_ball"><socket_parent_frame>/bodyset/b</socket_parent_frame><socket_child_frame>/bodyset/c</socket_child_frame>
        <coordinates><Coordinate name="b1"/><Coordinate name="b2"/><Coordinate name="b3"/></coordinates>
      </BallJoint>
      <CustomJoint name="j_custom"><socket_parent_frame>/bodyset/c</socket_parent_frame><socket_child_frame>/bodyset/d</socket_child_frame>
        <coordinates><Coordinate name="knee_beta"/><Coordinate name="knee"/></coordinates>
        <SpatialTransform>
          <TransformAxis name="rotation1"><coordinates>knee</coordinates><axis>0 0 1</axis><LinearFunction name="function"><coefficients>1 0</coefficients></LinearFunction></TransformAxis>
          <TransformAxis name="translation1"><coordinates>knee</coordinates><axis>1 0 0</axis><function><PolynomialFunction><coefficients>0.1 0.2 0.3</coefficients></PolynomialFunction></function></TransformAxis>
          <TransformAxis name="translation2"><coordinates>knee_beta</coordinates><axis>0 1 0</axis><NaturalCubicSpline name="function"><x>0 1 2</x><y>0 1 4</y></NaturalCubicSpline></TransformAxis>
        </SpatialTransform>
      </CustomJoint>
      <UniversalJoint name="j_univ"><socket_parent_frame>/bodyset/d</socket_parent_frame><socket_child_frame>/bodyset/e</socket_child_frame>
        <coordinates><Coordinate name="u1"/><Coordinate name="u2"/></coordinates>
      </UniversalJoint>
      <WeldJoint name="j_weld"><socket_parent_frame>/ground</socket_parent_frame><socket_child_frame>/bodyset/f</socket_child_frame></WeldJoint>
      <EllipsoidJoint name="j_ellipsoid"/>
    </objects></JointSet>
    <ConstraintSet name="constraintset"><objects>
      <CoordinateCouplerConstraint name="coupler"><isEnforced>true</isEnforced>
        <coupled_coordinates_function><SimmSpline name="f"><x>-1 0 1</x><y>-0.5 0 0.5</y></SimmSpline></coupled_coordinates_function>
        <independent_coordinate_names>knee</independent_coordinate_names><dependent_coordinate_name>knee_beta</dependent_coordinate_name><scale_factor>2</scale_factor>
      </CoordinateCouplerConstraint>
      <WeldConstraint name="weld_c"/>
    </objects></ConstraintSet>
    <ForceSet name="forceset"><objects>
      <Millard2012EquilibriumMuscle name="m1"><isDisabled>true</isDisabled>
        <GeometryPath name="geometrypath"><PathPointSet><objects>
          <PathPoint name="p1"><socket_parent_frame>/bodyset/a/a_tip</socket_parent_frame><location>0.01 0.02 0.03</location></PathPoint>
          <ConditionalPathPoint name="p2"><socket_parent_frame>/bodyset/b</socket_parent_frame><socket_coordinate>/jointset/j_pin/pin_q</socket_coordinate><range>-0.5 0.5</range></ConditionalPathPoint>
          <MovingPathPoint name="p3"><socket_parent_frame>/bodyset/c</socket_parent_frame><socket_x_coordinate>/jointset/j_custom/knee</socket_x_coordinate><x_location><LinearFunction><coefficients>0.5 0.1</coefficients></LinearFunction></x_location><y_location><Constant><value>0.2</value></Constant></y_location></MovingPathPoint>
        </objects></PathPointSet>
        <PathWrapSet><objects><PathWrap name="w"><wrap_object>cyl</wrap_object><method>midpoint</method><range>1 2</range></PathWrap></objects></PathWrapSet>
        </GeometryPath>
        <max_isometric_force>500</max_isometric_force><fiber_damping>0.01</fiber_damping>
        <ActiveForceLengthCurve name="ActiveForceLengthCurve"><min_norm_active_fiber_length>0.47</min_norm_active_fiber_length></ActiveForceLengthCurve>
      </Millard2012EquilibriumMuscle>
      <Ligament name="lig"><GeometryPath><PathPointSet><objects>
          <PathPoint name="l1"><socket_parent_frame>/bodyset/d</socket_parent_frame></PathPoint>
          <PathPoint name="l2"><socket_parent_frame>/bodyset/e</socket_parent_frame><location>0 -0.2 0</location></PathPoint>
        </objects></PathPointSet></GeometryPath>
        <resting_length>0.3</resting_length><pcsa_force>1000</pcsa_force>
        <force_length_curve><SimmSpline><x>0 1 2</x><y>0 0 1</y></SimmSpline></force_length_curve>
      </Ligament>
      <GeneralizedForce name="reserve"><coordinate>pin_q</coordinate><optimal_force>10</optimal_force><min_control>-inf</min_control><max_control>Inf</max_control></GeneralizedForce>
      <PointActuator name="push"><body>b</body><point>0 1 0</point><point_is_global>true</point_is_global><direction>0 0 1</direction><optimal_force>5</optimal_force></PointActuator>
      <TorqueActuator name="twist"><bodyA>b</bodyA><bodyB>ground</bodyB><axis>1 0 0</axis><torque_is_global>false</torque_is_global></TorqueActuator>
      <CoordinateLimitForce name="limit"><coordinate>pin_q</coordinate><upper_limit>30</upper_limit><transition>2</transition></CoordinateLimitForce>
      <ExpressionBasedCoordinateForce name="expression"/>
    </objects></ForceSet>
    <MarkerSet name="markerset"><objects><Marker name="mk"><socket_parent_frame>/bodyset/b</socket_parent_frame><location>1 2 3</location><fixed>true</fixed></Marker></objects></MarkerSet>
    <ContactGeometrySet name="contactgeometryset"><objects><ContactSphere name="contact"><socket_frame>/bodyset/b</socket_frame><location>0 0.1 0</location><radius>0.02</radius></ContactSphere><ContactMesh name="mesh"/></objects></ContactGeometrySet>
    <SomethingNew name="novel"/>
  </Model>
</OpenSimDocument>
)";

TEST(OsimModel, SmallModelWithEveryElement) {
    const std::string path = writeTestFile(kSmallModel);
    const OsimModel model = readOsimModel(path);
    EXPECT_EQ(model.gravity, Eigen::Vector3d(0, 0, -9.81));
    ASSERT_EQ(model.ground.wrapObjects.size(), 1u);
    EXPECT_EQ(model.ground.wrapObjects[0].radius, 0.1);
    ASSERT_EQ(model.bodies.size(), 6u);
    EXPECT_EQ(model.bodies[0].inertia, (Eigen::Matrix<double, 6, 1>() << 0.1, 0.2, 0.3, 0.01, 0.02, 0.03).finished());
    const OsimBody& b = model.bodies[1];
    ASSERT_EQ(b.wrapObjects.size(), 2u);
    EXPECT_EQ(b.wrapObjects[0].quadrant, "-y");
    EXPECT_FALSE(b.wrapObjects[0].active);
    EXPECT_EQ(b.wrapObjects[1].shape, OsimWrapObject::Shape::Torus);
    EXPECT_EQ(b.wrapObjects[1].outerRadius, 0.04);

    // a_tip is offset from a_site, itself offset from body a: the chain composed.
    const Eigen::Matrix3d R_AS = bodyFixedXYZ(0.1, 0.2, 0.3);
    const Eigen::Vector3d p_AT = Eigen::Vector3d(0, -0.5, 0) + R_AS * Eigen::Vector3d(0.2, 0, 0);
    const Eigen::Matrix3d R_AT = R_AS * bodyFixedXYZ(-0.3, 0.4, 0.5);
    ASSERT_EQ(model.frames.size(), 3u);
    const OsimJoint* pin = findJoint(model, "j_pin");
    ASSERT_NE(pin, nullptr);
    EXPECT_EQ(pin->parent.body, "a");  // "a_tip", a bare name, found as the model's only frame of that name
    EXPECT_EQ(pin->parent.path, "/bodyset/a/a_tip");
    EXPECT_LT((pin->parent.p_BF - p_AT).norm(), 1e-15);
    EXPECT_LT((pin->parent.R_BF - R_AT).norm(), 1e-15);
    EXPECT_EQ(pin->child.body, "b");
    EXPECT_EQ(pin->child.p_BF, Eigen::Vector3d(0, 0.1, 0));

    ASSERT_EQ(model.joints.size(), 6u);  // the EllipsoidJoint is listed as unsupported
    ASSERT_EQ(model.coordinates.size(), 14u);
    const OsimCoordinate* f1 = findCoordinate(model, "f1");
    EXPECT_EQ(f1->rangeMin, -10);  // OpenSim's defaults
    EXPECT_EQ(f1->rangeMax, 10);
    EXPECT_EQ(findCoordinate(model, "f4")->motionType, OsimMotionType::Translational);
    const OsimCoordinate* pinQ = findCoordinate(model, "pin_q");
    EXPECT_EQ(pinQ->defaultValue, 0.5);
    EXPECT_EQ(pinQ->rangeMin, -1);
    EXPECT_TRUE(pinQ->clamped);
    EXPECT_TRUE(pinQ->locked);

    // The CustomJoint's coordinates in order of first use, knee before knee_beta, with their motions.
    const OsimJoint* custom = findJoint(model, "j_custom");
    ASSERT_EQ(custom->numCoordinates, 2);
    EXPECT_EQ(model.coordinates[custom->firstCoordinate].name, "knee");
    EXPECT_EQ(model.coordinates[custom->firstCoordinate].motionType, OsimMotionType::Rotational);
    EXPECT_EQ(model.coordinates[custom->firstCoordinate + 1].name, "knee_beta");
    EXPECT_EQ(model.coordinates[custom->firstCoordinate + 1].motionType, OsimMotionType::Coupled);
    EXPECT_EQ(custom->spatialTransform[1].axis, Eigen::Vector3d::UnitY());  // absent: OpenSim's default axis
    EXPECT_EQ(custom->spatialTransform[1].function.type, OsimFunctionType::Constant);
    EXPECT_EQ(custom->spatialTransform[3].function.type, OsimFunctionType::Polynomial);
    EXPECT_EQ(custom->spatialTransform[3].function.coefficients, (std::vector<double>{0.1, 0.2, 0.3}));
    EXPECT_EQ(custom->spatialTransform[4].function.type, OsimFunctionType::NaturalCubicSpline);
    EXPECT_EQ(custom->spatialTransform[4].function.y, (std::vector<double>{0, 1, 4}));

    ASSERT_EQ(model.couplers.size(), 1u);
    EXPECT_EQ(model.couplers[0].dependentCoordinate, "knee_beta");
    EXPECT_EQ(model.couplers[0].independentCoordinates, std::vector<std::string>{"knee"});
    EXPECT_EQ(model.couplers[0].function.type, OsimFunctionType::SimmSpline);
    EXPECT_EQ(model.couplers[0].scaleFactor, 2);

    ASSERT_EQ(model.pathForces.size(), 2u);
    const OsimPathForce& muscle = model.pathForces[0];
    EXPECT_EQ(muscle.kind, OsimPathForce::Kind::Muscle);
    EXPECT_FALSE(muscle.limits.appliesForce);  // isDisabled
    EXPECT_EQ(muscle.limits.minControl, 0.01);
    EXPECT_EQ(muscle.maxIsometricForce, 500);
    EXPECT_EQ(muscle.optimalFiberLength, 0.1);  // Muscle's default
    EXPECT_EQ(muscle.properties.at("fiber_damping"), "0.01");
    EXPECT_EQ(muscle.properties.at("ActiveForceLengthCurve.min_norm_active_fiber_length"), "0.47");
    ASSERT_EQ(muscle.path.points.size(), 3u);
    EXPECT_EQ(muscle.path.points[0].frame.body, "a");
    EXPECT_LT((muscle.path.points[0].frame.p_BF - p_AT).norm(), 1e-15);
    EXPECT_EQ(muscle.path.points[1].coordinate, "pin_q");
    EXPECT_EQ(muscle.path.points[1].rangeMax, 0.5);
    const OsimPathPoint& moving = muscle.path.points[2];
    EXPECT_EQ(moving.locationCoordinates[0], "knee");
    EXPECT_EQ(moving.locationCoordinates[1], "");
    EXPECT_EQ(moving.locationFunctions[0].coefficients, (std::vector<double>{0.5, 0.1}));
    EXPECT_EQ(moving.locationFunctions[1].value, 0.2);
    EXPECT_EQ(moving.locationFunctions[2].type, OsimFunctionType::Constant);
    ASSERT_EQ(muscle.path.wraps.size(), 1u);
    EXPECT_EQ(muscle.path.wraps[0].body, "b");
    EXPECT_EQ(muscle.path.wraps[0].method, "midpoint");
    EXPECT_EQ(muscle.path.wraps[0].rangeEnd, 2);
    const OsimPathForce& ligament = model.pathForces[1];
    EXPECT_EQ(ligament.kind, OsimPathForce::Kind::Ligament);
    EXPECT_EQ(ligament.properties.at("resting_length"), "0.3");
    EXPECT_EQ(ligament.curves.at("force_length_curve").x, (std::vector<double>{0, 1, 2}));

    ASSERT_EQ(model.coordinateActuators.size(), 1u);  // the old name GeneralizedForce
    EXPECT_EQ(model.coordinateActuators[0].coordinate, "pin_q");
    EXPECT_EQ(model.coordinateActuators[0].limits.optimalForce, 10);
    EXPECT_EQ(model.coordinateActuators[0].limits.minControl, -INFINITY);
    EXPECT_EQ(model.coordinateActuators[0].limits.maxControl, INFINITY);
    ASSERT_EQ(model.pointActuators.size(), 1u);
    EXPECT_TRUE(model.pointActuators[0].pointIsGlobal);
    EXPECT_EQ(model.pointActuators[0].direction, Eigen::Vector3d::UnitZ());
    ASSERT_EQ(model.torqueActuators.size(), 1u);
    EXPECT_EQ(model.torqueActuators[0].bodyB, "ground");
    EXPECT_FALSE(model.torqueActuators[0].torqueIsGlobal);
    ASSERT_EQ(model.markers.size(), 1u);
    EXPECT_EQ(model.markers[0].location, Eigen::Vector3d(1, 2, 3));

    // Everything not captured is listed with its line.
    std::set<std::string> unsupported;
    for (const OsimUnsupported& item : model.unsupported) {
        unsupported.insert(item.type + " " + item.name);
        EXPECT_EQ(item.where, path + ":" + std::to_string(lineOf(kSmallModel, "name=\"" + item.name + "\"")));
    }
    EXPECT_EQ(unsupported, (std::set<std::string>{"WrapDoubleCylinderObst obst", "EllipsoidJoint j_ellipsoid",
                                                  "WeldConstraint weld_c", "ExpressionBasedCoordinateForce expression",
                                                  "ContactMesh mesh", "SomethingNew novel"}));
    // Force elements and contact geometry are read, in OpenSim's units and defaults.
    ASSERT_EQ(model.coordinateLimits.size(), 1u);
    EXPECT_EQ(model.coordinateLimits[0].coordinate, "pin_q");
    EXPECT_EQ(model.coordinateLimits[0].upperLimit, 30);
    EXPECT_EQ(model.coordinateLimits[0].transition, 2);
    EXPECT_EQ(model.coordinateLimits[0].lowerStiffness, 1);
    ASSERT_EQ(model.contactGeometry.size(), 1u);
    EXPECT_EQ(model.contactGeometry[0].frame.body, "b");
    EXPECT_EQ(model.contactGeometry[0].frame.p_BF, Eigen::Vector3d(0, 0.1, 0));
    EXPECT_EQ(model.contactGeometry[0].radius, 0.02);
}

// Reading kSmallModel with `from` replaced by `to` fails at the line of `at` (searched in the changed text)
// with a message holding every one of `words`.
::testing::AssertionResult rejects(const std::string& from, const std::string& to, const std::string& at,
                                   const std::vector<std::string>& words) {
    std::string text = kSmallModel;
    const std::size_t position = text.find(from);
    if (position == std::string::npos) return ::testing::AssertionFailure() << "'" << from << "' is not in the model";
    text.replace(position, from.size(), to);
    const std::string path = writeTestFile(text);
    return test::throwsErrorAt([&] { readOsimModel(path); }, path + ":" + std::to_string(lineOf(text, at)) + ":",
                               words, text);
}

TEST(OsimModel, MissingBody) {
    EXPECT_TRUE(rejects("<socket_parent_frame>/bodyset/b</socket_parent_frame><socket_coordinate>",
                        "<socket_parent_frame>/bodyset/nobody</socket_parent_frame><socket_coordinate>",
                        "/bodyset/nobody", {"<socket_parent_frame>", "'/bodyset/nobody'", "no body or frame"}));
}

TEST(OsimModel, UnknownFunctionType) {
    EXPECT_TRUE(rejects("<NaturalCubicSpline name=\"function\"><x>0 1 2</x><y>0 1 4</y></NaturalCubicSpline>",
                        "<StepFunction name=\"function\"><start_value>0</start_value></StepFunction>", "StepFunction",
                        {"<StepFunction name='function'>", "unknown function type", "SimmSpline"}));
}

TEST(OsimModel, MissingCoordinate) {
    EXPECT_TRUE(rejects("/jointset/j_pin/pin_q", "/jointset/j_pin/nothing", "nothing",
                        {"<socket_coordinate>", "'/jointset/j_pin/nothing' is no coordinate"}));
    EXPECT_TRUE(rejects("<dependent_coordinate_name>knee_beta", "<dependent_coordinate_name>ankle",
                        "<dependent_coordinate_name>", {"'ankle' is no coordinate"}));
}

// A force element that leaves out the property naming its coordinate or body is refused at the element.
TEST(OsimModel, ForceWithoutItsCoordinateOrBody) {
    EXPECT_TRUE(rejects("<coordinate>pin_q</coordinate><upper_limit>", "<upper_limit>", "<CoordinateLimitForce",
                        {"<CoordinateLimitForce name='limit'>", "missing <coordinate>"}));
    EXPECT_TRUE(rejects("<bodyA>b</bodyA>", "", "<TorqueActuator", {"<TorqueActuator name='twist'>", "missing <bodyA>"}));
}

TEST(OsimModel, MissingWrapObject) {
    EXPECT_TRUE(rejects("<wrap_object>cyl", "<wrap_object>cone", "<wrap_object>", {"'cone' is no wrap object"}));
}

TEST(OsimModel, UndeclaredTransformCoordinate) {
    EXPECT_TRUE(rejects("<coordinates>knee_beta</coordinates>", "<coordinates>knee_gamma</coordinates>",
                        "<CustomJoint", {"'knee_gamma', not declared"}));
}

TEST(OsimModel, WrongNumberOfCoordinates) {
    EXPECT_TRUE(rejects("<Coordinate name=\"u2\"/>", "", "<UniversalJoint",
                        {"1 coordinates", "a UniversalJoint has 2"}));
}

TEST(OsimModel, NaNAndMissingValues) {
    EXPECT_TRUE(rejects("<Body name=\"c\"><mass>1</mass>", "<Body name=\"c\"><mass>nan</mass>", "<mass>nan",
                        {"<mass>", "NaN"}));
    EXPECT_TRUE(rejects("<Body name=\"c\"><mass>1</mass>", "<Body name=\"c\">", "<Body name=\"c\"",
                        {"<Body name='c'>", "missing <mass>"}));
    EXPECT_TRUE(rejects("<translation>0 -0.5 0</translation>", "<translation>0 -0.5</translation>",
                        "<translation>0 -0.5<", {"expected 3 numbers", "'0 -0.5'"}));
}

TEST(OsimModel, FramesOffsetInALoop) {
    EXPECT_TRUE(rejects("<socket_parent>..</socket_parent>", "<socket_parent>../a_tip</socket_parent>",
                        "name=\"a_site\"", {"loop"}));
}

// As MjcfModel.RefusesElementsNestedTooDeep: the .osim reader loads its files the same way.
TEST(OsimModel, ElementsNestedTooDeep) {
    std::string nested;
    for (int i = 0; i < 600; ++i) nested += "<a>";
    for (int i = 0; i < 600; ++i) nested += "</a>";
    EXPECT_TRUE(rejects("<Body name=\"c\"><mass>1</mass>", "<Body name=\"c\"><mass>1</mass>" + nested, "<a><a>",
                        {"<a>", "nested 501 elements deep", "500"}));
}

TEST(OsimModel, MalformedXmlAndOldVersions) {
    EXPECT_TRUE(rejects("</BallJoint>", "</Ball>", "</Ball>", {"malformed XML", "mismatch", "</Ball>"}));
    EXPECT_TRUE(rejects("Version=\"40000\"", "Version=\"30000\"", "<Model", {"Version 30000", "OpenSim 4"}));
    const std::string missing = ::testing::TempDir() + "/no_such_model.osim";
    EXPECT_TRUE(test::throwsErrorAt([&] { readOsimModel(missing); }, missing + ": ", {"cannot open"}, missing));
}

}  // namespace
}  // namespace sinew

// Quirks OpenSim 4.4 accepts and sinew imports as OpenSim does, with a warning naming the body: an inertia
// SimTK::Inertia refuses (reset by OpenSim's Body::getInertia to a sphere from the moments' norm), a massless
// body given inertia (reset to zero), and muscles anchored to ground. The expected inertias are OpenSim's
// formula written out here; the ground-anchored length is the distance between the two points in the world.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/io/osim_model.hpp"
#include "sinew/io/osim_model_converter.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

// A file private to the running test, since ctest may run this file's tests in parallel.
std::string writeTestFile(const std::string& text) {
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sinew_osim_quirks";
    std::filesystem::create_directories(dir);
    const std::string path =
        (dir / (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".osim")).string();
    std::ofstream(path) << text;
    return path;
}

// A slider along x carrying body "a" (its inertia given), a pin on a carrying a massless welded body "tip"
// that is given inertia, and a muscle from a point on ground to a point on a.
std::string makeModel(const std::string& inertiaOfA) {
    return R"(<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="40000">
  <Model name="quirks">
    <Ground name="ground"/>
    <gravity>0 -9.81 0</gravity>
    <BodySet name="bodyset"><objects>
      <Body name="a"><mass>1.5</mass><mass_center>0.1 0 0</mass_center><inertia>)" +
           inertiaOfA + R"(</inertia></Body>
      <Body name="tip"><mass>0</mass><inertia>0.01 0.01 0.01 0 0 0</inertia></Body>
    </objects></BodySet>
    <JointSet name="jointset"><objects>
      <SliderJoint name="slide"><socket_parent_frame>/ground</socket_parent_frame><socket_child_frame>/bodyset/a</socket_child_frame>
        <coordinates><Coordinate name="x"><default_value>0.25</default_value></Coordinate></coordinates>
      </SliderJoint>
      <WeldJoint name="weld"><socket_parent_frame>/bodyset/a</socket_parent_frame><socket_child_frame>/bodyset/tip</socket_child_frame></WeldJoint>
    </objects></JointSet>
    <ForceSet name="forceset"><objects>
      <Thelen2003Muscle name="pull">
        <GeometryPath name="geometrypath"><PathPointSet><objects>
          <PathPoint name="p0"><socket_parent_frame>/ground</socket_parent_frame><location>-0.5 0.3 0.1</location></PathPoint>
          <PathPoint name="p1"><socket_parent_frame>/bodyset/a</socket_parent_frame><location>0.2 -0.1 0</location></PathPoint>
        </objects></PathPointSet></GeometryPath>
        <max_isometric_force>100</max_isometric_force><optimal_fiber_length>0.3</optimal_fiber_length><tendon_slack_length>0.2</tendon_slack_length>
      </Thelen2003Muscle>
    </objects></ForceSet>
  </Model>
</OpenSimDocument>
)";
}

int findLink(const Model& model, const std::string& name) {
    const std::vector<Link>& links = model.getLinks();
    const auto it = std::find_if(links.begin(), links.end(), [&](const Link& link) { return link.name == name; });
    EXPECT_NE(it, links.end()) << name;
    return static_cast<int>(it - links.begin());
}

bool hasLineWith(const std::vector<std::string>& lines, const std::string& a, const std::string& b) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& line) {
        return line.find(a) != std::string::npos && line.find(b) != std::string::npos;
    });
}

TEST(OsimQuirks, AnInertiaViolatingTheTriangleInequalityBecomesOpenSimsSphere) {
    // The toes of gait2354-era models: moments (0, 0, 0.00090462) fail the triangle inequality.
    const std::string path = writeTestFile(makeModel("0 0 0.00090462 0 0 0"));
    const OsimConversion conversion = convertOsimModel(readOsimModel(path));
    const Link& a = conversion.model.getLinks()[static_cast<std::size_t>(findLink(conversion.model, "a"))];
    const double sphere = std::sqrt(0.00090462 * 0.00090462) / std::sqrt(3.0);  // |diag| / sqrt(3), Body.cpp
    EXPECT_NEAR((a.inertia_Bcom - sphere * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 0, 1e-12);
    EXPECT_DOUBLE_EQ(a.mass, 1.5);
    EXPECT_TRUE(hasLineWith(conversion.warnings, "Body 'a' (" + path + ":", "reset to a sphere of moment 0.000522283"));
}

TEST(OsimQuirks, NegativeMomentsAndLargeProductsAreInvalidToo) {
    for (const std::string inertia : {"-0.01 0.02 0.02 0 0 0", "0.01 0.01 0.01 0.009 0 0"}) {
        const OsimConversion conversion = convertOsimModel(readOsimModel(writeTestFile(makeModel(inertia))));
        const Link& a = conversion.model.getLinks()[static_cast<std::size_t>(findLink(conversion.model, "a"))];
        std::istringstream values(inertia);
        Eigen::Vector3d moments;
        values >> moments[0] >> moments[1] >> moments[2];
        EXPECT_NEAR((a.inertia_Bcom - moments.norm() / std::sqrt(3.0) * Eigen::Matrix3d::Identity()).norm(), 0, 1e-12)
            << inertia;
        EXPECT_TRUE(hasLineWith(conversion.warnings, "Body 'a'", "invalid inertia")) << inertia;
    }
}

// A muscle's curve parameters are read whole: "0.6x" is no number (the C library's stod took its 0.6).
TEST(OsimQuirks, AMuscleParameterWithTrailingTextIsRefused) {
    std::string text = makeModel("0.01 0.02 0.025 0 0 0");
    const std::string end = "</tendon_slack_length>";
    text.insert(text.find(end) + end.size(), "<FmaxMuscleStrain>0.6x</FmaxMuscleStrain>");
    const std::string path = writeTestFile(text);
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(text.find("<Thelen2003Muscle")), '\n'));
    EXPECT_TRUE(test::throwsErrorAt([&] { convertOsimModel(readOsimModel(path)); }, path + ":" + std::to_string(line),
                                    {"muscle 'pull'", "FmaxMuscleStrain '0.6x' is not a number"}, text));
}

TEST(OsimQuirks, AValidInertiaIsKeptAsGiven) {
    const OsimConversion conversion = convertOsimModel(readOsimModel(writeTestFile(makeModel("0.01 0.02 0.025 0.001 0 0"))));
    const Link& a = conversion.model.getLinks()[static_cast<std::size_t>(findLink(conversion.model, "a"))];
    Eigen::Matrix3d expected;
    expected << 0.01, 0.001, 0, 0.001, 0.02, 0, 0, 0, 0.025;
    EXPECT_EQ(a.inertia_Bcom, expected);
    EXPECT_FALSE(hasLineWith(conversion.warnings, "Body 'a'", "inertia"));
}

TEST(OsimQuirks, AMasslessBodyGivenInertiaGetsNone) {
    const OsimConversion conversion = convertOsimModel(readOsimModel(writeTestFile(makeModel("0.01 0.02 0.025 0 0 0"))));
    const Link& tip = conversion.model.getLinks()[static_cast<std::size_t>(findLink(conversion.model, "tip"))];
    EXPECT_EQ(tip.mass, 0);
    EXPECT_TRUE(tip.inertia_Bcom.isZero(0));
    EXPECT_TRUE(hasLineWith(conversion.warnings, "Body 'tip'", "massless but with non-zero inertia"));
}

// A wrist as OpenSim models build one: a massless intermediate body between the flexion and deviation
// pins. OpenSim and Simbody take it (the hand beyond it keeps the system regular), and so does sinew: the
// body stays massless, on a joint of its own.
TEST(OsimQuirks, AMasslessIntermediateBodyIsKept) {
    const std::string path = writeTestFile(R"(<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="40000">
  <Model name="wrist">
    <Ground name="ground"/>
    <gravity>0 -9.81 0</gravity>
    <BodySet name="bodyset"><objects>
      <Body name="lunate"><mass>0</mass><inertia>0 0 0 0 0 0</inertia></Body>
      <Body name="hand"><mass>0.45</mass><mass_center>0.01 -0.07 0</mass_center><inertia>0.0009 0.0003 0.0008 0 0 0</inertia></Body>
    </objects></BodySet>
    <JointSet name="jointset"><objects>
      <PinJoint name="flexion"><socket_parent_frame>/ground</socket_parent_frame><socket_child_frame>/bodyset/lunate</socket_child_frame>
        <coordinates><Coordinate name="flex"/></coordinates>
      </PinJoint>
      <PinJoint name="deviation"><socket_parent_frame>/bodyset/lunate</socket_parent_frame><socket_child_frame>/bodyset/hand</socket_child_frame>
        <coordinates><Coordinate name="dev"/></coordinates>
      </PinJoint>
    </objects></JointSet>
  </Model>
</OpenSimDocument>
)");
    const Model model = loadModel(path, {});
    const Link& lunate = model.getLinks()[static_cast<std::size_t>(findLink(model, "lunate"))];
    EXPECT_EQ(lunate.mass, 0);
    EXPECT_TRUE(lunate.inertia_Bcom.isZero(0));
    EXPECT_EQ(model.getJoint(findLink(model, "lunate")).type, JointType::Custom);
    EXPECT_EQ(model.getNumU(), 2);
}

TEST(OsimQuirks, AMuscleAnchoredToGroundKeepsItsWorldPoint) {
    const std::string path = writeTestFile(makeModel("0.01 0.02 0.025 0 0 0"));
    std::vector<std::string> notes;
    const Model model = loadModel(path, [&](const std::string& line) { notes.push_back(line); });
    EXPECT_TRUE(hasLineWith(notes, "warning: Ground 'ground'", "'ground_anchor', a massless link welded to ground"));
    ASSERT_EQ(model.getNumWires(), 1);
    Data data(model);
    for (const double x : {0.25, -0.4, 1.3}) {
        Eigen::VectorXd q = model.getDefaultQ();
        q[0] = x;
        calcPositionKinematics(model, data, q);
        calcWirePaths(model, data);
        // The slider moves a's origin along ground's x; p1 rides on it, p0 stays in the world.
        const Eigen::Vector3d p0(-0.5, 0.3, 0.1), p1(0.2 + x, -0.1, 0);
        EXPECT_NEAR(data.wireLength[0], (p1 - p0).norm(), 1e-14) << "x = " << x;
    }
}

// OpenSim's own model collection (../shared/data/opensim-models): every .osim imports, point masses (the
// double pendulums' rods: mass, zero inertia) included.
// Each muscle type gets its own law where sinew has one (Millard's curves and DeGroote's, with their
// properties, an empty optional property left unset), and Thelen's with a warning naming it where not.
TEST(OsimQuirks, MuscleTypesKeepTheirOwnLaws) {
    const std::string thelen = makeModel("0.01 0.02 0.025 0 0 0");
    const auto convert = [&](const std::string& open, const std::string& extra, const std::string& close) {
        std::string text = thelen;
        text.replace(text.find("<Thelen2003Muscle name=\"pull\">"), 30, open);
        text.replace(text.find("</Thelen2003Muscle>"), 19, extra + close);
        return convertOsimModel(readOsimModel(writeTestFile(text)));
    };
    const OsimConversion millard = convert(
        "<Millard2012EquilibriumMuscle name=\"pull\">",
        "<fiber_damping>0.05</fiber_damping><ActiveForceLengthCurve><minimum_value>0</minimum_value></ActiveForceLengthCurve>"
        "<FiberForceLengthCurve><stiffness_at_one_norm_force></stiffness_at_one_norm_force></FiberForceLengthCurve>",
        "</Millard2012EquilibriumMuscle>");
    const ForceLawSpec& m = millard.model.getWire(0).lawSpec;
    EXPECT_EQ(m.type, "millard2012_muscle");
    EXPECT_EQ(m.parameters.getScalar("fiber_damping"), 0.05);
    EXPECT_EQ(m.parameters.getScalar("minimum_value"), 0);
    EXPECT_FALSE(m.parameters.has("stiffness_at_one_norm_force"));
    const OsimConversion deGroote = convert(
        "<DeGrooteFregly2016Muscle name=\"pull\">",
        "<active_force_width_scale>1.5</active_force_width_scale><ignore_passive_fiber_force>true</ignore_passive_fiber_force>",
        "</DeGrooteFregly2016Muscle>");
    const ForceLawSpec& d = deGroote.model.getWire(0).lawSpec;
    EXPECT_EQ(d.type, "degroote_fregly2016_muscle");
    EXPECT_EQ(d.parameters.getScalar("active_force_width_scale"), 1.5);
    EXPECT_EQ(d.parameters.getScalar("ignore_passive_fiber_force"), 1);
    EXPECT_FALSE(hasLineWith(deGroote.warnings, "DeGrooteFregly2016Muscle", "thelen"));
    const OsimConversion rigid = convert("<RigidTendonMuscle name=\"pull\">", "", "</RigidTendonMuscle>");
    EXPECT_EQ(rigid.model.getWire(0).lawSpec.type, "thelen2003_muscle");
    EXPECT_TRUE(hasLineWith(rigid.warnings, "RigidTendonMuscle 'pull'", "becomes thelen2003_muscle"));
}

TEST(OsimQuirks, OpenSimsModelCollectionImports) {
    const std::filesystem::path root = std::filesystem::path(SINEW_SHARED_DIR) / "data" / "opensim-models";
    if (!std::filesystem::exists(root)) GTEST_SKIP() << root << " is absent (it ships with ../shared only)";
    int imported = 0, files = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
        if (entry.path().extension() != ".osim") continue;
        ++files;
        const std::string path = entry.path().string();
        try {
            const Model model = loadModel(path, {});
            EXPECT_GT(model.getNumLinks(), 0) << path;
            ++imported;
        } catch (const Error& e) {
            ADD_FAILURE() << path << ": " << e.what();
        }
    }
    EXPECT_GT(files, 30);
    EXPECT_EQ(imported, files);
    std::cout << "imported " << imported << " of " << files << " OpenSim models\n";
}

}  // namespace
}  // namespace sinew

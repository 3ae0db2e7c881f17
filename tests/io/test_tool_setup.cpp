// Tool setups: the shipped inverse-dynamics and static-optimization setups read with the values their XML
// holds and every file they name resolved to an existing file; a force-set file; bad setups refused at
// their line.
#include <gtest/gtest.h>

#include <cmath>

#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/tool_setup.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

const std::string kOpenSimDir = std::string(SINEW_SHARED_DIR) + "/data/opensim";

TEST(ToolSetup, GaitInverseDynamics) {
    const std::string path = kOpenSimDir + "/gait2354/subject01_Setup_InverseDynamics.xml";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "OpenSim data not found at " << kOpenSimDir;
    const InverseDynamicsSetup setup = readInverseDynamicsSetup(path);
    EXPECT_EQ(setup.name, "subject01_walk1");
    for (const std::string& file : {setup.modelFile, setup.externalLoadsFile, setup.coordinatesFile})
        EXPECT_TRUE(std::filesystem::is_regular_file(file)) << file;
    EXPECT_EQ(std::filesystem::path(setup.modelFile).filename(), "subject01_simbody.osim");
    EXPECT_EQ(std::filesystem::path(setup.coordinatesFile).filename(), "subject01_walk1_ik.mot");
    EXPECT_EQ(setup.startTime, 0.4);
    EXPECT_EQ(setup.endTime, 1.6);
    EXPECT_EQ(setup.forcesToExclude, std::vector<std::string>{"Muscles"});
    EXPECT_EQ(setup.lowpassCutoffFrequencyForCoordinates, 6);
    EXPECT_EQ(setup.outputGenForceFile, "inverse_dynamics.sto");
    EXPECT_EQ(setup.resultsDirectory,
              (std::filesystem::path(kOpenSimDir) / "gait2354" / "ResultsInverseDynamics").lexically_normal());
    EXPECT_EQ(setup.inputDirectory, "");
    EXPECT_FALSE(setup.coordinatesInDegrees);
}

TEST(ToolSetup, Arm26InverseDynamicsAndStaticOptimization) {
    const std::string dir = kOpenSimDir + "/arm26";
    if (!std::filesystem::exists(dir)) GTEST_SKIP() << "OpenSim data not found at " << kOpenSimDir;
    const InverseDynamicsSetup id = readInverseDynamicsSetup(dir + "/arm26_Setup_InverseDynamics.xml");
    EXPECT_TRUE(std::filesystem::is_regular_file(id.modelFile));
    EXPECT_EQ(id.externalLoadsFile, "");
    ASSERT_TRUE(id.coordinatesInDegrees);
    EXPECT_TRUE(*id.coordinatesInDegrees);
    EXPECT_EQ(id.endTime, 1);

    const AnalyzeSetup so = readAnalyzeSetup(dir + "/arm26_Setup_StaticOptimization.xml");
    EXPECT_EQ(so.name, "arm26");
    EXPECT_TRUE(std::filesystem::is_regular_file(so.modelFile));
    EXPECT_TRUE(std::filesystem::is_regular_file(so.coordinatesFile));
    EXPECT_EQ(so.statesFile, "");
    EXPECT_EQ(so.speedsFile, "");
    EXPECT_FALSE(so.replaceForceSet);
    EXPECT_TRUE(so.forceSetFiles.empty());
    EXPECT_EQ(so.initialTime, 0);
    EXPECT_EQ(so.finalTime, 1);
    EXPECT_EQ(so.lowpassCutoffFrequencyForCoordinates, 6);
    EXPECT_EQ(so.outputPrecision, 8);
    EXPECT_TRUE(so.solveForEquilibriumForAuxiliaryStates);
    ASSERT_TRUE(so.staticOptimization);
    EXPECT_EQ(so.staticOptimization->activationExponent, 2);
    EXPECT_TRUE(so.staticOptimization->useMusclePhysiology);
    EXPECT_TRUE(so.staticOptimization->useModelForceSet);
    EXPECT_EQ(so.staticOptimization->stepInterval, 1);
    EXPECT_EQ(so.staticOptimization->endTime, 1);
    EXPECT_EQ(so.staticOptimization->optimizerConvergenceCriterion, 1e-4);  // OpenSim's default, absent here
    EXPECT_TRUE(so.unsupported.empty());
}

std::string writeSetup(const std::string& name, const std::string& text) {
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sinew_tool_setup";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / name) << text;
    return (dir / name).string();
}

TEST(ToolSetup, ForceSetFileAndAnalyzeToolReferencingIt) {
    const std::string forces = writeSetup("reserves.xml", R"(<OpenSimDocument Version="30000">
<ForceSet name="reserves"><objects>
  <CoordinateActuator name="r_elbow_reserve"><coordinate>r_elbow_flex</coordinate><optimal_force>1</optimal_force>
    <min_control>-Infinity</min_control><max_control>Infinity</max_control></CoordinateActuator>
  <PointActuator name="FX"><body>pelvis</body><point>0 0.1 0</point><direction>1 0 0</direction><force_is_global>true</force_is_global><optimal_force>2</optimal_force></PointActuator>
  <TorqueActuator name="MZ"><bodyA>pelvis</bodyA><bodyB>ground</bodyB><axis>0 0 1</axis><optimal_force>3</optimal_force><max_control>5</max_control></TorqueActuator>
  <SpringGeneralizedForce name="spring"/>
</objects></ForceSet></OpenSimDocument>
)");
    const OsimForceSet set = readForceSetFile(forces);
    ASSERT_EQ(set.coordinateActuators.size(), 1u);
    EXPECT_EQ(set.coordinateActuators[0].coordinate, "r_elbow_flex");
    EXPECT_EQ(set.coordinateActuators[0].limits.minControl, -INFINITY);
    ASSERT_EQ(set.pointActuators.size(), 1u);
    EXPECT_TRUE(set.pointActuators[0].forceIsGlobal);
    EXPECT_FALSE(set.pointActuators[0].pointIsGlobal);
    EXPECT_EQ(set.pointActuators[0].point, Eigen::Vector3d(0, 0.1, 0));
    ASSERT_EQ(set.torqueActuators.size(), 1u);
    EXPECT_EQ(set.torqueActuators[0].limits.optimalForce, 3);
    EXPECT_EQ(set.torqueActuators[0].limits.maxControl, 5);
    EXPECT_EQ(set.torqueActuators[0].limits.minControl, -INFINITY);
    ASSERT_EQ(set.unsupported.size(), 1u);
    EXPECT_EQ(set.unsupported[0].where, forces + ":7");

    const std::string setup = writeSetup("analyze.xml", R"(<OpenSimDocument Version="30000">
<AnalyzeTool name="run">
  <model_file>models/arm.osim</model_file>
  <force_set_files>reserves.xml other/residuals.xml</force_set_files>
  <states_file>states.sto</states_file>
  <AnalysisSet name="Analyses"><objects><Kinematics name="kin"/></objects></AnalysisSet>
</AnalyzeTool></OpenSimDocument>
)");
    const AnalyzeSetup analyze = readAnalyzeSetup(setup);
    const std::filesystem::path dir = std::filesystem::path(setup).parent_path();
    EXPECT_EQ(analyze.forceSetFiles, (std::vector<std::string>{forces, (dir / "other" / "residuals.xml").string()}));
    EXPECT_EQ(analyze.modelFile, (dir / "models" / "arm.osim").string());
    EXPECT_TRUE(analyze.replaceForceSet);  // OpenSim's default
    EXPECT_FALSE(analyze.staticOptimization);
    ASSERT_EQ(analyze.unsupported.size(), 1u);
    EXPECT_EQ(analyze.unsupported[0].type, "Kinematics");
}

// The tool is the document's object, not any text in the file: an AnalyzeTool whose comment mentions an
// InverseDynamicsTool is an AnalyzeTool; a tool sinew does not run is refused at its line.
TEST(ToolSetup, ToolTypeIsTheDocumentsObject) {
    const std::string analyze = writeSetup("analyze_with_comment.xml", R"(<OpenSimDocument Version="40000">
<!-- made from <InverseDynamicsTool> results -->
<AnalyzeTool name="so"><model_file>m.osim</model_file><coordinates_file>q.mot</coordinates_file></AnalyzeTool>
</OpenSimDocument>
)");
    const ToolSetup analyzeSetup = readToolSetup(analyze);
    ASSERT_TRUE(std::holds_alternative<AnalyzeSetup>(analyzeSetup));
    EXPECT_EQ(std::get<AnalyzeSetup>(analyzeSetup).name, "so");
    const std::string id = writeSetup("id_type.xml", R"(<OpenSimDocument Version="40000">
<InverseDynamicsTool name="id"><model_file>m.osim</model_file><coordinates_file>q.mot</coordinates_file>
</InverseDynamicsTool></OpenSimDocument>
)");
    const ToolSetup idSetup = readToolSetup(id);
    ASSERT_TRUE(std::holds_alternative<InverseDynamicsSetup>(idSetup));
    EXPECT_EQ(std::get<InverseDynamicsSetup>(idSetup).name, "id");
    const std::string scale = writeSetup("scale.xml", R"(<OpenSimDocument Version="40000">

<ScaleTool name="subject"/></OpenSimDocument>
)");
    EXPECT_TRUE(test::throwsErrorAt([&] { readToolSetup(scale); }, scale + ":3: ",
                                    {"ScaleTool", "InverseDynamicsTool, InverseKinematicsTool or AnalyzeTool"}, "a ScaleTool setup"));
}

// OpenSim 3's IK setup layout (Gait10dof18musc's): tasks with apply and weight, an Unassigned coordinate file.
TEST(ToolSetup, InverseKinematicsTool) {
    const std::string path = writeSetup("ik.xml", R"(<OpenSimDocument Version="30000">
<InverseKinematicsTool name="walk">
<model_file> ../subject01.osim </model_file>
<constraint_weight>Inf</constraint_weight>
<accuracy>1e-005</accuracy>
<IKTaskSet><objects>
<IKMarkerTask name="Sternum"><apply>true</apply><weight>1</weight></IKMarkerTask>
<IKMarkerTask name="R.Knee.Lat"><apply>false</apply><weight>1</weight></IKMarkerTask>
<IKCoordinateTask name="knee_angle_r"><apply>true</apply><weight>5</weight><value_type>manual_value</value_type><value>0.2</value></IKCoordinateTask>
</objects><groups /></IKTaskSet>
<marker_file>walk.trc</marker_file>
<coordinate_file>Unassigned</coordinate_file>
<time_range> 0 2.5</time_range>
<output_motion_file>walk_IK.mot</output_motion_file>
</InverseKinematicsTool></OpenSimDocument>
)");
    const ToolSetup tool = readToolSetup(path);
    ASSERT_TRUE(std::holds_alternative<InverseKinematicsSetup>(tool));
    const InverseKinematicsSetup& setup = std::get<InverseKinematicsSetup>(tool);
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    EXPECT_EQ(setup.modelFile, (folder / "../subject01.osim").lexically_normal().string());
    EXPECT_EQ(setup.markerFile, (folder / "walk.trc").string());
    EXPECT_TRUE(setup.coordinateFile.empty());
    EXPECT_EQ(setup.accuracy, 1e-5);
    EXPECT_TRUE(std::isinf(setup.constraintWeight));
    EXPECT_EQ(setup.startTime, 0);
    EXPECT_EQ(setup.endTime, 2.5);
    ASSERT_EQ(setup.markerTasks.size(), 2u);
    EXPECT_FALSE(setup.markerTasks[1].apply);
    ASSERT_EQ(setup.coordinateTasks.size(), 1u);
    EXPECT_EQ(setup.coordinateTasks[0].valueType, "manual_value");
    EXPECT_EQ(setup.coordinateTasks[0].value, 0.2);
    EXPECT_EQ(setup.coordinateTasks[0].weight, 5);
    EXPECT_EQ(setup.outputMotionFile, "walk_IK.mot");
    const std::string bad = writeSetup("ik_bad.xml", R"(<OpenSimDocument Version="40000">
<InverseKinematicsTool name="walk"><model_file>m.osim</model_file><marker_file>w.trc</marker_file>
<IKTaskSet><objects>
<IKCoordinateTask name="knee"><value_type>guess</value_type></IKCoordinateTask>
</objects></IKTaskSet></InverseKinematicsTool></OpenSimDocument>
)");
    EXPECT_TRUE(test::throwsErrorAt([&] { readToolSetup(bad); }, bad + ":4: ", {"value_type 'guess'"}, "a bad value_type"));
    const std::string noMarkers = writeSetup("ik_no_markers.xml", R"(<OpenSimDocument Version="40000">
<InverseKinematicsTool name="walk"><model_file>m.osim</model_file></InverseKinematicsTool></OpenSimDocument>
)");
    EXPECT_TRUE(test::throwsErrorAt([&] { readToolSetup(noMarkers); }, noMarkers + ":2: ", {"marker_file"}, "no marker file"));
}

TEST(ToolSetup, BadSetups) {
    const std::string reversed = writeSetup("reversed.xml", R"(<OpenSimDocument Version="30000">
<InverseDynamicsTool name="id">
  <model_file>m.osim</model_file><coordinates_file>q.mot</coordinates_file>
  <time_range>2 1</time_range>
</InverseDynamicsTool></OpenSimDocument>
)");
    EXPECT_TRUE(test::throwsErrorAt([&] { readInverseDynamicsSetup(reversed); }, reversed + ":4: ",
                                    {"<time_range>", "starts at 2", "after its end"}, ""));
    EXPECT_TRUE(test::throwsErrorAt([&] { readAnalyzeSetup(reversed); }, reversed + ":1: ",
                                    {"<OpenSimDocument>", "holds no <AnalyzeTool>"}, ""));
    const std::string noMotion = writeSetup("no_motion.xml", R"(<OpenSimDocument Version="30000">
<AnalyzeTool name="so"><model_file>m.osim</model_file><coordinates_file> </coordinates_file>
  <AnalysisSet><objects><StaticOptimization name="so"><activation_exponent>0</activation_exponent></StaticOptimization></objects></AnalysisSet>
</AnalyzeTool></OpenSimDocument>
)");
    EXPECT_TRUE(test::throwsErrorAt([&] { readAnalyzeSetup(noMotion); }, noMotion + ":2: ",
                                    {"<AnalyzeTool name='so'>", "no motion"}, ""));
    const std::string noModel = writeSetup("no_model.xml", R"(<OpenSimDocument Version="30000">
<InverseDynamicsTool name="id"><coordinates_file>q.mot</coordinates_file></InverseDynamicsTool></OpenSimDocument>
)");
    EXPECT_TRUE(test::throwsErrorAt([&] { readInverseDynamicsSetup(noModel); }, noModel + ":2: ",
                                    {"missing <model_file>"}, ""));
}

}  // namespace
}  // namespace sinew

// ExternalLoads files: the gait example's ground reactions resolve to the data file's columns (checked by
// label), the bodies are checked against the model, and bad identifiers or files fail at their line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/external_loads.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

const std::string kGaitDir = std::string(SINEW_SHARED_DIR) + "/data/opensim/gait2354";

std::vector<std::string> labels(const ExternalLoads& loads, const std::array<int, 3>& columns) {
    std::vector<std::string> names;
    for (int c : columns) names.push_back(c < 0 ? "-" : loads.data.columns[c]);
    return names;
}

TEST(ExternalLoads, GaitGroundReactions) {
    const std::string path = kGaitDir + "/subject01_walk1_grf.xml";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "OpenSim data not found at " << kGaitDir;
    const ExternalLoads loads = readExternalLoads(path);
    EXPECT_EQ(loads.name, "Ex2");
    EXPECT_EQ(loads.dataFile, (std::filesystem::path(kGaitDir) / "subject01_walk1_grf.mot").lexically_normal());
    EXPECT_EQ(loads.data.rows.size(), 1501u);
    EXPECT_EQ(loads.lowpassCutoffFrequencyForLoadKinematics, -1);
    ASSERT_EQ(loads.forces.size(), 2u);
    const ExternalForce& right = loads.forces[0];
    EXPECT_EQ(right.name, "right");
    EXPECT_TRUE(right.appliesForce);
    EXPECT_EQ(right.appliedToBody, "calcn_r");
    EXPECT_EQ(right.forceExpressedInBody, "ground");
    EXPECT_EQ(right.dataSourceName, "Unassigned");
    EXPECT_EQ(labels(loads, right.forceColumns),
              (std::vector<std::string>{"ground_force_vx", "ground_force_vy", "ground_force_vz"}));
    EXPECT_EQ(labels(loads, right.pointColumns),
              (std::vector<std::string>{"ground_force_px", "ground_force_py", "ground_force_pz"}));
    EXPECT_EQ(labels(loads, right.torqueColumns),
              (std::vector<std::string>{"ground_torque_x", "ground_torque_y", "ground_torque_z"}));
    EXPECT_EQ(labels(loads, loads.forces[1].forceColumns),
              (std::vector<std::string>{"1_ground_force_vx", "1_ground_force_vy", "1_ground_force_vz"}));
    EXPECT_EQ(loads.forces[1].appliedToBody, "calcn_l");

    // The right foot's vertical force in the first row, as the file's first data line has it.
    EXPECT_EQ(loads.data.rows[0][right.forceColumns[1]], 745.4661142);

    checkExternalLoadsBodies(loads, readOsimModel(kGaitDir + "/subject01_simbody.osim"));
    const std::string arm = kGaitDir + "/../arm26/arm26.osim";
    EXPECT_TRUE(test::throwsErrorAt([&] { checkExternalLoadsBodies(loads, readOsimModel(arm)); }, path + ":5: ",
                                    {"'right'", "'calcn_r'", "arm26.osim"}, ""));
}

// Writes a data file and an ExternalLoads file next to it, with one force whose lines are given.
std::string writeLoads(const std::string& force, const std::string& datafile = "loads.mot") {
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sinew_external_loads" /
                                      ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "loads.mot") << "loads\nendheader\ntime\tF_x\tF_y\tF_z\tP_x\tP_y\tT_x\tT_y\tT_z\n"
                                     << "0\t1\t2\t3\t4\t5\t6\t7\t8\n";
    const std::string path = (dir / "loads.xml").string();
    std::ofstream(path) << "<OpenSimDocument Version=\"40000\">\n<ExternalLoads name=\"loads\">\n<objects>\n"
                           "<ExternalForce name=\"push\">\n<applied_to_body>b</applied_to_body>\n"
                        << force << "</ExternalForce>\n</objects>\n<datafile>" << datafile
                        << "</datafile>\n</ExternalLoads>\n</OpenSimDocument>\n";
    return path;
}

TEST(ExternalLoads, TorqueOnlyForce) {
    const ExternalLoads loads = readExternalLoads(writeLoads("<torque_identifier>T_</torque_identifier>\n"));
    EXPECT_EQ(labels(loads, loads.forces[0].torqueColumns), (std::vector<std::string>{"T_x", "T_y", "T_z"}));
    EXPECT_EQ(loads.forces[0].forceColumns, (std::array<int, 3>{-1, -1, -1}));
}

TEST(ExternalLoads, IdentifierMustNameThreeColumns) {
    const std::string path =
        writeLoads("<force_identifier>F_</force_identifier>\n<point_identifier>P_</point_identifier>\n");
    EXPECT_TRUE(test::throwsErrorAt([&] { readExternalLoads(path); }, path + ":7: ",
                                    {"<point_identifier>", "'P_' starts 2 column labels", "P_x, P_y", "exactly 3"}, ""));
}

TEST(ExternalLoads, ForceOrTorqueRequired) {
    const std::string path = writeLoads("<point_identifier>P_</point_identifier>\n");
    EXPECT_TRUE(test::throwsErrorAt([&] { readExternalLoads(path); }, path + ":4: ",
                                    {"<ExternalForce name='push'>", "neither a force nor a torque"}, ""));
}

TEST(ExternalLoads, MissingDataFile) {
    const std::string path = writeLoads("<force_identifier>F_</force_identifier>\n", "nothing.mot");
    const std::string data = (std::filesystem::path(path).parent_path() / "nothing.mot").string();
    EXPECT_TRUE(test::throwsErrorAt([&] { readExternalLoads(path); }, data + ": ", {"cannot open"}, ""));
    const std::string none = writeLoads("<force_identifier>F_</force_identifier>\n", "");
    EXPECT_TRUE(test::throwsErrorAt([&] { readExternalLoads(none); }, none + ":2: ", {"missing <datafile>"}, ""));
}

}  // namespace
}  // namespace sinew

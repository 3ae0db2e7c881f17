// OpenSim models imported, written as sinew model files and read back give bit-identical wire Jacobians
// and inverse dynamics; motion tables with the wrong columns are refused by name.
#include <gtest/gtest.h>

#include <filesystem>

#include "sinew/core/data.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/osim_model_converter.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tools/inverse_dynamics_tool.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

const std::filesystem::path kOpenSimData = std::filesystem::path(SINEW_SHARED_DIR) / "data" / "opensim";

Eigen::MatrixXd calcJacobianAt(const Model& model, const Eigen::VectorXd& q) {
    Data data(model);
    calcPositionKinematics(model, data, q);
    calcWirePaths(model, data);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    calcWireJacobian(model, data, J);
    return J;
}

void checkRoundTrip(const std::string& osim, const std::string& motion) {
    const Model imported = convertOsimModel(readOsimModel((kOpenSimData / osim).string())).model;
    const std::string text = writeModelText(imported);
    const Model reloaded = readModelText(text, "round trip of " + osim);
    EXPECT_EQ(writeModelText(reloaded), text);
    for (const double shift : {0.0, 0.3, -0.4}) {
        const Eigen::VectorXd q = imported.getDefaultQ().array() + shift;
        const Eigen::MatrixXd J = calcJacobianAt(imported, q);
        EXPECT_TRUE(J == calcJacobianAt(reloaded, q)) << osim << " at default pose + " << shift;
        EXPECT_GT(J.cwiseAbs().maxCoeff(), 0);
    }
    const StorageTable table = readStorageFile((kOpenSimData / motion).string());
    InverseDynamicsOptions options;
    options.lowpassCutoffHz = 6;
    const StorageTable a = runInverseDynamics(imported, table, nullptr, options);
    const StorageTable b = runInverseDynamics(reloaded, table, nullptr, options);
    EXPECT_EQ(a.columns, b.columns);
    EXPECT_EQ(a.times, b.times);
    EXPECT_EQ(a.rows, b.rows);
}

TEST(OsimImportRoundTrip, Arm26JacobianAndInverseDynamicsIdentical) {
    if (!std::filesystem::exists(kOpenSimData / "arm26")) GTEST_SKIP() << "../shared/data/opensim/arm26 is absent";
    checkRoundTrip("arm26/arm26.osim", "arm26/arm26_InverseKinematics.mot");
}

TEST(OsimImportRoundTrip, Gait2354JacobianAndInverseDynamicsIdentical) {
    if (!std::filesystem::exists(kOpenSimData / "gait2354")) GTEST_SKIP() << "../shared/data/opensim/gait2354 is absent";
    checkRoundTrip("gait2354/subject01_simbody.osim", "gait2354/subject01_walk1_ik.mot");
}

// Built here, so it runs everywhere: a two-coordinate arm and motion tables that do not fit it.
TEST(InverseDynamicsMotion, ColumnMismatchNamesTheColumns) {
    const Model model = readModelText(R"(sinew_model: 1
name: arm
links:
  - {name: upper, mass: 2, com: [0, -0.15, 0], inertia: [0.02, 0.002, 0.02, 0, 0, 0]}
  - {name: lower, mass: 1, com: [0, -0.12, 0], inertia: [0.01, 0.001, 0.01, 0, 0, 0]}
joints:
  - {name: shoulder, type: pin, parent: ground, child: upper, axis: [0, 0, 1]}
  - {name: elbow, type: pin, parent: upper, child: lower, parent_point: [0, -0.3, 0], axis: [0, 0, 1]}
)", "arm.yaml");
    StorageTable table{"motion", true, {"shoulder", "wrist"}, {0, 0.01, 0.02, 0.03, 0.04, 0.05, 0.06}, {}};
    for (std::size_t r = 0; r < table.times.size(); ++r) table.rows.push_back({1.0 * static_cast<double>(r), 2.0});
    table.where = "motion.mot:7";
    EXPECT_TRUE(test::throwsErrorAt([&] { runInverseDynamics(model, table, nullptr, {}); }, "motion.mot:7",
                                    {"elbow", "wrist"}, "columns shoulder, wrist"));
    table.columns = {"shoulder", "elbow"};
    const StorageTable result = runInverseDynamics(model, table, nullptr, {});
    EXPECT_EQ(result.columns, (std::vector<std::string>{"shoulder_moment", "elbow_moment"}));
}

}  // namespace
}  // namespace sinew

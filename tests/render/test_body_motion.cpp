// Frames from motion and tension tables: tensions taken from the table's row at the motion's time, or from
// the force laws with speeds by differences (against core's speeds at the same rate); bad tables and
// frames refused with messages that name the file and the column or frame.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/render/body_motion.hpp"
#include "two_wire_model.hpp"

namespace sinew {
namespace {

std::string writeTable(const std::string& name, const std::vector<std::string>& columns,
                       const std::vector<double>& times, const std::vector<std::vector<double>>& rows) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sinew_test_body_motion";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / name).string();
    writeStorageFile(StorageTable{name, false, columns, times, rows}, path);
    return path;
}

template <class F>
std::string messageOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

void expectContains(const std::string& text, const std::string& part) {
    EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

TEST(BodyMotion, TensionsFromTheTableRowAtTheMotionsTime) {
    const Model model = test::makeTwoWireModel();
    const std::string q = writeTable("q.sto", {"hinge"}, {0.0, 0.1, 0.2}, {{0.0}, {0.2}, {0.4}});
    const std::string f = writeTable("f.sto", {"loaded", "slack"}, {0.1, 0.2}, {{11.0, 1.0}, {22.0, 2.0}});
    const PoseTable motion = readPoseTable(model, q);
    const TensionTable tensions = readTensionTable(model, f);
    const std::vector<BodyFrame> frames = calcBodyFrames(model, &motion, &tensions, {2});
    EXPECT_EQ(frames[0].time, 0.2);
    EXPECT_EQ(frames[0].wires[0].tension, 2.0);   // slack, by column name
    EXPECT_EQ(frames[0].wires[1].tension, 22.0);  // loaded
    // Row 0 (t = 0) has no tensions row.
    const std::string message = messageOf([&] { calcBodyFrames(model, &motion, &tensions, {0}); });
    expectContains(message, f + ": no row at t = 0 s, the time of frame 0 of " + q);
}

// Without tensions, the spring-dampers at the row's length and a speed by central differences: for a
// constant hinge rate the difference over +-0.01 s is core's speed at that rate to O(dt^2).
TEST(BodyMotion, TensionsFromTheForceLawsWithDifferencedSpeeds) {
    const Model model = test::makeTwoWireModel();
    const double rate = 2.0, dt = 0.01;
    const std::string q = writeTable("q_rate.sto", {"hinge"}, {0.0, dt, 2 * dt}, {{0.3}, {0.3 + rate * dt}, {0.3 + 2 * rate * dt}});
    const PoseTable motion = readPoseTable(model, q);
    const std::vector<BodyFrame> frames = calcBodyFrames(model, &motion, nullptr, {1});

    Data data(model);
    calcPositionKinematics(model, data, Eigen::VectorXd::Constant(1, 0.3 + rate * dt));
    calcVelocityKinematics(model, data, Eigen::VectorXd::Constant(1, rate));
    calcWirePaths(model, data);
    calcWireSpeeds(model, data);
    const double expected = 1000 * (data.wireLength[1] - 0.25) + 10 * data.wireSpeed[1];
    EXPECT_GT(std::abs(data.wireSpeed[1]), 0.05);
    EXPECT_NEAR(frames[0].wires[1].tension, expected, 10 * 1e-3);
}

TEST(BodyMotion, TensionColumnsMustBeTheModelsWires) {
    const Model model = test::makeTwoWireModel();
    const std::string f = writeTable("f_bad.sto", {"slack", "bogus"}, {0.0}, {{1.0, 2.0}});
    const std::string message = messageOf([&] { readTensionTable(model, f); });
    expectContains(message, f);
    expectContains(message, "missing 'loaded'");
    expectContains(message, "not expected 'bogus'");
}

TEST(BodyMotion, NegativeTensionNamesRowAndColumn) {
    const Model model = test::makeTwoWireModel();
    const std::string f = writeTable("f_negative.sto", {"slack", "loaded"}, {0.0, 0.5}, {{1.0, 2.0}, {1.0, -3.0}});
    expectContains(messageOf([&] { readTensionTable(model, f); }), f + ": row 1 (t = 0.5 s), column 'loaded'");
}

TEST(BodyMotion, MotionColumnsMustBeTheModelsCoordinates) {
    const Model model = test::makeTwoWireModel();
    const std::string q = writeTable("q_bad.sto", {"knee"}, {0.0}, {{0.1}});
    const std::string message = messageOf([&] { readPoseTable(model, q); });
    expectContains(message, q);
    expectContains(message, "missing 'hinge'");
}

TEST(BodyMotion, FramesOutOfRange) {
    const Eigen::Vector3d times(0.0, 0.5, 1.0);
    EXPECT_EQ(findFrame(times, 2, "m.sto"), 2);
    EXPECT_EQ(messageOf([&] { findFrame(times, 3, "m.sto"); }), "frame 3 is out of range: m.sto has 3 frames (0 to 2)");
    EXPECT_EQ(messageOf([&] { findFrame(times, -1, "m.sto"); }), "frame -1 is out of range: m.sto has 3 frames (0 to 2)");
    EXPECT_EQ(findFrameAtTime(times, 0.7, "m.sto"), 1);
    EXPECT_EQ(messageOf([&] { findFrameAtTime(times, 1.5, "m.sto"); }), "time 1.5 s is out of range: m.sto spans 0 to 1 s");
    EXPECT_EQ(selectStripFrames(times, 2, "m.sto"), (std::vector<int>{0, 2}));
    expectContains(messageOf([&] { selectStripFrames(times, 4, "m.sto"); }), "--strip 4: m.sto has 3 frames");
}

}  // namespace
}  // namespace sinew

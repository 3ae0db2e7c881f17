// sinew's inverse dynamics tool against OpenSim 4.4.1's results on OpenSim's own examples
// (../shared/data/opensim, see its README), through the unchanged OpenSim setup files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>

#include "sinew/core/forward_simulation.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/inverse_dynamics_tool.hpp"
#include "support/error_assertions.hpp"
#include "support/force_element_model.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

const std::filesystem::path kOpenSimData = std::filesystem::path(SINEW_SHARED_DIR) / "data" / "opensim";

double interpolate(const StorageTable& table, std::size_t column, double t) {
    const auto& times = table.times;
    if (t <= times.front()) return table.rows.front()[column];
    if (t >= times.back()) return table.rows.back()[column];
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
    const double s = (t - times[i - 1]) / (times[i] - times[i - 1]);
    return (1 - s) * table.rows[i - 1][column] + s * table.rows[i][column];
}

// Runs the setup and returns, per reference column, the RMS difference of sinew's output from the
// reference interpolated onto sinew's times; prints the table docs/validation.md quotes.
std::vector<std::pair<std::string, double>> runAndCompare(const std::string& example,
                                                          const std::filesystem::path& setupPath,
                                                          const std::filesystem::path& referencePath) {
    const InverseDynamicsSetup setup = readInverseDynamicsSetup(setupPath.string());
    const std::string output = (std::filesystem::path(::testing::TempDir()) / ("sinew_id_" + example)).string();
    const std::string written = runInverseDynamicsTool(setup, output, {});
    const StorageTable ours = readStorageFile(written);
    const StorageTable reference = readStorageFile(referencePath.string());
    EXPECT_GT(ours.times.size(), 10u);
    std::vector<std::pair<std::string, double>> rms;
    for (std::size_t c = 0; c < reference.columns.size(); ++c) {
        const auto it = std::find(ours.columns.begin(), ours.columns.end(), reference.columns[c]);
        if (it == ours.columns.end()) {
            ADD_FAILURE() << "sinew's output lacks OpenSim's column " << reference.columns[c];
            continue;
        }
        const std::size_t k = static_cast<std::size_t>(it - ours.columns.begin());
        double sum = 0;
        for (std::size_t r = 0; r < ours.times.size(); ++r) {
            const double d = ours.rows[r][k] - interpolate(reference, c, ours.times[r]);
            sum += d * d;
        }
        rms.emplace_back(reference.columns[c], std::sqrt(sum / static_cast<double>(ours.times.size())));
    }
    std::cout << example << ": RMS difference from OpenSim's (" << ours.times.size() << " frames)\n";
    for (const auto& [name, value] : rms) std::cout << "  " << std::setw(28) << std::left << name << value << "\n";
    return rms;
}

bool contains(const std::vector<std::string>& notes, const std::vector<std::string>& words) {
    return std::any_of(notes.begin(), notes.end(), [&](const std::string& note) {
        return std::all_of(words.begin(), words.end(), [&](const std::string& w) { return note.find(w) != std::string::npos; });
    });
}

// OpenSim's tools hold a coordinate missing from the motion at its default value and do not read columns
// that are no coordinate. arm26's elbow left out of a degrees table that has a column too many: the same
// generalized forces as the table written out by hand with the elbow at its default (60 degrees), and a
// note for each.
TEST(InverseDynamicsTool, AMissingCoordinateIsHeldAtItsDefaultAndAnExtraColumnIsNotRead) {
    const Model model = test::loadArm26().model;
    const std::vector<std::string> names = getCoordinateNames(model);
    StorageTable partial, byHand;
    partial.inDegrees = byHand.inDegrees = true;
    partial.columns = {"r_shoulder_qw", "r_shoulder_qx", "r_shoulder_qy", "r_shoulder_qz", "marker_x"};
    byHand.columns = names;
    for (int r = 0; r <= 50; ++r) {
        const double t = 0.02 * r, a = 0.3 * std::sin(3 * t);
        partial.times.push_back(t);
        byHand.times.push_back(t);
        partial.rows.push_back({std::cos(a), 0.0, 0.0, std::sin(a), 7.0});
        std::vector<double> row(names.size());
        for (std::size_t c = 0; c < names.size(); ++c) {
            if (names[c] == "r_shoulder_qw") row[c] = std::cos(a);
            else if (names[c] == "r_shoulder_qz") row[c] = std::sin(a);
            else if (names[c] == "r_elbow") row[c] = 60;  // its default, 1.0471975511965976 rad, in degrees
        }
        byHand.rows.push_back(row);
    }
    ASSERT_EQ(names.size(), 5u);
    std::vector<std::string> notes;
    const StorageTable completed = completeCoordinateTable(model, partial, [&](const std::string& n) { notes.push_back(n); });
    EXPECT_TRUE(contains(notes, {"'r_elbow'", "default value 1.047"}));
    EXPECT_TRUE(contains(notes, {"'marker_x'", "not read"}));
    const StorageTable ours = runInverseDynamics(model, completed, nullptr, {});
    const StorageTable reference = runInverseDynamics(model, byHand, nullptr, {});
    ASSERT_EQ(ours.rows.size(), reference.rows.size());
    for (std::size_t r = 0; r < ours.rows.size(); ++r)
        for (std::size_t c = 0; c < ours.columns.size(); ++c)
            EXPECT_NEAR(ours.rows[r][c], reference.rows[r][c], 1e-12 * (1 + std::abs(reference.rows[r][c])));
}

// The tool reads the model and the motion files at once; when more than one is bad, the error is the one
// reading them in turn would give: the model's first, then the external loads', then the coordinates'.
TEST(InverseDynamicsTool, FilesReadAtOnceReportTheFirstBadOneInTurn) {
    const std::string folder = ::testing::TempDir();
    InverseDynamicsSetup setup;
    setup.modelFile = folder + "/no_such_model.osim";
    setup.externalLoadsFile = folder + "/no_such_loads.xml";
    setup.coordinatesFile = folder + "/no_such_motion.mot";
    const std::string output = folder + "/sinew_id_bad_files";
    auto run = [&] { runInverseDynamicsTool(setup, output, {}); };
    EXPECT_TRUE(test::throwsErrorAt(run, setup.modelFile + ":", {"cannot"}, "all three files missing"));
    setup.modelFile = test::sourcePath("models/arm26.yaml");
    EXPECT_TRUE(test::throwsErrorAt(run, setup.externalLoadsFile + ":", {"cannot"}, "loads and motion missing"));
    setup.externalLoadsFile.clear();
    EXPECT_TRUE(test::throwsErrorAt(run, setup.coordinatesFile + ":", {"cannot"}, "the motion missing"));
    EXPECT_FALSE(std::filesystem::exists(output));
}

// A sinusoidal arm26 motion with every coordinate, in degrees.
StorageTable makeArm26Motion(const Model& model, int rows) {
    StorageTable table;
    table.inDegrees = true;
    table.columns = getCoordinateNames(model);
    for (int r = 0; r < rows; ++r) {
        const double t = 0.02 * r, a = 0.3 * std::sin(3 * t);
        table.times.push_back(t);
        std::vector<double> row(table.columns.size());
        for (std::size_t c = 0; c < row.size(); ++c) {
            if (table.columns[c] == "r_shoulder_qw") row[c] = std::cos(a);
            else if (table.columns[c] == "r_shoulder_qz") row[c] = std::sin(a);
            else if (table.columns[c] == "r_elbow") row[c] = 60 + 20 * std::sin(2 * t);
        }
        table.rows.push_back(row);
    }
    return table;
}

// The frames run in two halves on two threads; progress still starts at the first frame, only rises, and
// ends at the last, which is what `sinew inverse-dynamics` times its first frame and the rest by.
TEST(InverseDynamics, ProgressRisesFromTheFirstFrameToTheLast) {
    const Model model = test::loadArm26().model;
    const StorageTable motion = makeArm26Motion(model, 51);
    std::vector<std::pair<int, int>> calls;
    InverseDynamicsOptions options;
    options.onFrame = [&](int frame, int frames) { calls.emplace_back(frame, frames); };
    const StorageTable result = runInverseDynamics(model, motion, nullptr, options);
    ASSERT_EQ(result.rows.size(), 51u);
    ASSERT_FALSE(calls.empty());
    EXPECT_EQ(calls.front().first, 1);
    EXPECT_EQ(calls.back().first, 51);
    for (std::size_t i = 0; i < calls.size(); ++i) {
        EXPECT_EQ(calls[i].second, 51);
        if (i > 0) {
            EXPECT_GT(calls[i].first, calls[i - 1].first);
        }
    }
}

// The coordinates' columns are processed in two halves side by side; with a bad value in each half, the
// error is still the first bad row of the whole table, as processing it whole reports.
TEST(InverseDynamics, BadValuesInBothHalvesReportTheFirstBadRow) {
    const Model model = test::loadArm26().model;
    const StorageTable motion = makeArm26Motion(model, 51);
    CoordinateSamples samples = readCoordinateSamples(model, motion);
    const Eigen::Index last = samples.q.cols() - 1;
    samples.q(9, 0) = std::numeric_limits<double>::quiet_NaN();
    samples.q(2, last) = std::numeric_limits<double>::infinity();
    EXPECT_TRUE(test::throwsErrorAt([&] { preprocessCoordinateSamples(model, samples, 6, 0, 1); }, "coordinate preprocessing: row 2",
                                    {getCoordinateNames(model)[static_cast<std::size_t>(last)], "not finite"},
                                    "bad values at (row 9, column 0) and (row 2, the last column)"));
}

// The ID tool processes the coordinates' table while it reads the model (preprocessMotionTable), taking
// from it what the model's samples need: bit for bit what processing the samples gives. gait2354's table in
// degrees, with a column the model does not read and a coordinate left out: the translations and the
// missing coordinate are processed again, the angles taken. A bad value in the unread column fails the
// early processing, which the samples then do not need.
TEST(InverseDynamics, ATableProcessedBeforeTheModelGivesTheSameTrajectory) {
    const std::filesystem::path example = kOpenSimData / "gait2354";
    if (!std::filesystem::exists(example))
        GTEST_SKIP() << "../shared/data/opensim/gait2354 is absent (it ships only with sinew's developer data)";
    const Model model = loadModel((example / "subject01_simbody.osim").string(), {});
    StorageTable file = readStorageFile((example / "subject01_walk1_ik.mot").string());
    ASSERT_TRUE(file.inDegrees);
    const std::size_t left = static_cast<std::size_t>(
        std::find(file.columns.begin(), file.columns.end(), "mtp_angle_l") - file.columns.begin());
    ASSERT_LT(left, file.columns.size());
    file.columns[left] = "marker_x";  // mtp_angle_l is missing; marker_x is read by no coordinate
    const CoordinateSamples samples = readCoordinateSamples(model, completeCoordinateTable(model, file, {}));
    const CoordinateTrajectory reference = preprocessCoordinateSamples(model, samples, 6, 0.4, 1.6);
    const ProcessedMotionTable processed = preprocessMotionTable(file, 6, 0.4, 1.6);
    const CoordinateTrajectory ours = preprocessCoordinateSamples(model, samples, 6, 0.4, 1.6, &processed);
    EXPECT_TRUE(ours.times == reference.times);
    EXPECT_TRUE(ours.q == reference.q);
    EXPECT_TRUE(ours.qdot == reference.qdot);
    EXPECT_TRUE(ours.qddot == reference.qddot);
    EXPECT_TRUE(ours.processedTimes == reference.processedTimes);
    EXPECT_TRUE(ours.processedValues == reference.processedValues);
    EXPECT_EQ(ours.firstRow, reference.firstRow);
    ASSERT_EQ(ours.splines.size(), reference.splines.size());
    for (std::size_t c = 0; c < ours.splines.size(); ++c)
        for (const double t : {0.4137, 0.9, 1.5912})
            EXPECT_EQ(ours.splines[c].calcDerivative(t, 2), reference.splines[c].calcDerivative(t, 2)) << c;
    // The columns processed again reused the early processing's set-ups: their splines share its sites.
    const std::vector<std::string> names = getCoordinateNames(model);
    auto splineOf = [&](const std::string& name) -> const SmoothingSpline& {
        return ours.splines[static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin())];
    };
    EXPECT_EQ(&splineOf("pelvis_tx").getX(), &splineOf("pelvis_tilt").getX());
    EXPECT_EQ(&splineOf("mtp_angle_l").getX(), &splineOf("pelvis_tilt").getX());
    // Processed with another cutoff, the table is not taken.
    EXPECT_TRUE(preprocessCoordinateSamples(model, samples, 4, 0.4, 1.6, &processed).q ==
                preprocessCoordinateSamples(model, samples, 4, 0.4, 1.6).q);

    for (std::vector<double>& row : file.rows) row[left] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(test::throwsErrorAt([&] { preprocessMotionTable(file, 6, 0.4, 1.6); }, file.where,
                                    {"'marker_x'", "not finite"}, "a NaN column"));
    const CoordinateTrajectory withoutIt =
        preprocessCoordinateSamples(model, readCoordinateSamples(model, completeCoordinateTable(model, file, {})), 6, 0.4, 1.6);
    EXPECT_TRUE(withoutIt.q == reference.q);
}

TEST(InverseDynamicsTool, Gait2354MatchesOpenSim) {
    if (!std::filesystem::exists(kOpenSimData / "gait2354"))
        GTEST_SKIP() << "../shared/data/opensim/gait2354 is absent (it ships only with sinew's developer data)";
    const std::filesystem::path example = kOpenSimData / "gait2354";
    for (const auto& [name, value] : runAndCompare("gait2354", example / "subject01_Setup_InverseDynamics.xml",
                                                   example / "opensim-4.4.1" / "inverse_dynamics.sto"))
        EXPECT_LE(value, 2.0) << name;
}

TEST(InverseDynamicsTool, Arm26MatchesOpenSim) {
    if (!std::filesystem::exists(kOpenSimData / "arm26"))
        GTEST_SKIP() << "../shared/data/opensim/arm26 is absent (it ships only with sinew's developer data)";
    const std::filesystem::path example = kOpenSimData / "arm26";
    for (const auto& [name, value] : runAndCompare("arm26", example / "arm26_Setup_InverseDynamics.xml",
                                                   example / "opensim-4.4.1" / "arm26_InverseDynamics.sto"))
        EXPECT_LE(value, 1e-2) << name;
}

// OpenSim's Gait10dof18musc walking pipeline (../shared/data/opensim-models, an older OpenSim's reference):
// its ID setup as it stands, ground reactions through its ExternalLoads.
TEST(InverseDynamicsTool, Gait10dof18muscWalkMatchesOpenSimsReference) {
    const std::filesystem::path example =
        std::filesystem::path(SINEW_SHARED_DIR) / "data/opensim-models/Pipelines/Gait10dof18musc/OutputReference";
    if (!std::filesystem::exists(example)) GTEST_SKIP() << example << " is absent (it ships only with sinew's developer data)";
    for (const auto& [name, value] : runAndCompare("gait10dof18musc", example / "ID" / "walk_Setup_ID.xml",
                                                   example / "ID" / "Results" / "subject01_walk_ID.sto"))
        EXPECT_LE(value, 2.0) << name;
}

// The model's force elements act in inverse dynamics, as OpenSim applies every force not excluded: the
// block-and-leg model (spring, bushing, knee limit) simulated free in the air with nothing applied needs no
// generalized force, up to the splines' differentiation of the recorded motion; with the elements left
// out, inverse dynamics asks for the forces they gave.
TEST(InverseDynamicsTool, TheModelsForceElementsAct) {
    std::string text = test::kForceElementModelText;
    text.replace(text.find("initial_position: [0, 1.1, 0]"), 29, "initial_position: [0, 3.0, 0]");
    const Model model = readModelText(text, "elements_in_air.yaml");
    ForwardSimulationOptions simulation;
    simulation.duration = 0.3;
    simulation.reportInterval = 0.002;
    simulation.accuracy = 1e-11;
    simulation.initialSpeeds = Eigen::VectorXd::Constant(model.getNumU(), 0.3);
    StorageTable motion;
    motion.columns = getCoordinateNames(model);
    simulateForwardSinew(model, simulation, [&](const SimulationFrame& frame) {
        motion.times.push_back(frame.time);
        motion.rows.emplace_back(frame.q.data(), frame.q.data() + frame.q.size());
    });
    InverseDynamicsOptions options;
    options.startTime = 0.05, options.finalTime = 0.25;  // away from the splines' ends
    const StorageTable with = runInverseDynamics(model, motion, nullptr, options);
    options.forceElements = false;
    const StorageTable without = runInverseDynamics(model, motion, nullptr, options);
    double largestWith = 0, largestWithout = 0;
    for (std::size_t r = 0; r < with.rows.size(); ++r)
        for (std::size_t c = 0; c < with.columns.size(); ++c) {
            largestWith = std::max(largestWith, std::fabs(with.rows[r][c]));
            largestWithout = std::max(largestWithout, std::fabs(without.rows[r][c]));
        }
    std::cout << "free motion: largest generalized force " << largestWith << " with the force elements, "
              << largestWithout << " without\n";
    EXPECT_GT(largestWithout, 1.0);
    EXPECT_LE(largestWith, 1e-3 * largestWithout);
}

}  // namespace
}  // namespace sinew

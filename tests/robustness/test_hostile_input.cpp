// Hostile input at the library's doors (issue 15): times the splines cannot resolve, numbers beyond what the
// dynamics and Clp carry, non-finite model fields, Simbody's refusals, runaway simulations, and output files
// that fail to write. Each input here once aborted, hung, leaked a Simbody message or wrote a wrong file;
// the expectations are the documented refusals (message at the file and line, naming the field).
#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/signal/smoothing_spline.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/osim_model.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/io/trc_file.hpp"
#include "sinew/plugin/simbody_simulation.hpp"
#include "sinew/tensions/distribution_problem.hpp"
#include "support/error_assertions.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

namespace fs = std::filesystem;

std::string readText(const std::string& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string arm26Text() { return readText(test::sourcePath("models/arm26.yaml")); }

// arm26.yaml with its first occurrence of `from` replaced (which must exist).
std::string editedArm26(const std::string& from, const std::string& to) {
    std::string text = arm26Text();
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
}

int lineOf(const std::string& text, const std::string& needle) {
    const std::size_t at = text.find(needle);
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

fs::path freshFolder(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("sinew_robustness_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void expectFitOrError(const Eigen::VectorXd& t, const Eigen::VectorXd& y) {
    try {
        const SmoothingSpline spline = SmoothingSpline::fitFromErrorVariance(5, t, y, 0.0);
        for (Eigen::Index i = 0; i < t.size(); ++i) EXPECT_TRUE(std::isfinite(spline.calcValue(t[i]))) << i;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("smoothing spline: "), std::string::npos) << e.what();
    }
}

// Rows 4 and 5 a few ulps apart: once an Eigen assertion (abort) inside the quintic spline's factorisation.
TEST(HostileInput, CloseTimesAreRefusedNamingTheRows) {
    Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(20, 0, 0.19);
    t[5] = t[4] + 1e-17;
    const Eigen::MatrixXd q = t.array().sin().matrix();
    CoordinatePreprocessingOptions options;
    options.columnNames = {"elbow"};
    EXPECT_TRUE(test::throwsErrorAt([&] { preprocessCoordinates(t, q, options); }, "coordinate preprocessing: ",
                                    {"row 5", "row 4", "1e-9 s"}, "rows 1e-17 s apart"));
    // The spline on its own (no preprocessing in front) fits or throws sinew::Error; it never aborts.
    expectFitOrError(t, q.col(0));
}

TEST(HostileInput, AbsurdTimesAreRefused) {
    const Eigen::VectorXd base = Eigen::VectorXd::LinSpaced(20, 0, 0.19);
    const Eigen::MatrixXd q = base.array().sin().matrix();
    for (const double scale : {1e300, 1e-300}) {
        const Eigen::VectorXd t = base * scale;
        EXPECT_THROW(preprocessCoordinates(t, q), Error) << scale;
        expectFitOrError(t, q.col(0));
    }
}

// Found by fuzz_storage_file: a label line of a form feed only (not blank to trim(), no cells to the
// stream split) read the first label of an empty list (UBSan: reference binding to null pointer).
TEST(FuzzRegression, StorageLabelLineOfOtherWhiteSpace) {
    const fs::path dir = freshFolder("fuzz_storage");
    for (const char* blank : {"\f", "\v", " \f \v"}) {
        const std::string path = (dir / "labels.sto").string();
        using namespace std::string_literals;  // the input's first line holds a NUL
        std::ofstream(path) << "\x01\x00\ne\nve4\nendheader\n\n\n"s << blank << "\nDt6267803\t50.45\t0.29\b\t0\n";
        EXPECT_TRUE(test::throwsErrorAt([&] { readStorageFile(path); }, path + ":7: ", {"missing column labels"}, blank));
    }
}

// Found by fuzz_trc_file: a file of one vertical tab (a line not blank to the reader's trim, no cells to
// the stream split) read the first cell of an empty list (a segfault).
TEST(FuzzRegression, TrcLineOfOtherWhiteSpace) {
    const fs::path dir = freshFolder("fuzz_trc");
    for (const char* blank : {"\v", "\f", " \v\f"}) {
        const std::string path = (dir / "blank.trc").string();
        std::ofstream(path) << blank;
        EXPECT_TRUE(test::throwsErrorAt([&] { readTrcFile(path); }, path + ":2: ", {"ends before the header"}, blank));
    }
}

// Found by CI's fuzz_trc_file run: the reader reserved room for NumMarkers names before counting them, so a
// header of 2e9 markers asked for 64 GB (std::bad_alloc here, over libFuzzer's malloc limit there).
TEST(FuzzRegression, TrcHugeMarkerCountIsCountedNotReserved) {
    const fs::path dir = freshFolder("fuzz_trc_count");
    const std::string path = (dir / "count.trc").string();
    std::ofstream(path) << "PathFileType\t4\t(X/Y/Z)\tcount.trc\n"
                        << "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\n"
                        << "60\t60\t1\t2000000000\tm\n"
                        << "Frame#\tTime\tA\t\t\n\t\tX1\tY1\tZ1\n1\t0\t1\t2\t3\n";
    EXPECT_TRUE(test::throwsErrorAt([&] { readTrcFile(path); }, path + ":4: ",
                                    {"1 marker names", "NumMarkers=2000000000"}, "NumMarkers=2e9"));
}

// A ground reaction of 1e308 N once gave forces of 1e295 with exit 0.
TEST(HostileInput, StorageMagnitudesNameFileLineAndColumn) {
    const fs::path dir = freshFolder("magnitudes");
    const std::string path = (dir / "grf.mot").string();
    std::ofstream(path) << "grf\nendheader\ntime\tfx\tfy\n0\t1\t2\n0.01\t3\t1e308\n0.02\t5\t6\n";
    const StorageTable table = readStorageFile(path);
    EXPECT_NO_THROW(checkStorageMagnitudes(table, {0}, 1e7, "a force"));
    EXPECT_TRUE(test::throwsErrorAt([&] { checkStorageMagnitudes(table, {0, 1}, 1e7, "a force"); }, path + ":5: ",
                                    {"'fy'", "1e+308", "t = 0.01 s", "a force"}, "1e308 N"));
}

// A stiffness of 1e308 overflowed the first force; a point 1e20 m away collapsed every step (a hang).
TEST(HostileInput, ExtremeModelFieldsAreRefusedAtTheirLine) {
    const std::string stiff = editedArm26("stiffness: 5959.104478", "stiffness: 1e308");
    EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { readModelText(stiff, "stiff.yaml"); },
                                                "stiff.yaml:" + std::to_string(lineOf(stiff, "1e308")) + ":",
                                                {"'stiffness'", "1e308", "1e9"}, stiff));
    const std::string far = editedArm26("at: [-0.05365, -0.01373, 0.14723]", "at: [1e20, -0.01373, 0.14723]");
    EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { readModelText(far, "far.yaml"); },
                                                "far.yaml:" + std::to_string(lineOf(far, "1e20")) + ":",
                                                {"'at'", "1e20"}, far));
    EXPECT_NO_THROW(readModelText(editedArm26("stiffness: 5959.104478", "stiffness: 1e9"), "bound.yaml"));
}

const char* const kOsimWithInfiniteMass = R"(<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="40000">
  <Model name="inf">
    <BodySet name="bodyset"><objects>
      <Body name="a">
        <mass>Infinity</mass><mass_center>0 -0.1 0</mass_center><inertia>0.1 0.1 0.1 0 0 0</inertia>
      </Body>
    </objects></BodySet>
    <JointSet name="jointset"><objects>
      <PinJoint name="pin"><socket_parent_frame>/ground</socket_parent_frame><socket_child_frame>/bodyset/a</socket_child_frame>
        <coordinates><Coordinate name="q"/></coordinates>
      </PinJoint>
    </objects></JointSet>
  </Model>
</OpenSimDocument>
)";

// `sinew import` once wrote such a model to YAML, which `sinew info` then refused.
TEST(HostileInput, OsimInfinityIsRefusedAtItsLine) {
    const fs::path dir = freshFolder("osim_inf");
    for (const char* value : {"Infinity", "-inf", "1e300"}) {
        std::string text = kOsimWithInfiniteMass;
        text.replace(text.find("Infinity"), 8, value);
        const std::string path = (dir / "inf.osim").string();
        std::ofstream(path) << text;
        EXPECT_TRUE(test::throwsErrorAt([&] { readOsimModel(path); }, path + ":6", {"<mass>", value}, text)) << value;
    }
}

// Values Clp takes for infinite (and a good way below) once failed an assertion inside ClpNonLinearCost.
TEST(HostileInput, HugeDistributionProblemsAreRefusedBeforeTheLp) {
    DistributionProblem problem;
    problem.A.resize(1, 2);
    problem.A.insert(0, 0) = 1;
    problem.A.insert(0, 1) = -1;
    problem.A.makeCompressed();
    problem.lower = Eigen::VectorXd::Zero(2);
    problem.upper = Eigen::VectorXd::Constant(2, 100);
    problem.cost = Eigen::VectorXd::Ones(2);
    problem.weight = Eigen::VectorXd::Ones(2);
    problem.target = Eigen::VectorXd::Constant(1, 1e25);
    problem.tolerance = Eigen::VectorXd::Zero(1);
    problem.isEquality = {true};
    EXPECT_TRUE(test::throwsErrorAt([&] { validateDistributionProblem(problem); }, "distribution problem: ",
                                    {"target[0]", "1e+25", "1e20"}, "target 1e25"));
    problem.target[0] = 1;
    EXPECT_NO_THROW(validateDistributionProblem(problem));
    problem.upper[1] = 1e300;
    EXPECT_TRUE(test::throwsErrorAt([&] { validateDistributionProblem(problem); }, "distribution problem: ",
                                    {"bounds[1]"}, "upper bound 1e300"));
}

// The mass centre 1e5 m off the link origin: Simbody's MassProperties once threw its own message through.
TEST(HostileInput, SimbodyRefusalNamesTheLink) {
    const Model model = readModelText(
        editedArm26("com: [0.0, -0.180496, 0.0], inertia: [0.01481, 0.004551, 0.013193",
                    "com: [0.0, -1e5, 3.0], inertia: [1e-7, 1e-7, 1.5e-7"),
        "far_com.yaml");
    ForwardSimulationOptions options;
    options.hangBy = "base";
    options.duration = 0.01;
    try {
        simulateForward(model, options, [](const SimulationFrame&) {});
        FAIL() << "accepted";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("link 'r_humerus'"), std::string::npos) << message;
        EXPECT_EQ(message.find("SimTK"), std::string::npos) << message;
        EXPECT_EQ(message.find(".h:"), std::string::npos) << message;
    }
}

// --duration 0.015 at the default interval once stopped at 0.01 s; 3e7 s and an interval of 1e-300 s
// overflowed the frame count and ended after one frame with exit 0.
TEST(HostileInput, ReportTimesEndAtTheDurationAndAreBounded) {
    const Model model = test::loadArm26().model;
    ForwardSimulationOptions options;
    options.hangBy = "base";
    options.duration = 0.015;
    for (const auto engine : {simulateForward, simulateForwardSinew}) {
        std::vector<double> times;
        engine(model, options, [&](const SimulationFrame& f) { times.push_back(f.time); });
        ASSERT_EQ(times.size(), 3u);
        EXPECT_EQ(times[1], 0.01);
        EXPECT_EQ(times[2], 0.015);
    }
    for (const auto& [duration, interval, option] :
         {std::tuple{3e7, 0.01, "--duration"}, {1.0, 1e-300, "--duration"}, {INFINITY, 0.01, "--duration"},
          {1.0, NAN, "--interval"}, {1.0, -1.0, "--interval"}}) {
        options.duration = duration;
        options.reportInterval = interval;
        EXPECT_TRUE(test::throwsErrorAt([&] { checkSimulationOptions(options); }, option, {}, "")) << duration;
        EXPECT_THROW(simulateForwardSinew(model, options, [](const SimulationFrame&) {}), Error);
    }
}

// A stiffness of 1e8 N/m on a 1.5 kg forearm: the adaptive step falls to ~1e-6 s; the budget stops the run
// with a message naming the time, after the frames it reached, instead of running for minutes.
TEST(HostileInput, StepBudgetStopsAStiffRun) {
    const Model model = readModelText(editedArm26("stiffness: 5959.104478", "stiffness: 1e8"), "stiff.yaml");
    ForwardSimulationOptions options;
    options.hangBy = "base";
    options.duration = 1;
    options.maxSteps = 3000;
    for (const auto engine : {simulateForward, simulateForwardSinew}) {
        int frames = 0;
        EXPECT_TRUE(test::throwsErrorAt([&] { engine(model, options, [&](const SimulationFrame&) { ++frames; }); },
                                        "simulation stopped at t = ", {"--max-steps 3000"}, "stiff"));
        EXPECT_GE(frames, 1);
    }
    options.maxSteps = 1000000;
    options.minStep = 1e-4;  // above what the stiff wire needs
    for (const auto engine : {simulateForward, simulateForwardSinew})
        EXPECT_TRUE(test::throwsErrorAt([&] { engine(model, options, [](const SimulationFrame&) {}); },
                                        "simulation stopped at t = ", {"--min-step"}, "stiff"));
}

TEST(AtomicOutput, AFullDeviceFailsTheWrite) {
    if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
    StorageTable table{"t", false, {"a"}, {0.0, 1.0}, {{1.0}, {2.0}}};
    for (int i = 0; i < 20000; ++i) table.times.push_back(2.0 + i), table.rows.push_back({1.0 / 3});
    EXPECT_TRUE(test::throwsErrorAt([&] { writeStorageFile(table, "/dev/full"); }, "/dev/full: write failed", {}, ""));
    EXPECT_THROW(writeFileAtomically("/dev/full", std::string(1 << 16, 'x')), Error);
}

TEST(AtomicOutput, AFailedSetLeavesThePreviousFilesAndNoTemporary) {
    const fs::path dir = freshFolder("atomic_set");
    const std::string a = (dir / "a.sto").string(), b = (dir / "b").string();
    std::ofstream(a) << "previous run\n";
    fs::create_directories(b);  // the second output cannot be a file: the set fails at its open
    const StorageTable table{"t", false, {"x"}, {0.0}, {{1.0}}};
    {
        OutputFileSet set;
        writeStorageFile(table, set, a);
        EXPECT_THROW(writeStorageFile(table, set, b), Error);
    }
    EXPECT_EQ(readText(a), "previous run\n");
    int entries = 0;
    for (const auto& entry : fs::directory_iterator(dir)) entries += entry.path().filename() != "b";
    EXPECT_EQ(entries, 1) << "a temporary was left";
}

TEST(AtomicOutput, CommitReplacesAndRetiresStaleFiles) {
    const fs::path dir = freshFolder("atomic_retire");
    const std::string tensions = (dir / "t.sto").string(), activations = (dir / "t_activations.sto").string();
    std::ofstream(tensions) << "old\n";
    std::ofstream(activations) << "old activations\n";
    OutputFileSet set;
    writeStorageFile(StorageTable{"t", false, {"x"}, {0.0}, {{1.0}}}, set, tensions);
    set.retire(activations);
    EXPECT_EQ(readText(tensions), "old\n") << "replaced before commit";
    set.commit();
    EXPECT_EQ(readStorageFile(tensions).rows, (std::vector<std::vector<double>>{{1.0}}));
    EXPECT_FALSE(fs::exists(activations));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace sinew

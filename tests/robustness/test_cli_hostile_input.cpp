// The command-line tool on hostile arguments and inputs (issue 15): every refusal exits non-zero with the
// option or the file and line named; outputs cover the motion's time range only; a failed or stopped run
// leaves no file that looks whole. Runs the built `sinew` itself; the OpenSim examples in ../shared/data
// are used where present (those tests skip with a message otherwise).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "sinew/io/storage_file.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

namespace fs = std::filesystem;

struct CliRun {
    int status = -1;
    std::string output;  // stdout and stderr
};

CliRun runSinew(const std::string& arguments) {
    CliRun run;
    FILE* pipe = popen((std::string(SINEW_CLI) + " " + arguments + " 2>&1").c_str(), "r");
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) run.output.append(buffer, n);
    const int status = pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return run;
}

fs::path freshFolder(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("sinew_cli_robustness_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

const std::string kArm26 = test::sourcePath("models/arm26.yaml");
const std::string kShared = std::string(SINEW_SHARED_DIR) + "/data/opensim";

#define SKIP_WITHOUT(path)                                                                  \
    if (!fs::exists(path)) GTEST_SKIP() << (path) << " is absent (../shared/data not here)"

TEST(CliHostileInput, NumericOptionErrorsNameTheOption) {
    for (const auto& [arguments, expected] :
         {std::pair{"--duration 1s", "--duration expects a finite number, got '1s'"},
          {"--duration inf", "--duration expects a finite number, got 'inf'"},
          {"--interval nan", "--interval expects a finite number, got 'nan'"},
          {"--duration 3e7", "--duration 30000000 s at --interval 0.01 s gives 3e+09 frames"},
          {"--interval 1e-300", "gives 1e+300 frames"},
          {"--duration -1", "--duration -1: expected a finite time > 0 s"}}) {
        const CliRun run = runSinew("simulate " + kArm26 + " " + arguments + " -o " + freshFolder("options").string());
        EXPECT_EQ(run.status, 1) << arguments;
        EXPECT_NE(run.output.find(expected), std::string::npos) << arguments << ":\n" << run.output;
    }
}

TEST(CliHostileInput, SimulateEndsAtTheDuration) {
    const fs::path dir = freshFolder("duration");
    const CliRun run = runSinew("simulate " + kArm26 + " --hang-by base --duration 0.015 -o " + dir.string());
    ASSERT_EQ(run.status, 0) << run.output;
    const StorageTable table = readStorageFile((dir / "arm26_coordinates.sto").string());
    ASSERT_EQ(table.times.size(), 3u);
    EXPECT_EQ(table.times.back(), 0.015);
}

// A wire of 1e8 N/m: the budget stops the run; the frames reached are written as *_incomplete.sto and the
// previous run's complete files go, so the folder never mixes runs.
TEST(CliHostileInput, StoppedSimulationWritesMarkedIncompleteFiles) {
    const fs::path dir = freshFolder("budget");
    ASSERT_EQ(runSinew("simulate " + kArm26 + " --hang-by base --duration 0.02 -o " + dir.string()).status, 0);
    ASSERT_TRUE(fs::exists(dir / "arm26_coordinates.sto"));
    std::ifstream in(kArm26);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("stiffness: 5959.104478"), 22, "stiffness: 1e8");
    const std::string stiff = (dir / "stiff.yaml").string();
    std::ofstream(stiff) << text;
    const CliRun run = runSinew("simulate " + stiff + " --hang-by base --duration 1 --max-steps 3000 -o " + dir.string());
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("simulation stopped at t = "), std::string::npos) << run.output;
    for (const char* kind : {"coordinates", "speeds", "tensions", "energy"}) {
        EXPECT_FALSE(fs::exists(dir / ("arm26_" + std::string(kind) + ".sto"))) << kind;
        const StorageTable table = readStorageFile((dir / ("arm26_" + std::string(kind) + "_incomplete.sto")).string());
        EXPECT_GE(table.times.size(), 1u);
        ASSERT_EQ(table.header.size(), 1u);
        EXPECT_EQ(table.header[0].rfind("incomplete: simulation stopped at t = ", 0), 0u) << table.header[0];
    }
}

const char* const kTinyOsim = R"(<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="40000">
  <Model name="tiny">
    <Ground name="ground"/>
    <BodySet name="bodyset"><objects>
      <Body name="a"><mass>1</mass><mass_center>0 -0.1 0</mass_center><inertia>0.1 0.1 0.1 0 0 0</inertia></Body>
    </objects></BodySet>
    <JointSet name="jointset"><objects>
      <PinJoint name="pin"><socket_parent_frame>/ground</socket_parent_frame><socket_child_frame>/bodyset/a</socket_child_frame>
        <coordinates><Coordinate name="q"/></coordinates>
      </PinJoint>
    </objects></JointSet>
  </Model>
</OpenSimDocument>
)";

// Once truncated mid-number with exit 0.
TEST(CliHostileInput, AFullDiskFailsTheCommand) {
    if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
    const fs::path dir = freshFolder("full");
    const std::string osim = (dir / "tiny.osim").string();
    std::ofstream(osim) << kTinyOsim;
    ASSERT_EQ(runSinew("import " + osim + " -o " + (dir / "tiny.yaml").string()).status, 0);
    const CliRun run = runSinew("import " + osim + " -o /dev/full");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("/dev/full: write failed"), std::string::npos) << run.output;
}

TEST(CliHostileInput, ImportRefusesInfinityAtItsLine) {
    const fs::path dir = freshFolder("import_inf");
    std::string text = kTinyOsim;
    text.replace(text.find("<mass>1</mass>"), 14, "<mass>-Infinity</mass>");
    const std::string osim = (dir / "inf.osim").string();
    std::ofstream(osim) << text;
    const CliRun run = runSinew("import " + osim + " -o " + (dir / "inf.yaml").string());
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.output.find(osim + ":6"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir / "inf.yaml"));
}

// gait2354's walk is 0.4-1.6 s, 73 rows: --lowpass 6 once wrote 145 rows from -0.2 s to 2.2 s (the padding).
TEST(CliHostileInput, LowpassOutputsCoverTheMotionOnly) {
    const std::string gait = kShared + "/gait2354";
    SKIP_WITHOUT(gait);
    const fs::path dir = freshFolder("lowpass");
    const std::string model = gait + "/subject01_simbody.osim", motion = gait + "/subject01_walk1_ik.mot";
    const StorageTable input = readStorageFile(motion);
    for (const std::string& command : {std::string("inverse-dynamics"), std::string("tensions --method qp")}) {
        const std::string out = (dir / "out.sto").string();
        const CliRun run = runSinew(command + " " + model + " " + motion + " --lowpass 6 -o " + out);
        ASSERT_EQ(run.status, 0) << run.output;
        const StorageTable table = readStorageFile(out);
        EXPECT_EQ(table.times.size(), input.times.size()) << command;
        // OpenSim's resampled grid sits within 1e-6 s of the motion's rows.
        EXPECT_GE(table.times.front(), input.times.front() - 1e-6) << command;
        EXPECT_LE(table.times.back(), input.times.back() + 1e-12) << command;
    }
}

TEST(CliHostileInput, LowpassAboveNyquistIsRefused) {
    const std::string arm = kShared + "/arm26";
    SKIP_WITHOUT(arm);
    const CliRun run = runSinew("inverse-dynamics " + arm + "/arm26.osim " + arm +
                             "/arm26_InverseKinematics.mot --lowpass 70 -o " + (freshFolder("nyquist") / "o.sto").string());
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.output.find("--lowpass 70 Hz is at or above the Nyquist frequency 60 Hz"), std::string::npos)
        << run.output;
}

// One ground-reaction sample of 1e308 once gave generalized forces of 1e295 with exit 0.
TEST(CliHostileInput, HugeGroundReactionIsRefusedAtItsLine) {
    const std::string gait = kShared + "/gait2354";
    SKIP_WITHOUT(gait);
    const fs::path dir = freshFolder("grf");
    std::ifstream in(gait + "/subject01_walk1_grf.mot");
    std::string line, text;
    int lineNumber = 0, target = 0;
    bool data = false;
    while (std::getline(in, line)) {
        ++lineNumber;
        if (data && ++target == 50) {  // the 49th data row: its second column (ground_force_vx) = 1e308
            const std::size_t tab = line.find('\t'), next = line.find('\t', tab + 1);
            line = line.substr(0, tab + 1) + "1e308" + line.substr(next);
            target = lineNumber;
            data = false;
        }
        if (line.rfind("time", 0) == 0) data = true, target = 1;
        text += line + "\n";
    }
    std::ofstream(dir / "grf.mot") << text;
    std::ifstream xmlIn(gait + "/subject01_walk1_grf.xml");
    std::string xml((std::istreambuf_iterator<char>(xmlIn)), std::istreambuf_iterator<char>());
    const std::size_t begin = xml.find("<datafile>") + 10;
    xml.replace(begin, xml.find("</datafile>") - begin, (dir / "grf.mot").string());
    std::ofstream(dir / "grf.xml") << xml;
    const CliRun run = runSinew("inverse-dynamics " + gait + "/subject01_simbody.osim " + gait +
                             "/subject01_walk1_ik.mot --external-loads " + (dir / "grf.xml").string() + " -o " +
                             (dir / "id.sto").string());
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.output.find((dir / "grf.mot").string() + ":" + std::to_string(target) + ": column '"),
              std::string::npos)
        << run.output;
    EXPECT_FALSE(fs::exists(dir / "id.sto"));
}

// `tensions --method lp` after `--method so` once left the so run's activations beside the new tensions.
TEST(CliHostileInput, TensionsRetireAnEarlierRunsActivations) {
    const std::string arm = kShared + "/arm26";
    SKIP_WITHOUT(arm);
    const fs::path dir = freshFolder("tensions_set");
    const std::string common = "tensions " + arm + "/arm26.osim " + arm + "/arm26_InverseKinematics.mot -o " +
                               (dir / "t.sto").string() + " --method ";
    ASSERT_EQ(runSinew(common + "so").status, 0);
    ASSERT_TRUE(fs::exists(dir / "t_activations.sto"));
    ASSERT_EQ(runSinew(common + "lp").status, 0);
    EXPECT_TRUE(fs::exists(dir / "t.sto"));
    EXPECT_TRUE(fs::exists(dir / "t_report.sto"));
    EXPECT_FALSE(fs::exists(dir / "t_activations.sto"));
}

}  // namespace
}  // namespace sinew

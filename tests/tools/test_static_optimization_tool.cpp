// sinew's static optimization through OpenSim's unchanged AnalyzeTool setup against OpenSim 4.4.1's
// results (../shared/data/opensim, see its README: 4.4.1 keeps activations at or above min_control 0.01).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <iomanip>
#include <iostream>

#include "sinew/io/storage_file.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/tools/static_optimization_tool.hpp"

namespace sinew {
namespace {

const std::filesystem::path kArm26 = std::filesystem::path(SINEW_SHARED_DIR) / "data" / "opensim" / "arm26";

// Per reference column: the RMS difference over the frames both tables have (times within 1e-6 s).
std::vector<double> calcRmsDifference(const StorageTable& ours, const StorageTable& reference) {
    std::vector<double> rms;
    for (const std::string& column : reference.columns) {
        const auto it = std::find(ours.columns.begin(), ours.columns.end(), column);
        if (it == ours.columns.end()) {
            ADD_FAILURE() << "sinew's output lacks OpenSim's column " << column;
            rms.push_back(NAN);
            continue;
        }
        const std::size_t k = static_cast<std::size_t>(it - ours.columns.begin());
        const std::size_t c = static_cast<std::size_t>(&column - reference.columns.data());
        double sum = 0;
        for (std::size_t r = 0; r < reference.times.size(); ++r) {
            EXPECT_NEAR(ours.times[r], reference.times[r], 1e-6) << "frame " << r;
            const double d = ours.rows[r][k] - reference.rows[r][c];
            sum += d * d;
        }
        rms.push_back(std::sqrt(sum / static_cast<double>(reference.times.size())));
    }
    return rms;
}

TEST(StaticOptimizationTool, Arm26MatchesOpenSim) {
    if (!std::filesystem::exists(kArm26))
        GTEST_SKIP() << "../shared/data/opensim/arm26 is absent (it ships only with sinew's developer data)";
    const AnalyzeSetup setup = readAnalyzeSetup((kArm26 / "arm26_Setup_StaticOptimization.xml").string());
    const std::string output = (std::filesystem::path(::testing::TempDir()) / "sinew_so_arm26").string();
    const std::vector<std::string> written = runStaticOptimizationTool(setup, output, {});
    ASSERT_EQ(written.size(), 3u);
    EXPECT_EQ(std::filesystem::path(written[0]).filename(), "arm26_StaticOptimization_force.sto");
    EXPECT_EQ(std::filesystem::path(written[1]).filename(), "arm26_StaticOptimization_activation.sto");
    const StorageTable force = readStorageFile(written[0]), activation = readStorageFile(written[1]);
    const StorageTable referenceForce = readStorageFile((kArm26 / "opensim-4.4.1" / "arm26_StaticOptimization_force.sto").string());
    const StorageTable referenceActivation =
        readStorageFile((kArm26 / "opensim-4.4.1" / "arm26_StaticOptimization_activation.sto").string());
    ASSERT_EQ(force.times.size(), referenceForce.times.size());
    ASSERT_EQ(activation.times.size(), referenceActivation.times.size());

    const std::vector<double> forceRms = calcRmsDifference(force, referenceForce);
    const std::vector<double> activationRms = calcRmsDifference(activation, referenceActivation);
    std::cout << "arm26 static optimization, RMS difference from OpenSim 4.4.1 (" << force.times.size() << " frames)\n"
              << "  muscle      force (N)   activation\n";
    for (std::size_t m = 0; m < referenceForce.columns.size(); ++m) {
        std::cout << "  " << std::setw(10) << std::left << referenceForce.columns[m] << std::setw(12) << forceRms[m]
                  << activationRms[m] << "\n";
        EXPECT_LE(forceRms[m], 5.0) << referenceForce.columns[m];
        EXPECT_LE(activationRms[m], 0.04) << referenceForce.columns[m];
    }
    // OpenSim's bounds hold: every activation within [min_control 0.01, 1].
    for (const std::vector<double>& row : activation.rows)
        for (double a : row) {
            EXPECT_GE(a, 0.01 - 1e-9);
            EXPECT_LE(a, 1 + 1e-9);
        }
}

// OpenSim's step_interval and output_precision: AnalyzeTool records at begin, at end and on the states
// rows Analysis::proceed accepts (absolute row % N == 0, the padded table's rows: the low-pass pads
// size / 2 rows before the first), and prints with output_precision decimals. arm26 with N = 7 and 5
// decimals against the same run with every frame.
TEST(StaticOptimizationTool, StepIntervalAndOutputPrecisionAreOpenSims) {
    if (!std::filesystem::exists(kArm26))
        GTEST_SKIP() << "../shared/data/opensim/arm26 is absent (it ships only with sinew's developer data)";
    const AnalyzeSetup every = readAnalyzeSetup((kArm26 / "arm26_Setup_StaticOptimization.xml").string());
    AnalyzeSetup sparse = every;
    sparse.staticOptimization->stepInterval = 7;
    sparse.outputPrecision = 5;
    const std::filesystem::path directory = std::filesystem::path(::testing::TempDir());
    const StorageTable all = readStorageFile(runStaticOptimizationTool(every, (directory / "so_every").string(), {})[1]);
    const std::string sparsePath = runStaticOptimizationTool(sparse, (directory / "so_sparse").string(), {})[1];
    const StorageTable some = readStorageFile(sparsePath);
    const std::size_t frames = all.times.size(), pad = readStorageFile((kArm26 / "arm26_InverseKinematics.mot").string()).times.size() / 2;
    std::vector<std::size_t> expected;
    for (std::size_t r = 0; r < frames; ++r)
        if (r == 0 || r + 1 == frames || (pad + r) % 7 == 0) expected.push_back(r);
    ASSERT_EQ(some.times.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
        EXPECT_NEAR(some.times[k], all.times[expected[k]], 1e-5) << "row " << k;
        for (std::size_t c = 0; c < all.columns.size(); ++c)
            EXPECT_NEAR(some.rows[k][c], all.rows[expected[k]][c], 1e-5) << "row " << k << " " << all.columns[c];
    }
    // Five decimals, fixed, as "%.5lf" prints them (the time keeps every digit: frames are found by it).
    std::ifstream file(sparsePath);
    std::string line;
    while (std::getline(file, line) && line != "endheader") {}
    std::getline(file, line);  // column labels
    std::getline(file, line);
    std::istringstream numbers(line);
    std::string number;
    numbers >> number;
    while (numbers >> number) {
        ASSERT_NE(number.find('.'), std::string::npos) << number;
        EXPECT_EQ(number.size() - number.find('.') - 1, 5u) << number;
    }
}

}  // namespace
}  // namespace sinew

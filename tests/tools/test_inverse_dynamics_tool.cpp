// sinew's inverse dynamics tool against OpenSim 4.4.1's results on OpenSim's own examples
// (../shared/data/opensim, see its README), through the unchanged OpenSim setup files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "sinew/io/storage_file.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/tools/inverse_dynamics_tool.hpp"

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
std::vector<std::pair<std::string, double>> runAndCompare(const std::string& example, const std::string& setupFile,
                                                          const std::string& referenceFile) {
    const InverseDynamicsSetup setup = readInverseDynamicsSetup((kOpenSimData / example / setupFile).string());
    const std::string output = (std::filesystem::path(::testing::TempDir()) / ("sinew_id_" + example)).string();
    const std::string written = runInverseDynamicsTool(setup, output, {});
    const StorageTable ours = readStorageFile(written);
    const StorageTable reference = readStorageFile((kOpenSimData / example / "opensim-4.4.1" / referenceFile).string());
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
    std::cout << example << ": RMS difference from OpenSim 4.4.1 (" << ours.times.size() << " frames)\n";
    for (const auto& [name, value] : rms) std::cout << "  " << std::setw(28) << std::left << name << value << "\n";
    return rms;
}

TEST(InverseDynamicsTool, Gait2354MatchesOpenSim) {
    if (!std::filesystem::exists(kOpenSimData / "gait2354"))
        GTEST_SKIP() << "../shared/data/opensim/gait2354 is absent (it ships only with sinew's developer data)";
    for (const auto& [name, value] : runAndCompare("gait2354", "subject01_Setup_InverseDynamics.xml", "inverse_dynamics.sto"))
        EXPECT_LE(value, 2.0) << name;
}

TEST(InverseDynamicsTool, Arm26MatchesOpenSim) {
    if (!std::filesystem::exists(kOpenSimData / "arm26"))
        GTEST_SKIP() << "../shared/data/opensim/arm26 is absent (it ships only with sinew's developer data)";
    for (const auto& [name, value] :
         runAndCompare("arm26", "arm26_Setup_InverseDynamics.xml", "arm26_InverseDynamics.sto"))
        EXPECT_LE(value, 1e-2) << name;
}

}  // namespace
}  // namespace sinew

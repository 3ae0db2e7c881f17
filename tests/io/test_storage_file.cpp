// OpenSim storage files: a written table reads back bit for bit, and malformed files are rejected with the
// file and line of the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/storage_file.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

// A path private to the running test, since ctest may run the tests of this file in parallel.
std::string testPath(const std::string& suffix) {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sinew_storage_file";
    std::filesystem::create_directories(dir);
    return (dir / (std::string(info->test_suite_name()) + "." + info->name() + suffix)).string();
}

std::string writeText(const std::string& text) {
    const std::string path = testPath(".sto");
    std::ofstream(path) << text;
    return path;
}

TEST(StorageFile, RoundTripIsBitIdentical) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> mantissa(-1, 1);
    std::uniform_int_distribution<int> exponent(-300, 300);
    StorageTable table;
    table.name = "random_motion";
    table.inDegrees = true;
    table.columns = {"a", "b_qw", "c"};
    for (int i = 0; i < 50; ++i) {
        // Values that need all 17 significant digits, from 1e-90 to 1e90 in size.
        table.times.push_back(i * 0.01);
        std::vector<double> row;
        for (std::size_t c = 0; c < table.columns.size(); ++c) row.push_back(std::ldexp(mantissa(rng), exponent(rng)));
        table.rows.push_back(row);
    }
    table.rows[0] = {0.1, -0.0, 1e308};  // a decimal with no exact binary form, a signed zero, near the top
    table.rows[1] = {4.9406564584124654e-324, -2.2250738585072009e-308, 1.0};  // subnormals

    const std::string path = testPath(".sto");
    writeStorageFile(table, path);
    const StorageTable read = readStorageFile(path);
    EXPECT_EQ(read.name, table.name);
    EXPECT_EQ(read.inDegrees, table.inDegrees);
    EXPECT_EQ(read.columns, table.columns);
    EXPECT_EQ(read.times, table.times);
    EXPECT_EQ(read.rows, table.rows);
    EXPECT_TRUE(std::signbit(read.rows[0][1]));
}

// Passes when reading `text` throws a sinew::Error whose message starts with "<path>:<line>" (no line number
// when `line` is 0) and contains `words`.
::testing::AssertionResult rejectsAt(const std::string& text, int line, const std::vector<std::string>& words) {
    const std::string path = writeText(text);
    return test::throwsErrorAt([&] { readStorageFile(path); },
                               path + ":" + (line > 0 ? std::to_string(line) + ":" : ""), words, text);
}

const std::string kHeader = "motion\nversion=1\nnRows=2\nnColumns=3\ninDegrees=no\nendheader\n";  // lines 1-6

TEST(StorageFile, MissingEndheader) {
    // The file ends while still in the header, so there is no line to blame.
    EXPECT_TRUE(rejectsAt("motion\nversion=1\ntime\ta\tb\n0\t1\t2\n", 0, {"endheader"}));
}

TEST(StorageFile, FirstColumnNotTime) {
    EXPECT_TRUE(rejectsAt(kHeader + "t\ta\tb\n0\t1\t2\n", 7, {"'time'", "'t'"}));
}

TEST(StorageFile, NonNumberField) {
    EXPECT_TRUE(rejectsAt(kHeader + "time\ta\tb\n0\t1\t2\n0.1\t1\tx2\n", 9, {"'x2'", "not a number"}));
    EXPECT_TRUE(rejectsAt(kHeader + "time\ta\tb\n0\t1.5e\t2\n", 8, {"'1.5e'", "not a number"}));
}

TEST(StorageFile, RowWithWrongNumberOfValues) {
    EXPECT_TRUE(rejectsAt(kHeader + "time\ta\tb\n0\t1\t2\n0.1\t1\n", 9, {"2 values", "expected 3"}));
    EXPECT_TRUE(rejectsAt(kHeader + "time\ta\tb\n0\t1\t2\t3\n", 8, {"4 values", "expected 3"}));
}

}  // namespace
}  // namespace sinew

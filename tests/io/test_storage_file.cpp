// OpenSim storage files: a written table reads back bit for bit, and malformed files are rejected with the
// file and line of the problem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
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

// Numbers as people and programs print them: short decimals (read by a fast path), long ones, exponents
// near and past 1e+-22, leading zeros, signed zeros, '+' signs and hexadecimal (left to from_chars and
// strtod). Each must read as the double strtod gives for the same text, bit for bit.
TEST(StorageFile, NumbersReadAsStrtodReadsThem) {
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> digitCount(1, 22), digit(0, 9), exponent(-40, 40), form(0, 5);
    auto digits = [&](int count) {
        std::string text;
        for (int i = 0; i < count; ++i) text += static_cast<char>('0' + digit(rng));
        return text;
    };
    std::vector<std::string> numbers = {"0", "-0", "0.0", "-0.000", "1", "9007199254740992", "9007199254740993",
                                        "18446744073709551615", "0.1", "1e22", "1e23", "1e-22", "1e-23", "-7.5E+3",
                                        "+2.5", "0x1p-3", "4.9406564584124654e-324", "1.7976931348623157e308",
                                        "000123.4500", ".5", "5.", "-.25e1", "123456789012345678901234567890"};
    for (int i = 0; i < 3000; ++i) {
        std::string text = (rng() % 2 ? "-" : "") + digits(digitCount(rng));
        switch (form(rng)) {
            case 0: break;
            case 1: text += "." + digits(digitCount(rng)); break;
            case 2: text += "e" + std::to_string(exponent(rng)); break;
            case 3: text += "." + digits(digitCount(rng)) + "E" + std::to_string(exponent(rng)); break;
            default: text = "0." + std::string(static_cast<std::size_t>(digitCount(rng) % 6), '0') + digits(digitCount(rng)); break;
        }
        numbers.push_back(text);
    }
    std::string file = "numbers\nversion=1\nnRows=" + std::to_string(numbers.size()) + "\nnColumns=2\nendheader\ntime\tvalue\n";
    for (std::size_t i = 0; i < numbers.size(); ++i) file += std::to_string(i) + "\t" + numbers[i] + "\n";
    const StorageTable table = readStorageFile(writeText(file));
    ASSERT_EQ(table.rows.size(), numbers.size());
    for (std::size_t i = 0; i < numbers.size(); ++i) {
        const double expected = std::strtod(numbers[i].c_str(), nullptr), read = table.rows[i][0];
        EXPECT_EQ(std::memcmp(&expected, &read, sizeof(double)), 0) << numbers[i] << " read as " << read;
    }
}

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


TEST(StorageFile, NaNInfAndEmptyCellsNameTheirColumn) {
    EXPECT_TRUE(rejectsAt(kHeader + "time\ta\tb\n0\t1\t2\n0.1\tnan\t2\n", 9, {"'nan'", "column 2 'a'", "finite"}));
    EXPECT_TRUE(rejectsAt(kHeader + "time\ta\tb\n0\t1\t-inf\n", 8, {"'-inf'", "column 3 'b'"}));
    EXPECT_TRUE(rejectsAt(kHeader + "time\ta\tb\n0\t\t2\n", 8, {"empty cell", "column 2 'a'"}));
}

TEST(StorageFile, NonFiniteCellsReadWhenAllowed) {
    // Tab-separated: nan, inf, an empty cell in the middle and cells cut off at the end read as NaN; blank
    // separated: nan and inf words.
    const std::string path = writeText("motion\nendheader\ntime\ta\tb\tc\n0\t1\tnan\t-inf\n0.1\t\t2\t3\n0.2\t4\t\t\n"
                                       "0.3\t5\n0.4 NaN 6 inf\n");
    const StorageTable read = readStorageFile(path, NonFinite::Allow);
    ASSERT_EQ(read.rows.size(), 5u);
    EXPECT_EQ(read.times, (std::vector<double>{0, 0.1, 0.2, 0.3, 0.4}));
    const auto isNaN = [](double value) { return std::isnan(value); };
    EXPECT_EQ(read.rows[0][0], 1);
    EXPECT_TRUE(isNaN(read.rows[0][1]));
    EXPECT_EQ(read.rows[0][2], -HUGE_VAL);
    EXPECT_TRUE(isNaN(read.rows[1][0]));
    EXPECT_EQ(read.rows[1][1], 2);
    EXPECT_EQ(read.rows[2][0], 4);
    EXPECT_TRUE(isNaN(read.rows[2][1]) && isNaN(read.rows[2][2]));
    EXPECT_TRUE(read.rows[3][0] == 5 && isNaN(read.rows[3][1]) && isNaN(read.rows[3][2]));
    EXPECT_TRUE(isNaN(read.rows[4][0]) && read.rows[4][1] == 6 && read.rows[4][2] == HUGE_VAL);
    // The default still refuses the same file, at the first non-finite cell.
    EXPECT_THROW(readStorageFile(path), Error);

    // What stays refused: a non-finite or empty time, a blank-separated row that is short, a non-number.
    const auto refusedAt = [](const std::string& text, int line, const std::vector<std::string>& words) {
        const std::string file = writeText(text);
        return test::throwsErrorAt([&] { readStorageFile(file, NonFinite::Allow); }, file + ":" + std::to_string(line) + ":",
                                   words, text);
    };
    EXPECT_TRUE(refusedAt(kHeader + "time\ta\tb\n0\t1\t2\nnan\t1\t2\n", 9, {"'nan'", "column 1 'time'", "finite"}));
    EXPECT_TRUE(refusedAt(kHeader + "time\ta\tb\n\t1\t2\n", 8, {"empty cell", "column 1 'time'"}));
    EXPECT_TRUE(refusedAt(kHeader + "time a b\n0 1 2\n0.1 1\n", 9, {"2 values", "expected 3"}));
    EXPECT_TRUE(refusedAt(kHeader + "time\ta\tb\n0\tx\t2\n", 8, {"'x'", "not a number"}));
}

TEST(StorageFile, TimeMustIncrease) {
    EXPECT_TRUE(rejectsAt(kHeader + "time\ta\tb\n0.1\t1\t2\n0.1\t1\t2\n", 9, {"time 0.1 does not increase"}));
}

TEST(StorageFile, BadHeader) {
    const std::string labels = "endheader\ntime\ta\tb\n0\t1\t2\n0.1\t1\t2\n";
    EXPECT_TRUE(rejectsAt("m\nversion=1\nnRows=2\nnColumns=3\ninDegrees=maybe\n" + labels, 5, {"inDegrees='maybe'"}));
    EXPECT_TRUE(rejectsAt("m\nversion=1\nnRows=two\n" + labels, 3, {"nRows='two'", "integer"}));
    EXPECT_TRUE(rejectsAt("m\nversion=1\nnRows=3\nnColumns=3\n" + labels, 3, {"nRows=3", "has 2 rows"}));
    EXPECT_TRUE(rejectsAt("m\nversion=1\nnRows=2\nnColumns=4\n" + labels, 6, {"3 column labels", "nColumns=4"}));
    EXPECT_TRUE(rejectsAt("DataType=Vec3\nendheader\ntime\ta\n0\t1\n", 1, {"DataType=Vec3"}));
}

// The header layout OpenSim 4 writes (STOFileAdapter): key=value lines, no name line, no nRows.
TEST(StorageFile, OpenSim4HeaderAndMetadataSurviveARoundTrip) {
    const std::string path = writeText(
        "DataType=double\nversion=3\nOpenSimVersion=4.4\ninDegrees=yes\nsubject=s01\nendheader\n"
        "time\tknee\thip\n0\t1.5\t2\n0.01\t1.6\t2.5\n");
    const StorageTable table = readStorageFile(path);
    EXPECT_EQ(table.name, "");
    EXPECT_TRUE(table.inDegrees);
    EXPECT_EQ(table.header, (std::vector<std::string>{"DataType=double", "OpenSimVersion=4.4", "subject=s01"}));
    EXPECT_EQ(table.columns, (std::vector<std::string>{"knee", "hip"}));
    EXPECT_EQ(table.rows[1], (std::vector<double>{1.6, 2.5}));
    EXPECT_EQ(table.where, path + ":7");

    const std::string copy = testPath(".copy.sto");
    writeStorageFile(table, copy);
    const StorageTable again = readStorageFile(copy);
    EXPECT_EQ(again.header, table.header);
    EXPECT_EQ(again.times, table.times);
    EXPECT_EQ(again.rows, table.rows);
}

TEST(StorageFile, WriterRefusesWhatCannotBeReadBack) {
    StorageTable table{"motion", false, {"a"}, {0.0}, {{std::nan("")}}};
    const std::string path = testPath(".sto");
    EXPECT_TRUE(test::throwsErrorAt([&] { writeStorageFile(table, path); }, path + ": ", {"column 'a'", "not finite"}, ""));
    table.rows = {{1.0}};
    table.name = "a=b";
    EXPECT_TRUE(test::throwsErrorAt([&] { writeStorageFile(table, path); }, path + ": ", {"'a=b'", "metadata"}, ""));
    table.name = "motion";
    table.header = {"endheader"};
    EXPECT_TRUE(test::throwsErrorAt([&] { writeStorageFile(table, path); }, path + ": ", {"'endheader'"}, ""));
}

TEST(StorageFile, MatchColumns) {
    const std::string path = writeText("motion\nendheader\ntime\tb\ta\ta\tc\n0\t1\t2\t3\t4\n");
    const StorageTable table = readStorageFile(path);
    EXPECT_EQ(matchStorageColumns(table, {"c", "b"}, ExtraColumns::Allow), (std::vector<int>{3, 0}));
    EXPECT_TRUE(test::throwsErrorAt([&] { matchStorageColumns(table, {"b", "a", "d"}, ExtraColumns::Refuse); },
                                    path + ":3: ", {"missing 'd'", "duplicated 'a' (2 times)", "not expected 'c'"}, ""));
    EXPECT_TRUE(test::throwsErrorAt([&] { matchStorageColumns(table, {"b", "c"}, ExtraColumns::Refuse); },
                                    path + ":3: ", {"not expected 'a', 'a'"}, ""));
}

// Every .mot and .sto file of the shared OpenSim data reads, with as many rows and columns as a plain
// count of its lines and labels gives, and writes back to a file that reads the same.
TEST(StorageFile, EveryOpenSimDataFileReadsAndRoundTrips) {
    const std::filesystem::path root = std::filesystem::path(SINEW_SHARED_DIR) / "data" / "opensim";
    if (!std::filesystem::exists(root)) GTEST_SKIP() << "OpenSim data not found at " << root;
    int files = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
        const std::string extension = entry.path().extension().string();
        if (extension != ".mot" && extension != ".sto") continue;
        ++files;
        SCOPED_TRACE(entry.path().string());
        const StorageTable table = readStorageFile(entry.path().string());
        std::ifstream in(entry.path());
        std::string line;
        int dataLines = -1;  // the labels line comes first
        bool inData = false;
        std::string labels;
        while (std::getline(in, line)) {
            if (inData && line.find_first_not_of(" \t\r") != std::string::npos && ++dataLines == 0) labels = line;
            if (line.rfind("endheader", 0) == 0) inData = true;
        }
        EXPECT_EQ(static_cast<int>(table.rows.size()), dataLines);
        EXPECT_EQ(table.columns.size() + 1, static_cast<std::size_t>(std::count(labels.begin(), labels.end(), '\t') + 1));

        const std::string copy = testPath("." + entry.path().filename().string());
        writeStorageFile(table, copy);
        const StorageTable again = readStorageFile(copy);
        EXPECT_EQ(again.name, table.name);
        EXPECT_EQ(again.inDegrees, table.inDegrees);
        EXPECT_EQ(again.header, table.header);
        EXPECT_EQ(again.columns, table.columns);
        EXPECT_EQ(again.times, table.times);
        EXPECT_EQ(again.rows, table.rows);
    }
    EXPECT_EQ(files, 11);

    const StorageTable ik = readStorageFile((root / "arm26" / "arm26_InverseKinematics.mot").string());
    EXPECT_EQ(ik.name, "Coordinates");
    EXPECT_TRUE(ik.inDegrees);
    EXPECT_EQ(ik.columns, (std::vector<std::string>{"r_shoulder_elev", "r_elbow_flex"}));
    EXPECT_EQ(ik.rows[0], (std::vector<double>{-0.03394423, -0.05440752}));
    // A header whose lines end in tabs, as Vicon-era tools wrote them.
    const StorageTable grf = readStorageFile((root / "gait2354" / "subject01_walk1_grf.mot").string());
    EXPECT_EQ(grf.name, "subject01_walk1_grf.mot");
    EXPECT_EQ(grf.times.back(), 2.5);
    EXPECT_EQ(grf.rows.back().back(), 0.99444594);
}
}  // namespace
}  // namespace sinew

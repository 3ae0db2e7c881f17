// TRC marker files: a written table reads back bit for bit, a real file's numbers are the ones in its text,
// units convert, missing samples stay missing, and each kind of malformed file is refused at its line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/trc_file.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

// A path private to the running test, since ctest may run the tests of this file in parallel.
std::string testPath(const std::string& suffix) {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sinew_trc_file";
    std::filesystem::create_directories(dir);
    return (dir / (std::string(info->test_suite_name()) + "." + info->name() + suffix)).string();
}

std::string writeText(const std::string& text, const std::string& suffix = ".trc") {
    const std::string path = testPath(suffix);
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

const std::filesystem::path kGaitData = std::filesystem::path(SINEW_SHARED_DIR) / "data" / "opensim-models" /
                                        "Pipelines" / "Gait10dof18musc" / "OutputReference" / "ExperimentalData";

// Two markers, three frames, in OpenSim's layout; `units` and the rows are the caller's.
std::string smallTrc(const std::string& units, const std::string& rows, int numFrames = 3) {
    return "PathFileType\t4\t(X/Y/Z)\tsmall.trc\n"
           "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames\n"
           "100.00\t100.00\t" + std::to_string(numFrames) + "\t2\t" + units + "\t100.00\t1\t3\n"
           "Frame#\tTime\tA\t\t\tB\t\t\n"
           "\t\tX1\tY1\tZ1\tX2\tY2\tZ2\n"
           "\n" + rows;
}
const std::string kRows =
    "1\t0.00\t1234.5\t-20.25\t7\t0.5\t1\t2\n"
    "2\t0.01\t1235.5\t-20.5\t7.25\t0.75\t1\t2\n"
    "3\t0.02\t1236.5\t-20.75\t7.5\t1\t1\t2\n";

// Equal to the last bit, with NaN where the other has NaN.
void expectSameTable(const MarkerTable& a, const MarkerTable& b) {
    EXPECT_EQ(a.markers, b.markers);
    EXPECT_EQ(a.frameNumbers, b.frameNumbers);
    EXPECT_EQ(a.times, b.times);
    EXPECT_EQ(a.dataRate, b.dataRate);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (std::size_t i = 0; i < a.positions.size(); ++i) {
        ASSERT_EQ(a.positions[i].cols(), b.positions[i].cols());
        for (Eigen::Index m = 0; m < a.positions[i].cols(); ++m)
            for (Eigen::Index axis = 0; axis < 3; ++axis) {
                const double x = a.positions[i](axis, m), y = b.positions[i](axis, m);
                if (std::isnan(x) || std::isnan(y))
                    EXPECT_TRUE(std::isnan(x) && std::isnan(y)) << "frame " << i << " marker " << m << " axis " << axis;
                else
                    EXPECT_EQ(x, y) << "frame " << i << " marker " << m << " axis " << axis;
            }
    }
}

TEST(TrcFile, RoundTripIsBitIdentical) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> position(-2, 2);
    std::bernoulli_distribution missing(0.1);
    MarkerTable table;
    table.markers = {"R.ASIS", "L.ASIS", "Top Head", "last"};
    table.dataRate = 1.0 / 0.0083333333333333332;
    for (int i = 0; i < 40; ++i) {
        table.frameNumbers.push_back(7 + i);
        table.times.push_back(0.1 + i / table.dataRate);
        Eigen::Matrix3Xd p(3, 4);
        for (Eigen::Index m = 0; m < 4; ++m)
            for (Eigen::Index axis = 0; axis < 3; ++axis)
                p(axis, m) = missing(rng) ? std::numeric_limits<double>::quiet_NaN() : position(rng);
        table.positions.push_back(p);
    }
    // The last marker missing on a frame: the row ends in empty cells, which the writer's tabs keep.
    table.positions[3].col(3).setConstant(std::numeric_limits<double>::quiet_NaN());
    table.positions[4](0, 0) = 4.9406564584124654e-324;

    const std::string path = testPath(".trc");
    writeTrcFile(path, table);
    const MarkerTable read = readTrcFile(path);
    EXPECT_EQ(read.source, path);
    expectSameTable(read, table);
    writeTrcFile(path, read);
    expectSameTable(readTrcFile(path), table);
}

TEST(TrcFile, RealFilesRoundTrip) {
    for (const char* name : {"subject01_walk.trc", "subject01_static.trc"}) {
        const std::filesystem::path file = kGaitData / name;
        if (!std::filesystem::exists(file)) GTEST_SKIP() << "OpenSim's Gait10dof18musc data not found at " << file;
        SCOPED_TRACE(file.string());
        const MarkerTable table = readTrcFile(file.string());
        const std::string path = testPath(std::string("_") + name);
        writeTrcFile(path, table);
        expectSameTable(readTrcFile(path), table);
    }
}

// The walk's first and last rows against numbers copied from the file's text (in mm there).
TEST(TrcFile, RealFileValuesAreTheTextsInMetres) {
    const std::filesystem::path file = kGaitData / "subject01_walk.trc";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "OpenSim's Gait10dof18musc data not found at " << file;
    const MarkerTable table = readTrcFile(file.string());
    EXPECT_EQ(table.dataRate, 60.0);
    ASSERT_EQ(table.markers.size(), 41u);
    EXPECT_EQ(table.markers.front(), "R.ASIS");
    EXPECT_EQ(table.markers[2], "V.Sacral");
    EXPECT_EQ(table.markers.back(), "Top.Head");
    ASSERT_EQ(table.times.size(), 151u);
    EXPECT_EQ(table.frameNumbers.front(), 1);
    EXPECT_EQ(table.frameNumbers.back(), 151);
    EXPECT_EQ(table.times.front(), 0.0);
    EXPECT_EQ(table.frameLines.front(), 7);
    // Line 7: "1  0.000000  617.247620  1055.275020  170.781980  639.606380  1044.258420  -88.909790 ..."
    EXPECT_DOUBLE_EQ(table.positions[0](0, 0), 0.61724762);
    EXPECT_DOUBLE_EQ(table.positions[0](1, 0), 1.05527502);
    EXPECT_DOUBLE_EQ(table.positions[0](2, 0), 0.17078198);
    EXPECT_DOUBLE_EQ(table.positions[0](2, 1), -0.08890979);

    // Every cell of every row against a plain split of the text.
    std::ifstream in(file);
    std::string line;
    for (int skip = 0; skip < 6; ++skip) std::getline(in, line);
    for (std::size_t i = 0; i < table.times.size(); ++i) {
        ASSERT_TRUE(std::getline(in, line));
        std::istringstream cells(line);
        double frame = 0, time = 0;
        cells >> frame >> time;
        EXPECT_EQ(table.frameNumbers[i], static_cast<int>(frame));
        EXPECT_EQ(table.times[i], time);
        for (Eigen::Index m = 0; m < 41; ++m)
            for (Eigen::Index axis = 0; axis < 3; ++axis) {
                double mm = 0;
                ASSERT_TRUE(cells >> mm) << "line " << 7 + i;
                EXPECT_NEAR(table.positions[i](axis, m), mm * 1e-3, 1e-15);
            }
    }
}

// The same positions in mm, cm and m read as the same numbers of metres (values exact in binary, so the
// correctly rounded division gives the very number the m text does).
TEST(TrcFile, UnitsConvertToMetres) {
    const MarkerTable mm = readTrcFile(writeText(smallTrc("mm", kRows), "_mm.trc"));
    const MarkerTable cm = readTrcFile(writeText(smallTrc("cm",
        "1\t0.00\t123.45\t-2.025\t0.7\t0.05\t0.1\t0.2\n"
        "2\t0.01\t123.55\t-2.05\t0.725\t0.075\t0.1\t0.2\n"
        "3\t0.02\t123.65\t-2.075\t0.75\t0.1\t0.1\t0.2\n"), "_cm.trc"));
    const MarkerTable m = readTrcFile(writeText(smallTrc("m",
        "1\t0.00\t1.2345\t-0.02025\t0.007\t0.0005\t0.001\t0.002\n"
        "2\t0.01\t1.2355\t-0.0205\t0.00725\t0.00075\t0.001\t0.002\n"
        "3\t0.02\t1.2365\t-0.02075\t0.0075\t0.001\t0.001\t0.002\n"), "_m.trc"));
    expectSameTable(mm, m);
    // The cm texts are not exact in binary: rounded twice (text, then division), within one ulp of 1.2 m.
    for (std::size_t i = 0; i < m.positions.size(); ++i)
        EXPECT_LE((cm.positions[i] - m.positions[i]).cwiseAbs().maxCoeff(), 2.3e-16);
}

// Empty cells, a row cut short and NaN text are missing samples; their neighbours are read as they are.
TEST(TrcFile, MissingSamplesAreNaN) {
    const MarkerTable table = readTrcFile(writeText(smallTrc("mm",
        "1\t0.00\t\t\t\t500\t1000\t2000\n"
        "2\t0.01\t1000\t2000\t3000\n"
        "3\t0.02\t1000\tNaN\t3000\t\t\t\t\t\n")));
    ASSERT_EQ(table.positions.size(), 3u);
    EXPECT_TRUE(table.positions[0].col(0).array().isNaN().all());
    EXPECT_EQ(table.positions[0].col(1), Eigen::Vector3d(0.5, 1, 2));
    EXPECT_EQ(table.positions[1].col(0), Eigen::Vector3d(1, 2, 3));
    EXPECT_TRUE(table.positions[1].col(1).array().isNaN().all());
    EXPECT_EQ(table.positions[2](0, 0), 1);
    EXPECT_TRUE(std::isnan(table.positions[2](1, 0)));
    EXPECT_EQ(table.positions[2](2, 0), 3);
    EXPECT_TRUE(table.positions[2].col(1).array().isNaN().all());
}

// CRLF endings, trailing tabs and blanks, no blank line after the labels (or several), and blank lines
// between the header lines all read as OpenSim's own layout does.
TEST(TrcFile, LayoutVariantsReadTheSame) {
    const MarkerTable reference = readTrcFile(writeText(smallTrc("mm", kRows), "_reference.trc"));
    std::string crlf = smallTrc("mm", kRows);
    for (std::size_t at = crlf.find('\n'); at != std::string::npos; at = crlf.find('\n', at + 2)) crlf.insert(at, "\r");
    std::string trailing = smallTrc("mm", kRows);
    for (std::size_t at = trailing.find('\n'); at != std::string::npos; at = trailing.find('\n', at + 3))
        trailing.insert(at, "\t ");
    std::string noBlank = smallTrc("mm", kRows);
    noBlank.erase(noBlank.find("\n\n"), 1);
    std::string blanks = smallTrc("mm", kRows);
    blanks.insert(blanks.find("DataRate"), "\n  \n");
    blanks += "\n\n";
    std::string spaces = smallTrc("mm", "1 0.00 1234.5 -20.25 7 0.5 1 2\n2 0.01 1235.5 -20.5 7.25 0.75 1 2\n"
                                        "3 0.02 1236.5 -20.75 7.5 1 1 2\n");
    for (const std::string& text : {crlf, trailing, noBlank, blanks, spaces}) {
        SCOPED_TRACE(text);
        expectSameTable(readTrcFile(writeText(text)), reference);
    }
}

struct Malformed {
    std::string name;
    std::string text;
    std::string at;                  // "line" or "line: column ..." the message starts with, after the path
    std::vector<std::string> words;  // the message must name these
};

TEST(TrcFile, MalformedFilesAreRefusedAtTheirLine) {
    auto replaced = [](std::string text, const std::string& from, const std::string& to) {
        return text.replace(text.find(from), from.size(), to);
    };
    const std::string good = smallTrc("mm", kRows);
    const std::vector<Malformed> cases = {
        {"bad number", replaced(good, "1235.5", "1235,5"), "8: column 3 (A X)", {"'1235,5' is not a number"}},
        {"infinite", replaced(good, "-20.5", "-inf"), "8: column 4 (A Y)", {"'-inf' is not finite"}},
        {"bad frame number", replaced(good, "2\t0.01", "2.5\t0.01"), "8: column 1 (Frame#)", {"not an integer"}},
        {"bad time", replaced(good, "0.01", "t1"), "8: column 2 (Time)", {"'t1' is not a finite time"}},
        {"too many cells", replaced(good, "7.25\t0.75\t1\t2", "7.25\t0.75\t1\t2\t9"), "8: column 9",
         {"9 cells", "2 markers make 8 columns"}},
        {"NumMarkers mismatch", replaced(good, "\t2\tmm", "\t3\tmm"), "4: ",
         {"2 marker names", "line 3 column 4 (NumMarkers) says NumMarkers=3"}},
        {"NumFrames mismatch", smallTrc("mm", kRows, 4), "3: column 3 (NumFrames)",
         {"NumFrames=4 but the file has 3 frames"}},
        {"non-increasing time", replaced(good, "0.02", "0.01"), "9: column 2 (Time)",
         {"time 0.01 does not increase", "line 8"}},
        {"unknown units", smallTrc("in", kRows), "3: column 5 (Units)", {"unknown Units 'in'", "mm, cm or m"}},
        {"no PathFileType line", good.substr(good.find('\n') + 1), "1: column 1", {"expected 'PathFileType'"}},
        {"no keys line", replaced(good, "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\t"
                                        "OrigDataStartFrame\tOrigNumFrames\n", ""),
         "2: ", {"no key 'DataRate'"}},
        {"no Units key", replaced(good, "\tUnits", "\tUnitz"), "2: ", {"no key 'Units'"}},
        {"value missing", replaced(good, "\t100.00\t1\t3\n", "\n"), "3: column 6 (OrigDataRate)",
         {"no value under the key 'OrigDataRate' of line 2"}},
        {"no marker names row", replaced(good, "Frame#\tTime\tA\t\t\tB\t\t\n", ""), "4: ",
         {"row of marker names", "'Frame#' and 'Time'"}},
        {"no coordinate labels row", replaced(good, "\t\tX1\tY1\tZ1\tX2\tY2\tZ2\n\n", ""), "5: ",
         {"6 coordinate labels", "a row of numbers"}},
        {"marker named twice", replaced(good, "\tB\t\t", "\tA\t\t"), "4: column 6", {"'A' is named twice", "column 3"}},
        {"header cut short", good.substr(0, good.find("Frame#")), "4: ", {"ends before", "marker names"}},
        {"empty file", "", "1: ", {"ends before the header's PathFileType line"}},
    };
    for (const Malformed& c : cases) {
        const std::string path = writeText(c.text, "_" + std::to_string(&c - cases.data()) + ".trc");
        EXPECT_TRUE(test::throwsErrorAt([&] { readTrcFile(path); }, path + ":" + c.at, c.words, c.text)) << c.name;
    }
    EXPECT_TRUE(test::throwsErrorAt([] { readTrcFile("/nonexistent/x.trc"); }, "/nonexistent/x.trc: ",
                                    {"cannot open"}, ""));
}

// A table that would not read back is refused before any file is started.
TEST(TrcFile, UnwritableTablesLeaveNoFile) {
    MarkerTable good;
    good.markers = {"A", "B"};
    good.dataRate = 100;
    good.frameNumbers = {1, 2};
    good.times = {0, 0.01};
    good.positions = {Eigen::Matrix3Xd::Zero(3, 2), Eigen::Matrix3Xd::Ones(3, 2)};
    auto with = [&](auto change) {
        MarkerTable table = good;
        change(table);
        return table;
    };
    const std::vector<std::pair<MarkerTable, std::string>> cases = {
        {with([](MarkerTable& t) { t.markers[1] = "A"; }), "named twice"},
        {with([](MarkerTable& t) { t.markers[1] = "B\tC"; }), "holds a tab"},
        {with([](MarkerTable& t) { t.dataRate = 0; }), "DataRate"},
        {with([](MarkerTable& t) { t.times[1] = 0; }), "does not increase"},
        {with([](MarkerTable& t) { t.frameNumbers.pop_back(); }), "one each per frame"},
        {with([](MarkerTable& t) { t.positions[1] = Eigen::Matrix3Xd::Zero(3, 3); }), "3 marker columns"},
        {with([](MarkerTable& t) { t.positions[1](2, 1) = -std::numeric_limits<double>::infinity(); }), "infinite"},
    };
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const auto& [table, words] = cases[i];
        const std::string path = testPath("_" + std::to_string(i) + ".trc");
        std::filesystem::remove(path);
        EXPECT_TRUE(test::throwsErrorAt([&] { writeTrcFile(path, table); }, path + ": ", {words}, words));
        EXPECT_FALSE(std::filesystem::exists(path)) << words;
    }
}

}  // namespace
}  // namespace sinew

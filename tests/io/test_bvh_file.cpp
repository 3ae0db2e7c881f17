// BVH motion files: a written motion reads back bit for bit, joint angles written by hand come back from the
// poses (against Eigen's own rotations and Euler angles), the length unit is inferred, and every kind of
// malformed file is refused at its line and column.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sinew/core/error.hpp"
#include "sinew/io/bvh_file.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A path private to the running test, since ctest may run the tests of this file in parallel.
std::string testPath(const std::string& suffix) {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sinew_bvh_file";
    std::filesystem::create_directories(dir);
    return (dir / (std::string(info->test_suite_name()) + "." + info->name() + suffix)).string();
}

std::string writeText(const std::string& text, const std::string& suffix = ".bvh") {
    const std::string path = testPath(suffix);
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

const std::filesystem::path kKick = std::filesystem::path(SINEW_SHARED_DIR) / "data" / "cmu_mocap" / "11_01.bvh";

void expectSameMotion(const BvhMotion& a, const BvhMotion& b) {
    ASSERT_EQ(a.joints.size(), b.joints.size());
    for (std::size_t j = 0; j < a.joints.size(); ++j) {
        SCOPED_TRACE(a.joints[j].name);
        EXPECT_EQ(a.joints[j].name, b.joints[j].name);
        EXPECT_EQ(a.joints[j].parent, b.joints[j].parent);
        EXPECT_EQ(a.joints[j].offset, b.joints[j].offset);
        EXPECT_EQ(a.joints[j].channels, b.joints[j].channels);
        EXPECT_EQ(a.joints[j].firstChannel, b.joints[j].firstChannel);
        EXPECT_EQ(a.joints[j].endSite, b.joints[j].endSite);
    }
    EXPECT_EQ(a.frameTime, b.frameTime);
    ASSERT_EQ(a.values.rows(), b.values.rows());
    ASSERT_EQ(a.values.cols(), b.values.cols());
    EXPECT_TRUE((a.values.array() == b.values.array()).all());
}

// A two-joint leg in the style most BVH writers use; lines 19 and 20 are its frames.
const std::string kLeg =
    "HIERARCHY\n"
    "ROOT hips\n"
    "{\n"
    "  OFFSET 0 0 0\n"
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    "  JOINT knee\n"
    "  {\n"
    "    OFFSET 0 -40 0\n"
    "    CHANNELS 3 Zrotation Xrotation Yrotation\n"
    "    End Site\n"
    "    {\n"
    "      OFFSET 0 -45 0\n"
    "    }\n"
    "  }\n"
    "}\n"
    "MOTION\n"
    "Frames: 2\n"
    "Frame Time: 0.01\n"
    "0 90 0 0 0 0 10 20 30\n"
    "0 91 0 0 0 0 11 21 31\n";

TEST(BvhFile, RealKickReads) {
    if (!std::filesystem::exists(kKick)) GTEST_SKIP() << "CMU motion capture 11_01.bvh not found at " << kKick;
    const BvhMotion motion = readBvhFile(kKick.string());
    ASSERT_FALSE(motion.joints.empty());
    EXPECT_EQ(motion.joints.front().name, "hip");
    EXPECT_EQ(motion.joints.front().channels,
              (std::vector<BvhChannel>{BvhChannel::Xposition, BvhChannel::Yposition, BvhChannel::Zposition,
                                       BvhChannel::Zrotation, BvhChannel::Yrotation, BvhChannel::Xrotation}));
    EXPECT_EQ(motion.values.rows(), 598);
    EXPECT_EQ(motion.values.cols(), 132);
    EXPECT_EQ(motion.frameTime, 0.00833333);
    EXPECT_EQ(motion.firstFrameLine, 276);
    // Line 276 begins "66.6251 84.7382 -214.236 0.0 0.0 0.0 -0.427942"; lines 7-8 are abdomen's offset.
    EXPECT_EQ(motion.values(0, 0), 66.6251);
    EXPECT_EQ(motion.values(0, 2), -214.236);
    EXPECT_EQ(motion.values(0, 6), -0.427942);
    const int abdomen = findBvhJoint(motion, "abdomen");
    ASSERT_EQ(abdomen, 1);
    EXPECT_EQ(motion.joints[1].offset, Eigen::Vector3d(0, 20.6881, -0.73152));
    EXPECT_EQ(motion.joints[1].firstChannel, 6);
    const int eyeEnd = findBvhJoint(motion, "leftEye_End");
    ASSERT_GE(eyeEnd, 0);
    EXPECT_TRUE(motion.joints[static_cast<std::size_t>(eyeEnd)].endSite);
    EXPECT_EQ(motion.joints[static_cast<std::size_t>(eyeEnd)].parent, findBvhJoint(motion, "leftEye"));
    // Poser-style CMU conversions are in centimetres: the thigh (rShin's offset) is 36.8 units.
    EXPECT_EQ(inferBvhLengthUnit(motion), 0.01);

    // Every row against a plain split of the text.
    std::ifstream in(kKick);
    std::string line;
    for (int skip = 1; skip < motion.firstFrameLine; ++skip) std::getline(in, line);
    for (Eigen::Index frame = 0; frame < motion.values.rows(); ++frame) {
        ASSERT_TRUE(std::getline(in, line));
        std::istringstream cells(line);
        for (Eigen::Index c = 0; c < motion.values.cols(); ++c) {
            double value = 0;
            ASSERT_TRUE(cells >> value);
            ASSERT_EQ(motion.values(frame, c), value) << "frame " << frame << " value " << c + 1;
        }
    }
}

TEST(BvhFile, RoundTripIsBitIdentical) {
    std::vector<std::string> paths;
    if (std::filesystem::exists(kKick)) paths.push_back(kKick.string());
    paths.push_back(writeText(kLeg, "_leg.bvh"));
    for (const std::string& source : paths) {
        SCOPED_TRACE(source);
        BvhMotion motion = readBvhFile(source);
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> mantissa(-1, 1);
        std::uniform_int_distribution<int> exponent(-60, 60);
        // Numbers that need all 17 digits, beside the file's own.
        for (Eigen::Index c = 0; c < motion.values.cols(); ++c) motion.values(0, c) = std::ldexp(mantissa(rng), exponent(rng));
        motion.values(0, 0) = -0.0;
        motion.joints.back().offset(1) = 0.1;
        motion.frameTime = 1.0 / 120;
        const std::string path = testPath(".bvh");
        writeBvhFile(path, motion);
        const BvhMotion read = readBvhFile(path);
        expectSameMotion(read, motion);
        EXPECT_TRUE(std::signbit(read.values(0, 0)));
        writeBvhFile(path, read);
        expectSameMotion(readBvhFile(path), motion);
    }
}

// Tabs, CRLF, braces against words and blank lines read as the plain layout does.
TEST(BvhFile, LayoutVariantsReadTheSame) {
    const BvhMotion reference = readBvhFile(writeText(kLeg, "_reference.bvh"));
    std::string crlf = kLeg;
    for (std::size_t at = crlf.find('\n'); at != std::string::npos; at = crlf.find('\n', at + 2)) crlf.insert(at, "\r");
    std::string glued = kLeg;
    for (std::size_t at = glued.find("\n{"); at != std::string::npos; at = glued.find("\n{")) glued.erase(at, 1);
    for (std::size_t at = glued.find("  "); at != std::string::npos; at = glued.find("  ")) glued.replace(at, 2, "\t");
    glued.insert(glued.find("MOTION"), "\n\n");
    glued += "\n\n";
    for (const std::string& text : {crlf, glued}) {
        SCOPED_TRACE(text);
        expectSameMotion(readBvhFile(writeText(text)), reference);
    }
}

// The axis of a BVH rotation channel, and its name.
struct ChannelAxis {
    BvhChannel channel;
    int index;  // 0, 1, 2 for X, Y, Z
    Eigen::Vector3d axis;
};
const ChannelAxis kX{BvhChannel::Xrotation, 0, Eigen::Vector3d::UnitX()};
const ChannelAxis kY{BvhChannel::Yrotation, 1, Eigen::Vector3d::UnitY()};
const ChannelAxis kZ{BvhChannel::Zrotation, 2, Eigen::Vector3d::UnitZ()};

// A chain of four joints with a different rotation order each (and position channels between the
// rotations of one), written by hand from known angles. The angles come back from the poses through Eigen's
// Euler angles, and the joint centres match a chain of Eigen transforms.
TEST(BvhFile, KnownAnglesOnAChainComeBack) {
    const std::vector<std::array<ChannelAxis, 3>> orders = {{kZ, kX, kY}, {kX, kY, kZ}, {kY, kZ, kX}, {kZ, kY, kX}};
    const std::vector<Eigen::Vector3d> offsets = {{0.5, 1, -0.25}, {0, -40, 2}, {3, -45, 1}, {-1, 0.5, 12}};
    const Eigen::Vector3d endOffset(0, 0, 7);
    std::mt19937 rng(7);
    // Ranges where Eigen's eulerAngles (first in [0, pi], others in [-pi, pi]) gives these very angles back.
    std::uniform_real_distribution<double> first(0.1, kPi - 0.1), second(-kPi / 2 + 0.1, kPi / 2 - 0.1),
        third(-kPi + 0.1, kPi - 0.1), shift(-20, 20);
    const int frames = 5;
    std::vector<std::vector<Eigen::Vector3d>> angles(frames, std::vector<Eigen::Vector3d>(4));  // rad
    std::vector<std::array<Eigen::Vector3d, 2>> shifts(frames);  // the root's and joint 2's position channels

    std::ostringstream text;
    text << std::setprecision(17) << "HIERARCHY\n";
    for (std::size_t j = 0; j < 4; ++j) {
        text << (j == 0 ? "ROOT j0" : "JOINT j" + std::to_string(j)) << "\n{\nOFFSET " << offsets[j].transpose() << '\n';
        const auto& o = orders[j];
        if (j == 0)
            text << "CHANNELS 6 Xposition Yposition Zposition ";
        else if (j == 2)  // position channels listed among the rotations still move the joint first
            text << "CHANNELS 6 Zposition " << bvhChannelName(o[0].channel) << " Xposition ";
        else
            text << "CHANNELS 3 ";
        text << (j == 2 ? "" : std::string(bvhChannelName(o[0].channel)) + " ") << bvhChannelName(o[1].channel)
             << (j == 2 ? " Yposition " : " ") << bvhChannelName(o[2].channel) << '\n';
    }
    text << "End Site\n{\nOFFSET " << endOffset.transpose() << "\n}\n}\n}\n}\n}\nMOTION\nFrames: " << frames
         << "\nFrame Time: 0.008333333333333333\n";
    for (int f = 0; f < frames; ++f) {
        shifts[f] = {Eigen::Vector3d(shift(rng), shift(rng), shift(rng)), Eigen::Vector3d(shift(rng), shift(rng), shift(rng))};
        const Eigen::Vector3d& s0 = shifts[f][0];
        const Eigen::Vector3d& s2 = shifts[f][1];
        text << s0(0) << ' ' << s0(1) << ' ' << s0(2);
        for (std::size_t j = 0; j < 4; ++j) {
            Eigen::Vector3d& a = angles[f][j];
            a = Eigen::Vector3d(first(rng), second(rng), third(rng));
            const Eigen::Vector3d degrees = a * 180 / kPi;
            if (j == 2)
                text << ' ' << s2(2) << ' ' << degrees(0) << ' ' << s2(0) << ' ' << degrees(1) << ' ' << s2(1) << ' '
                     << degrees(2);
            else
                text << ' ' << degrees(0) << ' ' << degrees(1) << ' ' << degrees(2);
        }
        text << '\n';
    }
    const BvhMotion motion = readBvhFile(writeText(text.str()));
    ASSERT_EQ(motion.joints.size(), 5u);
    ASSERT_EQ(motion.values.rows(), frames);

    for (int f = 0; f < frames; ++f) {
        const std::vector<BvhPose> poses = calcBvhPoses(motion, f);
        Eigen::Isometry3d X_GP = Eigen::Isometry3d::Identity();
        for (std::size_t j = 0; j < 4; ++j) {
            SCOPED_TRACE("frame " + std::to_string(f) + " joint " + std::to_string(j));
            const auto& o = orders[j];
            const Eigen::Matrix3d R_PJ =
                j == 0 ? poses[0].R_GJ : Eigen::Matrix3d(poses[j - 1].R_GJ.transpose() * poses[j].R_GJ);
            const Eigen::Vector3d recovered = R_PJ.eulerAngles(o[0].index, o[1].index, o[2].index);
            EXPECT_LT((recovered - angles[f][j]).cwiseAbs().maxCoeff(), 1e-9);
            EXPECT_LT((calcBvhLocalRotation(motion, static_cast<int>(j), f) - R_PJ).cwiseAbs().maxCoeff(), 1e-14);

            Eigen::Vector3d translation = offsets[j];
            if (j == 0) translation += shifts[f][0];
            if (j == 2) translation += shifts[f][1];
            const Eigen::Isometry3d X_PJ = Eigen::Translation3d(translation) * Eigen::AngleAxisd(angles[f][j](0), o[0].axis) *
                                           Eigen::AngleAxisd(angles[f][j](1), o[1].axis) *
                                           Eigen::AngleAxisd(angles[f][j](2), o[2].axis);
            X_GP = X_GP * X_PJ;
            EXPECT_LT((poses[j].p_GJ - X_GP.translation()).norm(), 1e-12);
            EXPECT_LT((poses[j].R_GJ - X_GP.rotation()).cwiseAbs().maxCoeff(), 1e-14);
        }
        EXPECT_LT((poses[4].p_GJ - X_GP * endOffset).norm(), 1e-12);
        EXPECT_LT((poses[4].R_GJ - X_GP.rotation()).cwiseAbs().maxCoeff(), 1e-14);
    }
}

// By hand: the leg's hips turned 90 degrees about Z put the knee, 40 below the hips, at +40 along X.
TEST(BvhFile, HandWorkedLegPose) {
    BvhMotion motion = readBvhFile(writeText(kLeg));
    motion.values.row(0) << 1, 2, 3, 90, 0, 0, 0, 0, 0;
    const std::vector<BvhPose> poses = calcBvhPoses(motion, 0);
    EXPECT_LT((poses[0].p_GJ - Eigen::Vector3d(1, 2, 3)).norm(), 1e-12);
    EXPECT_LT((poses[1].p_GJ - Eigen::Vector3d(41, 2, 3)).norm(), 1e-12);
    EXPECT_LT((poses[2].p_GJ - Eigen::Vector3d(86, 2, 3)).norm(), 1e-12);
    EXPECT_TRUE(test::throwsErrorAt([&] { calcBvhPoses(motion, 2); }, motion.source + ": ", {"frame 2 is out of range"}, ""));
}

TEST(BvhFile, LengthUnitFromTheSkeletonsSize) {
    BvhMotion motion = readBvhFile(writeText(kLeg));
    for (BvhJoint& joint : motion.joints) joint.offset *= 2;  // 170 tall, the rest pose standing on Y
    EXPECT_EQ(inferBvhLengthUnit(motion), 0.01);
    for (BvhJoint& joint : motion.joints) joint.offset /= 100;
    EXPECT_EQ(inferBvhLengthUnit(motion), 1.0);
    for (BvhJoint& joint : motion.joints) joint.offset *= 100 / 2.54;
    EXPECT_EQ(inferBvhLengthUnit(motion), 0.0254);
    for (BvhJoint& joint : motion.joints) joint.offset *= 2.54 * 10;
    EXPECT_EQ(inferBvhLengthUnit(motion), 0.001);
    // 0.85 units tall: 2 m per unit, not near a unit of length, comes back as it is.
    for (BvhJoint& joint : motion.joints) joint.offset /= 2000;
    EXPECT_DOUBLE_EQ(inferBvhLengthUnit(motion), 1.70 / 0.85);
    for (BvhJoint& joint : motion.joints) joint.offset.setZero();
    EXPECT_TRUE(test::throwsErrorAt([&] { inferBvhLengthUnit(motion); }, motion.source + ": ", {"no size"}, ""));
}

struct Malformed {
    std::string name;
    std::string text;
    std::string at;                  // "line:column" or "line" the message starts with, after the path
    std::vector<std::string> words;  // the message must name these
};

TEST(BvhFile, MalformedFilesAreRefusedAtTheirLine) {
    auto replaced = [](std::string text, const std::string& from, const std::string& to) {
        return text.replace(text.find(from), from.size(), to);
    };
    const std::string& good = kLeg;
    const std::string channels9 = "CHANNELS 3 Zrotation Xrotation Yrotation";
    const std::vector<Malformed> cases = {
        {"not BVH", replaced(good, "HIERARCHY", "HIERARCHX"), "1:1", {"expected 'HIERARCHY'", "'HIERARCHX'"}},
        {"no ROOT", replaced(good, "ROOT", "BOOT"), "2:1", {"expected 'ROOT'", "'BOOT'"}},
        {"no name", replaced(good, "ROOT hips", "ROOT"), "3:1", {"expected the name after ROOT", "'{'"}},
        {"no brace", replaced(good, "JOINT knee\n  {", "JOINT knee"), "7:5", {"expected '{' after JOINT knee", "'OFFSET'"}},
        {"unknown keyword", replaced(good, "    OFFSET 0 -40 0", "    OFSET 0 -40 0"), "8:5",
         {"unexpected 'OFSET' in 'knee'"}},
        {"bad offset", replaced(good, "0 -40 0", "0 -4O 0"), "8:14", {"OFFSET's Y of 'knee'", "'-4O'"}},
        {"short offset", replaced(good, "0 -45 0", "0 -45"), "13:5", {"OFFSET's Z", "'}'"}},
        {"second offset", replaced(good, "    OFFSET 0 -40 0", "    OFFSET 0 -40 0 OFFSET 1 1 1"), "8:20",
         {"a second OFFSET in 'knee'"}},
        {"no offset", replaced(good, "      OFFSET 0 -45 0\n", ""), "12:5", {"'knee_End' has no OFFSET"}},
        {"bad channel count", replaced(good, channels9, "CHANNELS 7 Zrotation Xrotation Yrotation"), "9:14",
         {"number of channels of 'knee' (0 to 6)", "'7'"}},
        {"unknown channel", replaced(good, channels9, "CHANNELS 3 Zrotation Wrotation Yrotation"), "9:26",
         {"channel 2 of the 3 of 'knee'", "'Wrotation'"}},
        {"too few channel names", replaced(good, channels9, "CHANNELS 3 Zrotation Xrotation"), "10:5",
         {"channel 3 of the 3", "'End'"}},
        {"repeated channel", replaced(good, channels9, "CHANNELS 3 Zrotation Xrotation Zrotation"), "9:36",
         {"'knee' lists Zrotation twice"}},
        {"channels on an End Site", replaced(good, "      OFFSET 0 -45 0", "      OFFSET 0 -45 0 CHANNELS 1 Xrotation"),
         "12:22", {"an End Site has no CHANNELS"}},
        {"child of an End Site", replaced(good, "      OFFSET 0 -45 0", "      OFFSET 0 -45 0 JOINT toe"), "12:22",
         {"an End Site has no children"}},
        {"End without Site", replaced(good, "End Site", "End Sight"), "10:9", {"expected 'Site' after 'End'"}},
        {"repeated name", replaced(good, "JOINT knee", "JOINT hips"), "6:3", {"a second joint named 'hips'", "line 2"}},
        {"channels after a child", replaced(replaced(good, "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation "
                                                           "Yrotation\n", ""),
                                            "  }\n}", "  }\n  CHANNELS 1 Xrotation\n}"),
         "14:3", {"CHANNELS of 'hips' after its child 'knee'"}},
        {"missing brace", good.substr(0, good.find("}\nMOTION")), "14:1", {"the file ends inside 'hips' (line 2)", "'}' is missing"}},
        {"no MOTION", good.substr(0, good.find("MOTION")), "15:1", {"expected 'ROOT' or 'MOTION'", "the end of the file"}},
        {"no channels", replaced(replaced(good, "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n",
                                          ""), "    " + channels9 + "\n", ""),
         "14:1", {"no CHANNELS"}},
        {"no Frames", replaced(good, "Frames: 2", "Frame: 2"), "17:1", {"expected 'Frames:'"}},
        {"bad Frames", replaced(good, "Frames: 2", "Frames: -2"), "17:9", {"number of frames", "'-2'"}},
        {"no Frame Time", replaced(good, "Frame Time:", "FrameTime:"), "18:1", {"expected 'Frame'"}},
        {"zero Frame Time", replaced(good, "Frame Time: 0.01", "Frame Time: 0"), "18:13", {"positive number of seconds"}},
        {"row on the Frame Time line", replaced(good, "Frame Time: 0.01\n", "Frame Time: 0.01 "), "18:18",
         {"after the Frame Time"}},
        {"short row", replaced(good, "0 91 0 0 0 0 11 21 31", "0 91 0 0 0 0 11 21"), "20: ",
         {"8 values, expected 9", "the first missing is value 9 (knee Yrotation)"}},
        {"long row", replaced(good, "0 91 0 0 0 0 11 21 31", "0 91 0 0 0 0 11 21 31 4"), "20: ", {"10 values, expected 9",
                                                                                                     "first extra is value 10"}},
        {"bad value", replaced(good, "0 91 0 0 0 0 11", "0 91 0 0 0 0 1l"), "20: value 7 (knee Zrotation)",
         {"'1l' is not a finite number"}},
        {"NaN value", replaced(good, "0 91 0", "0 nan 0"), "20: value 2 (hips Yposition)", {"'nan' is not a finite number"}},
        {"more rows than Frames", replaced(good, "Frames: 2", "Frames: 1"), "20: ", {"beyond the 1 frames", "line 17"}},
        {"fewer rows than Frames", replaced(good, "Frames: 2", "Frames: 3"), "20: ", {"ends after 2 of the 3 frames", "line 17"}},
    };
    for (const Malformed& c : cases) {
        const std::string path = writeText(c.text, "_" + std::to_string(&c - cases.data()) + ".bvh");
        EXPECT_TRUE(test::throwsErrorAt([&] { readBvhFile(path); }, path + ":" + c.at, c.words, c.text)) << c.name;
    }
    EXPECT_TRUE(test::throwsErrorAt([] { readBvhFile("/nonexistent/x.bvh"); }, "/nonexistent/x.bvh: ", {"cannot open"}, ""));
}

// A motion that would not read back is refused before any file is started.
TEST(BvhFile, UnwritableMotionsLeaveNoFile) {
    const BvhMotion good = readBvhFile(writeText(kLeg));
    auto with = [&](auto change) {
        BvhMotion motion = good;
        change(motion);
        return motion;
    };
    const std::vector<std::pair<BvhMotion, std::string>> cases = {
        {with([](BvhMotion& m) { m.joints[1].name = "left knee"; }), "one word"},
        {with([](BvhMotion& m) { m.joints[1].name = "hips"; }), "taken by another joint"},
        {with([](BvhMotion& m) { m.joints[2].name = "toe"; }), "'<parent>_End'"},
        {with([](BvhMotion& m) { m.joints[1].parent = 1; }), "does not come before it"},
        {with([](BvhMotion& m) {
             m.joints.insert(m.joints.begin() + 2, BvhJoint{"other", 0, Eigen::Vector3d::Zero(), {}, 9, false, 0});
         }),
         "not in depth-first order"},
        {with([](BvhMotion& m) { m.joints[2].channels = {BvhChannel::Xrotation}; }), "End Site has no channels"},
        {with([](BvhMotion& m) { m.joints[1].firstChannel = 0; }), "firstChannel is 0"},
        {with([](BvhMotion& m) { m.joints[1].channels[2] = BvhChannel::Zrotation; }), "listed twice"},
        {with([](BvhMotion& m) { m.values.conservativeResize(2, 8); }), "8 columns for 9 channels"},
        {with([](BvhMotion& m) { m.values(1, 3) = std::numeric_limits<double>::quiet_NaN(); }), "not finite"},
        {with([](BvhMotion& m) { m.joints[0].offset(0) = std::numeric_limits<double>::infinity(); }), "offset is not finite"},
        {with([](BvhMotion& m) { m.frameTime = 0; }), "Frame Time"},
    };
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const auto& [motion, words] = cases[i];
        const std::string path = testPath("_" + std::to_string(i) + ".bvh");
        std::filesystem::remove(path);
        EXPECT_TRUE(test::throwsErrorAt([&] { writeBvhFile(path, motion); }, path + ": ", {words}, words));
        EXPECT_FALSE(std::filesystem::exists(path)) << words;
    }
}

}  // namespace
}  // namespace sinew

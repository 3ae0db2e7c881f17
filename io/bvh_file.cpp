#include "sinew/io/bvh_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "number_text.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"

namespace sinew {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180;
constexpr std::array<BvhChannel, 6> kChannels = {BvhChannel::Xposition, BvhChannel::Yposition, BvhChannel::Zposition,
                                                 BvhChannel::Xrotation, BvhChannel::Yrotation, BvhChannel::Zrotation};

bool isPosition(BvhChannel channel) { return static_cast<int>(channel) < 3; }
int axisOf(BvhChannel channel) { return static_cast<int>(channel) % 3; }

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::optional<double> parseFiniteNumber(const std::string& text) {
    const std::optional<double> value = parseNumber(text);
    if (!value || !std::isfinite(*value)) return std::nullopt;
    return value;
}

std::optional<long> parseCount(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const long value = std::strtol(text.c_str(), &end, 10);
    if (end != text.c_str() + text.size() || value < 0) return std::nullopt;
    return value;
}

// The rotation by `angle` (rad) about the X, Y or Z axis.
Eigen::Matrix3d axisRotation(int axis, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    Eigen::Matrix3d R;
    if (axis == 0)
        R << 1, 0, 0, 0, c, -s, 0, s, c;
    else if (axis == 1)
        R << c, 0, s, 0, 1, 0, -s, 0, c;
    else
        R << c, -s, 0, s, c, 0, 0, 0, 1;
    return R;
}

Eigen::Matrix3d localRotation(const BvhJoint& joint, const Eigen::RowVectorXd& row) {
    Eigen::Matrix3d R_PJ = Eigen::Matrix3d::Identity();
    for (std::size_t k = 0; k < joint.channels.size(); ++k)
        if (!isPosition(joint.channels[k]))
            R_PJ = R_PJ * axisRotation(axisOf(joint.channels[k]), row(joint.firstChannel + static_cast<int>(k)) * kDegree);
    return R_PJ;
}

// Every joint's pose for one row of channel values, base to tip (parents come first).
std::vector<BvhPose> posesAt(const std::vector<BvhJoint>& joints, const Eigen::RowVectorXd& row) {
    std::vector<BvhPose> poses(joints.size());
    for (std::size_t j = 0; j < joints.size(); ++j) {
        const BvhJoint& joint = joints[j];
        Eigen::Vector3d p_PJ = joint.offset;
        for (std::size_t k = 0; k < joint.channels.size(); ++k)
            if (isPosition(joint.channels[k])) p_PJ(axisOf(joint.channels[k])) += row(joint.firstChannel + static_cast<int>(k));
        const Eigen::Matrix3d R_PJ = localRotation(joint, row);
        if (joint.parent < 0) {
            poses[j] = {R_PJ, p_PJ};
        } else {
            const BvhPose& parent = poses[static_cast<std::size_t>(joint.parent)];
            poses[j] = {parent.R_GJ * R_PJ, parent.p_GJ + parent.R_GJ * p_PJ};
        }
    }
    return poses;
}

int channelCount(const std::vector<BvhJoint>& joints) {
    int count = 0;
    for (const BvhJoint& joint : joints) count += static_cast<int>(joint.channels.size());
    return count;
}

// Reads one BVH file, turning every problem into an Error at "file:line:column" (hierarchy) or
// "file:line" (motion rows).
class BvhReader {
public:
    explicit BvhReader(std::string path) : path_(std::move(path)) {
        std::ifstream in(path_);
        if (!in) throw Error(path_ + ": cannot open for reading");
        for (std::string line; std::getline(in, line);) lines_.push_back(line);
        motion_.source = path_;
    }

    BvhMotion read() {
        const Token first = next();
        if (first.text != "HIERARCHY") fail(first, "expected 'HIERARCHY', got " + quoted(first) + "; not a BVH file");
        for (;;) {
            const Token token = next();
            if (token.text == "ROOT") {
                readJoint(token, -1, false);
            } else if (token.text == "MOTION" && !motion_.joints.empty()) {
                readMotion(token);
                return std::move(motion_);
            } else {
                fail(token, std::string(motion_.joints.empty() ? "expected 'ROOT'" : "expected 'ROOT' or 'MOTION'") +
                                ", got " + quoted(token));
            }
        }
    }

private:
    struct Token {
        std::string text;  // empty at the end of the file
        int line = 0;      // from 1
        int column = 0;    // from 1, in characters
    };

    std::string path_;
    std::vector<std::string> lines_;
    std::size_t line_ = 0, position_ = 0;  // the cursor: the next character to read
    BvhMotion motion_;
    std::map<std::string, int> jointLines_;
    int channels_ = 0;

    [[noreturn]] void fail(int line, const std::string& message) const {
        throw Error(path_ + ":" + std::to_string(line) + ": " + message);
    }
    [[noreturn]] void fail(const Token& at, const std::string& message) const {
        throw Error(path_ + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": " + message);
    }
    static std::string quoted(const Token& token) {
        return token.text.empty() ? std::string("the end of the file") : "'" + token.text + "'";
    }

    // Words and braces, across lines; a brace is a token of its own even when written against a word.
    Token next() {
        for (; line_ < lines_.size(); ++line_, position_ = 0) {
            const std::string& text = lines_[line_];
            while (position_ < text.size() && isBlank(text[position_])) ++position_;
            if (position_ == text.size()) continue;
            Token token{{}, static_cast<int>(line_ + 1), static_cast<int>(position_ + 1)};
            if (text[position_] == '{' || text[position_] == '}') {
                token.text = text.substr(position_++, 1);
                return token;
            }
            const std::size_t begin = position_;
            while (position_ < text.size() && !isBlank(text[position_]) && text[position_] != '{' && text[position_] != '}')
                ++position_;
            token.text = text.substr(begin, position_ - begin);
            return token;
        }
        return Token{{}, static_cast<int>(lines_.size()), 1};
    }

    void expect(const std::string& text, const std::string& context) {
        const Token token = next();
        if (token.text != text) fail(token, "expected '" + text + "' " + context + ", got " + quoted(token));
    }

    double readNumber(const std::string& what) {
        const Token token = next();
        const std::optional<double> value = parseFiniteNumber(token.text);
        if (!value) fail(token, "expected " + what + ", a finite number, got " + quoted(token));
        return *value;
    }

    void readJoint(const Token& keyword, int parent, bool endSite) {
        std::string name;
        if (endSite) {
            expect("Site", "after 'End'");
            name = motion_.joints[static_cast<std::size_t>(parent)].name + "_End";
        } else {
            const Token nameToken = next();
            if (nameToken.text.empty() || nameToken.text == "{" || nameToken.text == "}")
                fail(nameToken, "expected the name after " + keyword.text + ", got " + quoted(nameToken));
            name = nameToken.text;
        }
        const auto [previous, inserted] = jointLines_.emplace(name, keyword.line);
        if (!inserted)
            fail(keyword, "a second joint named '" + name + "' (the first is on line " +
                              std::to_string(previous->second) + ")");
        expect("{", "after " + (endSite ? std::string("End Site") : keyword.text + " " + name));

        const int index = static_cast<int>(motion_.joints.size());
        BvhJoint joint;
        joint.name = name;
        joint.parent = parent;
        joint.endSite = endSite;
        joint.firstChannel = channels_;
        joint.line = keyword.line;
        motion_.joints.push_back(joint);
        auto self = [&]() -> BvhJoint& { return motion_.joints[static_cast<std::size_t>(index)]; };

        bool haveOffset = false, haveChannels = false;
        std::string firstChild;
        for (;;) {
            const Token token = next();
            if (token.text == "OFFSET") {
                if (haveOffset) fail(token, "a second OFFSET in '" + name + "'");
                haveOffset = true;
                for (int axis = 0; axis < 3; ++axis)
                    self().offset(axis) = readNumber(std::string("OFFSET's ") + "XYZ"[axis] + " of '" + name + "'");
            } else if (token.text == "CHANNELS") {
                if (endSite) fail(token, "an End Site has no CHANNELS (in '" + name + "')");
                if (haveChannels) fail(token, "a second CHANNELS in '" + name + "'");
                if (!firstChild.empty())
                    fail(token, "CHANNELS of '" + name + "' after its child '" + firstChild +
                                    "': the motion's columns follow the joints, so a joint's CHANNELS come first");
                haveChannels = true;
                readChannels(name, self());
            } else if (token.text == "JOINT" || token.text == "End") {
                if (endSite) fail(token, "an End Site has no children (in '" + name + "')");
                const std::size_t child = motion_.joints.size();
                readJoint(token, index, token.text == "End");
                if (firstChild.empty()) firstChild = motion_.joints[child].name;
            } else if (token.text == "}") {
                if (!haveOffset) fail(token, "'" + name + "' has no OFFSET");
                return;
            } else if (token.text.empty()) {
                fail(token, "the file ends inside '" + name + "' (line " + std::to_string(keyword.line) +
                                "): a '}' is missing");
            } else {
                fail(token, "unexpected " + quoted(token) + " in '" + name + "'; expected " +
                                (endSite ? std::string("OFFSET or '}'") : "OFFSET, CHANNELS, JOINT, End Site or '}'"));
            }
        }
    }

    void readChannels(const std::string& name, BvhJoint& joint) {
        const Token countToken = next();
        const std::optional<long> count = parseCount(countToken.text);
        if (!count || *count > 6)
            fail(countToken, "expected the number of channels of '" + name + "' (0 to 6), got " + quoted(countToken));
        for (long k = 0; k < *count; ++k) {
            const Token token = next();
            std::optional<BvhChannel> channel;
            for (BvhChannel candidate : kChannels)
                if (token.text == bvhChannelName(candidate)) channel = candidate;
            if (!channel)
                fail(token, "expected channel " + std::to_string(k + 1) + " of the " + std::to_string(*count) + " of '" +
                                name + "' (Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation), got " +
                                quoted(token));
            for (BvhChannel listed : joint.channels)
                if (listed == *channel) fail(token, "'" + name + "' lists " + token.text + " twice");
            joint.channels.push_back(*channel);
        }
        channels_ += static_cast<int>(*count);
    }

    std::string describeValue(int column) const {
        for (const BvhJoint& joint : motion_.joints)
            if (column >= joint.firstChannel && column < joint.firstChannel + static_cast<int>(joint.channels.size()))
                return "value " + std::to_string(column + 1) + " (" + joint.name + " " +
                       bvhChannelName(joint.channels[static_cast<std::size_t>(column - joint.firstChannel)]) + ")";
        return "value " + std::to_string(column + 1);
    }

    void readMotion(const Token& motionToken) {
        if (channels_ == 0) fail(motionToken, "the hierarchy has no CHANNELS, so there is no motion to read");
        const Token framesToken = next();
        if (framesToken.text != "Frames:") fail(framesToken, "expected 'Frames:' after MOTION, got " + quoted(framesToken));
        const Token countToken = next();
        const std::optional<long> frames = parseCount(countToken.text);
        if (!frames) fail(countToken, "expected the number of frames, an integer >= 0, got " + quoted(countToken));
        expect("Frame", "(of 'Frame Time:') after the number of frames");
        expect("Time:", "after 'Frame'");
        const Token timeToken = next();
        const std::optional<double> frameTime = parseFiniteNumber(timeToken.text);
        if (!frameTime || *frameTime <= 0)
            fail(timeToken, "expected the Frame Time, a positive number of seconds, got " + quoted(timeToken));
        motion_.frameTime = *frameTime;
        const Token after = next();
        if (after.line == timeToken.line)
            fail(after, "unexpected " + quoted(after) + " after the Frame Time; the frames start on the next line");

        std::vector<double> values;
        long rows = 0;
        for (std::size_t l = static_cast<std::size_t>(timeToken.line); l < lines_.size(); ++l) {
            std::istringstream cells(lines_[l]);
            std::vector<std::string> row;
            for (std::string cell; cells >> cell;) row.push_back(cell);
            if (row.empty()) continue;
            const int line = static_cast<int>(l + 1);
            if (rows == *frames)
                fail(line, "a row beyond the " + std::to_string(*frames) + " frames that line " +
                               std::to_string(framesToken.line) + " announces");
            if (rows == 0) motion_.firstFrameLine = line;
            if (static_cast<int>(row.size()) != channels_)
                fail(line, std::to_string(row.size()) + " values, expected " + std::to_string(channels_) +
                               " (one per channel); the first " + (static_cast<int>(row.size()) < channels_ ? "missing" : "extra") +
                               " is " + describeValue(std::min(static_cast<int>(row.size()), channels_)));
            for (int c = 0; c < channels_; ++c) {
                const std::optional<double> value = parseFiniteNumber(row[static_cast<std::size_t>(c)]);
                if (!value) fail(line, describeValue(c) + ": '" + row[static_cast<std::size_t>(c)] + "' is not a finite number");
                values.push_back(*value);
            }
            ++rows;
        }
        if (rows < *frames)
            fail(static_cast<int>(lines_.size()), "the file ends after " + std::to_string(rows) + " of the " +
                                                      std::to_string(*frames) + " frames that line " +
                                                      std::to_string(framesToken.line) + " announces");
        motion_.values = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            values.data(), rows, channels_);
    }
};

void checkWritable(const std::string& path, const BvhMotion& motion) {
    auto refuse = [&](const std::string& message) { throw Error(path + ": " + message); };
    const std::vector<BvhJoint>& joints = motion.joints;
    if (joints.empty()) refuse("a motion with no joints cannot be written");
    std::map<std::string, std::size_t> names;
    int column = 0;
    std::vector<int> lastDescendant(joints.size());  // the last joint of each one's subtree so far
    for (std::size_t j = 0; j < joints.size(); ++j) {
        const BvhJoint& joint = joints[j];
        const std::string what = "joint " + std::to_string(j) + " '" + joint.name + "'";
        if (joint.name.empty() || joint.name.find_first_of(" \t\r\n\v\f{}") != std::string::npos)
            refuse(what + ": a name must be one word without braces");
        if (!names.emplace(joint.name, j).second) refuse(what + ": the name is taken by another joint");
        if (joint.parent < -1 || joint.parent >= static_cast<int>(j))
            refuse(what + ": its parent " + std::to_string(joint.parent) + " does not come before it");
        // Depth first: the parent is the last joint so far or an ancestor whose subtree ends just before j.
        if (joint.parent >= 0) {
            const auto parent = static_cast<std::size_t>(joint.parent);
            if (lastDescendant[parent] != static_cast<int>(j) - 1)
                refuse(what + ": the joints are not in depth-first order (its parent's subtree is interrupted)");
            for (int a = joint.parent; a >= 0; a = joints[static_cast<std::size_t>(a)].parent)
                lastDescendant[static_cast<std::size_t>(a)] = static_cast<int>(j);
            if (joints[parent].endSite) refuse(what + ": the parent is an End Site, which has no children");
        } else if (joint.endSite) {
            refuse(what + ": an End Site needs a parent");
        }
        lastDescendant[j] = static_cast<int>(j);
        if (joint.endSite && !joint.channels.empty()) refuse(what + ": an End Site has no channels");
        if (joint.endSite && joint.name != joints[static_cast<std::size_t>(joint.parent)].name + "_End")
            refuse(what + ": an End Site is named '<parent>_End', as readBvhFile names it");
        if (!joint.offset.allFinite()) refuse(what + ": the offset is not finite");
        if (joint.firstChannel != column)
            refuse(what + ": firstChannel is " + std::to_string(joint.firstChannel) + ", but the channels before it make " +
                   std::to_string(column));
        for (std::size_t k = 0; k < joint.channels.size(); ++k)
            for (std::size_t other = 0; other < k; ++other)
                if (joint.channels[k] == joint.channels[other])
                    refuse(what + ": " + bvhChannelName(joint.channels[k]) + " is listed twice");
        if (joint.channels.size() > 6) refuse(what + ": more than 6 channels");
        column += static_cast<int>(joint.channels.size());
    }
    if (column == 0) refuse("no joint has channels, so there is no motion to write");
    if (motion.values.cols() != column)
        refuse("values has " + std::to_string(motion.values.cols()) + " columns for " + std::to_string(column) + " channels");
    if (!motion.values.allFinite()) refuse("values holds a number that is not finite");
    if (!std::isfinite(motion.frameTime) || motion.frameTime <= 0) refuse("the Frame Time must be a positive number of seconds");
}

std::string describeMotion(const BvhMotion& motion) {
    return motion.source.empty() ? std::string("BVH motion") : motion.source;
}

void checkFrame(const BvhMotion& motion, int frame) {
    if (frame < 0 || frame >= motion.values.rows())
        throw Error(describeMotion(motion) + ": frame " + std::to_string(frame) + " is out of range (the motion has " +
                    std::to_string(motion.values.rows()) + " frames)");
}

void writeJoint(std::ostream& out, const std::vector<BvhJoint>& joints, std::size_t j) {
    const BvhJoint& joint = joints[j];
    int depth = 0;
    for (int a = joint.parent; a >= 0; a = joints[static_cast<std::size_t>(a)].parent) ++depth;
    const std::string indent(static_cast<std::size_t>(depth), '\t');
    if (joint.endSite)
        out << indent << "End Site\n";
    else
        out << indent << (joint.parent < 0 ? "ROOT " : "JOINT ") << joint.name << '\n';
    out << indent << "{\n" << indent << "\tOFFSET " << joint.offset(0) << ' ' << joint.offset(1) << ' ' << joint.offset(2) << '\n';
    if (!joint.endSite) {
        out << indent << "\tCHANNELS " << joint.channels.size();
        for (BvhChannel channel : joint.channels) out << ' ' << bvhChannelName(channel);
        out << '\n';
    }
    for (std::size_t child = j + 1; child < joints.size(); ++child)
        if (joints[child].parent == static_cast<int>(j)) writeJoint(out, joints, child);
    out << indent << "}\n";
}

}  // namespace

const char* bvhChannelName(BvhChannel channel) {
    switch (channel) {
        case BvhChannel::Xposition: return "Xposition";
        case BvhChannel::Yposition: return "Yposition";
        case BvhChannel::Zposition: return "Zposition";
        case BvhChannel::Xrotation: return "Xrotation";
        case BvhChannel::Yrotation: return "Yrotation";
        case BvhChannel::Zrotation: return "Zrotation";
    }
    return "?";
}

BvhMotion readBvhFile(const std::string& path) { return BvhReader(path).read(); }

void writeBvhFile(const std::string& path, const BvhMotion& motion) {
    checkWritable(path, motion);
    OutputFileSet set;
    std::ostream& out = set.open(path);
    out << std::setprecision(17) << "HIERARCHY\n";
    for (std::size_t j = 0; j < motion.joints.size(); ++j)
        if (motion.joints[j].parent < 0) writeJoint(out, motion.joints, j);
    out << "MOTION\nFrames: " << motion.values.rows() << "\nFrame Time: " << motion.frameTime << '\n';
    for (Eigen::Index frame = 0; frame < motion.values.rows(); ++frame) {
        for (Eigen::Index c = 0; c < motion.values.cols(); ++c) out << (c ? " " : "") << motion.values(frame, c);
        out << '\n';
    }
    set.commit();
}

int findBvhJoint(const BvhMotion& motion, const std::string& name) {
    for (std::size_t j = 0; j < motion.joints.size(); ++j)
        if (motion.joints[j].name == name) return static_cast<int>(j);
    return -1;
}

Eigen::Matrix3d calcBvhLocalRotation(const BvhMotion& motion, int joint, int frame) {
    checkFrame(motion, frame);
    return localRotation(motion.joints.at(static_cast<std::size_t>(joint)), motion.values.row(frame));
}

std::vector<BvhPose> calcBvhPoses(const BvhMotion& motion, int frame) {
    checkFrame(motion, frame);
    return posesAt(motion.joints, motion.values.row(frame));
}

double inferBvhLengthUnit(const BvhMotion& motion) {
    const std::vector<BvhPose> rest = posesAt(motion.joints, Eigen::RowVectorXd::Zero(channelCount(motion.joints)));
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
    for (const BvhPose& pose : rest) {
        low = low.cwiseMin(pose.p_GJ);
        high = high.cwiseMax(pose.p_GJ);
    }
    const double extent = rest.empty() ? 0.0 : (high - low).maxCoeff();
    if (!(extent > 0) || !std::isfinite(extent))
        throw Error(describeMotion(motion) + ": the skeleton has no size in its rest pose, so its length unit cannot be inferred");
    const double kAdultHeight = 1.70;  // m
    const double estimate = kAdultHeight / extent;
    for (double unit : {1.0, 0.3048, 0.0254, 0.01, 0.001})
        if (estimate < 1.5 * unit && estimate > unit / 1.5) return unit;
    return estimate;
}

}  // namespace sinew

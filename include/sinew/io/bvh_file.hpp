#pragma once
// Biovision hierarchy (BVH) motion files (docs/motion-capture.md): a HIERARCHY of joints (ROOT, JOINT, End
// Site), each with an OFFSET from its parent and CHANNELS (any of X/Y/Zposition and X/Y/Zrotation, in any
// order), then MOTION: "Frames: N", "Frame Time: dt" and one row of channel values per frame.
//
// Conventions (those of Biovision's format as BVH tools read it):
// - a joint's frame J sits in its parent's frame P at p_PJ = offset + (Xposition, Yposition, Zposition),
//   its position channels, those it lacks being 0 (a root's offset is added as well);
// - its rotation R_PJ is the product of its rotation channels in the order they are listed, each about the
//   axis of the frame produced so far (intrinsic): "Zrotation Xrotation Yrotation" is Rz(a) Rx(b) Ry(c);
//   angles are in degrees in the file and in `values`; position channels apply before every rotation,
//   wherever they are listed;
// - an End Site has no channels: its frame is its parent's, moved by its offset.
// Lengths are in the file's unit, which BVH does not state (inferBvhLengthUnit).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sinew {

enum class BvhChannel { Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation };

// The channel's name as BVH writes it ("Zrotation").
const char* bvhChannelName(BvhChannel channel);

struct BvhJoint {
    // The name after ROOT or JOINT; an End Site is named "<parent name>_End". Names are unique.
    std::string name;
    int parent = -1;                      // index into BvhMotion::joints; -1 for a ROOT
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // file units, in the parent's frame
    std::vector<BvhChannel> channels = {};              // in file order; none for an End Site
    int firstChannel = 0;                 // column of values holding channels[0]: the channels of the joints before
    bool endSite = false;                 // an End Site: a leaf with an offset and no channels
    int line = 0;                         // the line of its ROOT, JOINT or End Site keyword when read; 0 otherwise
};

struct BvhMotion {
    std::string source;                   // the file it was read from; empty when built in code
    // Depth first, in file order: a joint's parent comes before it and its subtree follows it unbroken,
    // so the joints' channels, in joint order, are the columns of `values`.
    std::vector<BvhJoint> joints;
    double frameTime = 0;                 // s between frames (BVH's "Frame Time")
    Eigen::MatrixXd values;               // (frames x channels) channel values, file units and degrees
    int firstFrameLine = 0;               // the file line of frame 0 when read (frame i on the i-th row line after it)
};

// The frame of a joint in the file's global frame G at one frame of the motion.
struct BvhPose {
    Eigen::Matrix3d R_GJ = Eigen::Matrix3d::Identity();  // the joint frame's axes, in G
    Eigen::Vector3d p_GJ = Eigen::Vector3d::Zero();      // its origin (the joint centre), in G, file units
};

// Throws sinew::Error naming "file:line:column" of a malformed hierarchy (a missing or misplaced keyword,
// brace or number, an unknown or repeated channel, channels on an End Site, a repeated name) and
// "file:line" with the value's number, joint and channel for a motion row (a value that is not a finite
// number, a row of the wrong length, more or fewer rows than Frames, a Frame Time <= 0).
BvhMotion readBvhFile(const std::string& path);

// Writes the motion with 17 significant digits, so that readBvhFile gives back the same numbers bit for
// bit. Throws sinew::Error, before any file is started, for a motion that would not read back (joints out
// of depth-first order, firstChannel or values' width not matching the channels, an End Site with channels
// or children, an empty, blank-holding or repeated name, a non-finite number, a Frame Time <= 0). A
// failed write leaves no file (io/atomic_file.hpp).
void writeBvhFile(const std::string& path, const BvhMotion& motion);

// The index of the joint named `name`, or -1.
int findBvhJoint(const BvhMotion& motion, const std::string& name);

// R_PJ of `joint` at `frame`, from its rotation channels (identity for a joint without them).
Eigen::Matrix3d calcBvhLocalRotation(const BvhMotion& motion, int joint, int frame);

// Every joint's pose (End Sites included) at `frame`, in joint order. Throws sinew::Error for a frame out
// of range.
std::vector<BvhPose> calcBvhPoses(const BvhMotion& motion, int frame);

// Metres per file unit, from the skeleton's size in its rest pose (every channel 0), since BVH does not
// state its unit. The rest pose's largest extent along X, Y or Z (a standing height, or a T-pose's arm
// span, which is about as long) is taken as an adult's 1.70 m; the estimate is snapped to m, cm, mm,
// inch or foot when within a factor 1.5 of it (standing heights from 1.13 m to 2.55 m), and returned as
// it is otherwise. CMU's Poser-style conversions (root `hip`) come out in cm. Throws sinew::Error for a
// skeleton of zero size.
double inferBvhLengthUnit(const BvhMotion& motion);

}  // namespace sinew

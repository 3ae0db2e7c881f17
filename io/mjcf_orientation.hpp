#pragma once
// MJCF orientations: a frame's quat, or one of MuJoCo's alternatives (axisangle, xyaxes, zaxis, euler),
// turned into a unit quaternion as MuJoCo 2.2.2's compiler does it (mjCAlternative::Set, user_objects.cc;
// mjuu_z2quat, user_util.cc). Private to sinew_io.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "mjcf_xml.hpp"

namespace sinew::mjcf {

// The compiler settings orientations depend on (<compiler angle eulerseq>).
struct AngleUnits {
    bool degree = true;                   // angle="degree", MuJoCo's default
    std::string eulerSequence = "xyz";    // lowercase: rotating axes; uppercase: fixed axes
};

// An orientation as written, before the compiler resolves it; a default class may hold one.
struct OrientationSpec {
    Eigen::Vector4d quat = Eigen::Vector4d(1, 0, 0, 0);  // w x y z, normalised when resolved
    std::optional<Eigen::Vector4d> axisAngle;              // axis, angle (degrees or radians)
    std::optional<Eigen::Matrix<double, 6, 1>> xyAxes;     // x axis, y axis (made orthogonal to x)
    std::optional<Eigen::Vector3d> zAxis;                  // the frame's z axis, by the minimal rotation
    std::optional<Eigen::Vector3d> euler;                  // angles of eulerSequence (degrees or radians)
};

// Reads quat and the alternatives of `element` over `spec`. More than one of quat, axisangle, xyaxes,
// zaxis, euler and fullinertia on one element is an error, as in MuJoCo.
void readOrientation(const XmlElement& element, OrientationSpec& spec);

// The unit quaternion (MuJoCo's order of precedence: quat, then axisangle, xyaxes, zaxis, euler override
// it). A zero quaternion or a degenerate axis is an error at `owner`.
Eigen::Quaterniond resolveOrientation(const OrientationSpec& spec, const AngleUnits& units, const XmlElement& owner);

// The minimal rotation taking (0, 0, 1) onto the unit vector `z` (mjuu_z2quat; a half turn about x when z
// points down).
Eigen::Quaterniond calcQuaternionFromZAxis(const Eigen::Vector3d& z);

}  // namespace sinew::mjcf

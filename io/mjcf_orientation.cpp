#include "mjcf_orientation.hpp"

#include <cctype>
#include <cmath>

namespace sinew::mjcf {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEpsilon = 1e-14;  // MuJoCo's mjEPS: below it (a squared norm) a vector is not normalised

double toRadians(double angle, const AngleUnits& units) { return units.degree ? angle / 180.0 * kPi : angle; }

Eigen::Vector3d normalizeOrFail(const Eigen::Vector3d& v, const XmlElement& owner, const char* what) {
    if (v.squaredNorm() < kEpsilon) owner.fail(std::string(what) + " is too small to give a direction");
    return v.normalized();
}

Eigen::Quaterniond fromAxisAngle(const Eigen::Vector4d& axisAngle, const AngleUnits& units, const XmlElement& owner) {
    const Eigen::Vector3d axis = normalizeOrFail(axisAngle.head<3>(), owner, "the axisangle axis");
    return Eigen::Quaterniond(Eigen::AngleAxisd(toRadians(axisAngle[3], units), axis));
}

Eigen::Quaterniond fromXYAxes(const Eigen::Matrix<double, 6, 1>& xy, const XmlElement& owner) {
    const Eigen::Vector3d x = normalizeOrFail(xy.head<3>(), owner, "the xyaxes x axis");
    const Eigen::Vector3d y = normalizeOrFail(xy.tail<3>() - x * x.dot(xy.tail<3>()), owner,
                                              "the xyaxes y axis, made orthogonal to x,");
    const Eigen::Vector3d z = normalizeOrFail(x.cross(y), owner, "cross(xaxis, yaxis)");
    Eigen::Matrix3d R;
    R << x, y, z;
    return Eigen::Quaterniond(R).normalized();
}

// The sequence is three of x, y, z, X, Y, Z (checked where <compiler> is read).
Eigen::Quaterniond fromEuler(const Eigen::Vector3d& euler, const AngleUnits& units) {
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    for (int i = 0; i < 3; ++i) {
        const char axisName = units.eulerSequence[static_cast<std::size_t>(i)];
        const int axis = static_cast<int>(std::string("xyzXYZ").find(axisName) % 3);
        const Eigen::Quaterniond turn(Eigen::AngleAxisd(toRadians(euler[i], units), Eigen::Vector3d::Unit(axis)));
        // Lowercase letters turn about the rotating axes (post-multiply), uppercase about the fixed ones.
        q = std::islower(static_cast<unsigned char>(axisName)) ? q * turn : turn * q;
    }
    return q.normalized();
}

}  // namespace

void readOrientation(const XmlElement& element, OrientationSpec& spec) {
    int given = 0;
    for (const char* name : {"quat", "axisangle", "xyaxes", "zaxis", "euler", "fullinertia"})
        given += element.findAttribute(name) ? 1 : 0;
    if (given > 1) element.fail("more than one of quat, axisangle, xyaxes, zaxis, euler, fullinertia; give one");
    readNumbers(element, "quat", spec.quat.data(), 4);
    Eigen::Vector4d axisAngle;
    if (readNumbers(element, "axisangle", axisAngle.data(), 4)) spec.axisAngle = axisAngle;
    Eigen::Matrix<double, 6, 1> xyAxes;
    if (readNumbers(element, "xyaxes", xyAxes.data(), 6)) spec.xyAxes = xyAxes;
    Eigen::Vector3d vector;
    if (readVector3(element, "zaxis", vector)) spec.zAxis = vector;
    if (readVector3(element, "euler", vector)) spec.euler = vector;
}

Eigen::Quaterniond resolveOrientation(const OrientationSpec& spec, const AngleUnits& units, const XmlElement& owner) {
    if (spec.quat.squaredNorm() < kEpsilon) owner.fail("quat is zero; expected a rotation quaternion (w x y z)");
    const Eigen::Vector4d unit = spec.quat.normalized();
    Eigen::Quaterniond q(unit[0], unit[1], unit[2], unit[3]);
    if (spec.axisAngle) q = fromAxisAngle(*spec.axisAngle, units, owner);
    if (spec.xyAxes) q = fromXYAxes(*spec.xyAxes, owner);
    if (spec.zAxis) q = calcQuaternionFromZAxis(normalizeOrFail(*spec.zAxis, owner, "zaxis"));
    if (spec.euler) q = fromEuler(*spec.euler, units);
    return q;
}

Eigen::Quaterniond calcQuaternionFromZAxis(const Eigen::Vector3d& z) {
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ().cross(z);
    const double s = axis.norm();
    axis = s < 1e-10 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d(axis / s);
    const double angle = std::atan2(s, z.z());
    return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis));
}

}  // namespace sinew::mjcf

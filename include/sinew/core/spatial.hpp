#pragma once
// Spatial (6D) algebra in Featherstone's form, all quantities in ground coordinates about the ground origin:
// motion vectors [angular velocity; velocity of the body point at the origin], force vectors [moment about
// the origin; force]. Featherstone, Rigid Body Dynamics Algorithms (2008), ch. 2.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sinew {

using SpatialVector = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

inline Eigen::Matrix3d skew(const Eigen::Vector3d& p) {
    Eigen::Matrix3d m;
    m << 0, -p.z(), p.y(), p.z(), 0, -p.x(), -p.y(), p.x(), 0;
    return m;
}

// v x m for motion vectors (RBDA eq. 2.31).
inline SpatialVector crossMotion(const SpatialVector& v, const SpatialVector& m) {
    SpatialVector r;
    r.head<3>() = v.head<3>().cross(m.head<3>());
    r.tail<3>() = v.tail<3>().cross(m.head<3>()) + v.head<3>().cross(m.tail<3>());
    return r;
}

// v x* f for force vectors (RBDA eq. 2.32).
inline SpatialVector crossForce(const SpatialVector& v, const SpatialVector& f) {
    SpatialVector r;
    r.head<3>() = v.head<3>().cross(f.head<3>()) + v.tail<3>().cross(f.tail<3>());
    r.tail<3>() = v.head<3>().cross(f.tail<3>());
    return r;
}

// The same force with its moment taken about a point `offset` away from the current one:
// n' = n - offset x f.
inline SpatialVector shiftForce(const SpatialVector& F, const Eigen::Vector3d& offset) {
    SpatialVector r = F;
    r.head<3>() -= offset.cross(F.tail<3>());
    return r;
}

// The same motion with its linear part taken at a point `offset` away: v' = v + w x offset.
inline SpatialVector shiftMotion(const SpatialVector& V, const Eigen::Vector3d& offset) {
    SpatialVector r = V;
    r.tail<3>() += V.head<3>().cross(offset);
    return r;
}

// Spatial inertia about the ground origin of mass m with centre of mass c and central inertia Ic, all in
// ground axes (RBDA eq. 2.63).
inline Matrix6d calcSpatialInertia(double mass, const Eigen::Vector3d& c, const Eigen::Matrix3d& Ic) {
    const Eigen::Matrix3d cx = skew(c);
    Matrix6d I;
    I.topLeftCorner<3, 3>() = Ic + mass * cx * cx.transpose();
    I.topRightCorner<3, 3>() = mass * cx;
    I.bottomLeftCorner<3, 3>() = mass * cx.transpose();
    I.bottomRightCorner<3, 3>() = mass * Eigen::Matrix3d::Identity();
    return I;
}

// OpenSim's orientation angles (PhysicalOffsetFrame orientation, WrapObject xyz_body_rotation): a body-fixed
// X-Y-Z sequence, R = Rx(a) Ry(b) Rz(c) (Simbody's Rotation::setRotationToBodyFixedXYZ).
inline Eigen::Matrix3d calcRotationFromBodyFixedXYZ(const Eigen::Vector3d& angles) {
    return (Eigen::AngleAxisd(angles[0], Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(angles[1], Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(angles[2], Eigen::Vector3d::UnitZ()))
        .toRotationMatrix();
}

}  // namespace sinew

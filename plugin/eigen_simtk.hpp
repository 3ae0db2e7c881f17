#pragma once
// Conversions between sinew's Eigen types and Simbody's, for the plugin's sources (not installed).
#include "sinew/plugin/ndebug_guard.hpp"

#include <Eigen/Core>
#include <Simbody.h>

namespace sinew {

inline SimTK::Vec3 toVec3(const Eigen::Vector3d& v) { return SimTK::Vec3(v[0], v[1], v[2]); }

inline Eigen::Vector3d toEigen(const SimTK::Vec3& v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

inline SimTK::Rotation toRotation(const Eigen::Matrix3d& R) {
    SimTK::Mat33 m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m(r, c) = R(r, c);
    return SimTK::Rotation(m);
}

inline Eigen::Matrix3d toEigen(const SimTK::Rotation& R) {
    Eigen::Matrix3d m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m(r, c) = R[r][c];
    return m;
}

}  // namespace sinew

#pragma once
// Mass properties of MJCF bodies as MuJoCo 2.2.2's compiler sets them (mjCGeom::Compile, GetVolume,
// SetInertia; mjCBody::GeomFrame and Compile, user_objects.cc): a geom's frame from fromto, its mass from
// mass or density times volume and its principal moments in closed form; a body's inertial frame from its
// <inertial> or its geoms, then the compiler's boundmass and boundinertia. Private to sinew_io.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mjcf_document.hpp"

namespace sinew::mjcf {

constexpr double kMinValue = 1e-15;  // MuJoCo's mjMINVAL

// A geom compiled: its frame in the body, its size after fromto, its mass and principal moments about its
// centre in its own axes.
struct CompiledGeom {
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();
    Eigen::Quaterniond quat = Eigen::Quaterniond::Identity();
    Eigen::Vector3d size = Eigen::Vector3d::Zero();
    double mass = 0;                                    // kg
    Eigen::Vector3d inertia = Eigen::Vector3d::Zero();  // kg m^2
};

// Throws ModelError at the geom for what MuJoCo's compiler refuses (sizes <= 0, fromto on a sphere, both
// pos and fromto). Mesh geoms are not compiled (their files are not read).
CompiledGeom compileGeom(const MjcfGeom& geom);

// MuJoCo's body_mass, body_ipos, body_iquat and body_inertia.
struct MassProperties {
    double mass = 0;                                           // kg
    Eigen::Vector3d com = Eigen::Vector3d::Zero();             // m, in the body frame
    Eigen::Quaterniond principalAxes = Eigen::Quaterniond::Identity();  // in the body frame
    Eigen::Vector3d principalMoments = Eigen::Vector3d::Zero();         // kg m^2
    Eigen::Matrix3d calcInertia() const;  // about the centre of mass, in body axes
};

// Body `body` (not the world) as compiled; mesh geoms take no part, as on a copy of the model without its
// mesh files. Throws ModelError at the body (or its inertial or geom) for what MuJoCo refuses: several
// geoms without mass, moments breaking A + B >= C without balanceinertia, a fullinertia that is not
// positive definite.
MassProperties calcBodyMassProperties(const MjcfModel& model, int body);

}  // namespace sinew::mjcf

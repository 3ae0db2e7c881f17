#pragma once
// An MJCF model read into plain structs: includes expanded, default classes and childclasses applied,
// angles in radians and orientations as unit quaternions, names resolved to indices, and nothing compiled
// yet (no inertia from geoms, no frames composed). Values absent from the XML take MuJoCo 2.2.2's
// defaults. What the reader recognises but sinew does not model is listed in `unsupported`, never dropped
// in silence. Private to sinew_io; the converter (mjcf_model_converter.cpp) turns it into a sinew Model.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "mjcf_defaults.hpp"

namespace sinew::mjcf {

enum class InertiaFromGeom { False, True, Auto };

struct CompilerSettings {
    AngleUnits angles;
    InertiaFromGeom inertiaFromGeom = InertiaFromGeom::Auto;
    std::array<int, 2> inertiaGroupRange{0, 5};  // geoms of these groups give a body its inertia
    double boundMass = 0, boundInertia = 0;      // kg, kg m^2: floors on every body's mass and principal moments
    double setTotalMass = -1;                    // kg; positive: all masses and inertias scaled to this total
    bool balanceInertia = false;                 // replace moments breaking A + B >= C by their mean
    bool autoLimits = false;                     // MuJoCo 2.2.2's default
    bool discardVisual = false;                  // drop geoms that collide with nothing (contype = conaffinity = 0)
};

struct MjcfJoint {
    std::string name;  // the joint's name, or "<body>_joint<k>" for an unnamed one
    JointKind type = JointKind::Hinge;
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();   // m, anchor in the body frame (zero for free joints)
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ(); // unit, body frame (hinge, slide)
    bool limited = false;
    double rangeMin = 0, rangeMax = 0;  // rad (hinge; ball: rangeMax the largest angle) or m (slide)
    double ref = 0;                     // rad or m: qpos0 of a hinge or slide
    double springref = 0, stiffness = 0, damping = 0, armature = 0, frictionloss = 0;
    std::string where;
};

struct MjcfInertial {
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();  // m, centre of mass in the body frame
    Eigen::Quaterniond quat = Eigen::Quaterniond::Identity();  // principal axes in the body frame
    double mass = 0;                                           // kg
    Eigen::Vector3d diagonal = Eigen::Vector3d::Zero();        // kg m^2, principal moments
    std::optional<Eigen::Matrix<double, 6, 1>> full;  // fullinertia Ixx Iyy Izz Ixy Ixz Iyz in the body frame
    std::string where;
};

struct MjcfBody {
    std::string name;  // the body's name, or "body<id>" for an unnamed one (MuJoCo's id, world = 0)
    int parent = -1;   // index into MjcfModel::bodies; -1 for the world
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();             // m, in the parent frame
    Eigen::Quaterniond quat = Eigen::Quaterniond::Identity();  // orientation in the parent frame
    std::optional<MjcfInertial> inertial;
    std::vector<MjcfJoint> joints;  // in file order, which is MuJoCo's order of composition
    bool mocap = false;
    std::string where;
};

struct MjcfGeom {
    std::string name;
    int body = 0;
    GeomKind type = GeomKind::Sphere;
    Eigen::Vector3d size = Eigen::Vector3d::Zero();
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();             // m, in the body frame
    Eigen::Quaterniond quat = Eigen::Quaterniond::Identity();  // in the body frame
    std::optional<Eigen::Matrix<double, 6, 1>> fromto;         // m, replaces pos, quat and the length
    std::optional<double> mass;
    double density = 1000;
    int group = 0;
    std::string mesh;
    std::string where;
};

struct MjcfSite {
    std::string name;
    int body = 0;
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();  // m, in the body frame
    std::string where;
};

// One entry of a tendon's path: a site, a wrapping geom (with its optional side site), a pulley, or (fixed
// tendons) a joint.
struct MjcfPathEntry {
    enum class Kind { Site, Geom, Pulley, Joint };
    Kind kind = Kind::Site;
    int object = -1;    // site or geom index (joints: unresolved, `name` only)
    int sideSite = -1;  // geom wraps: the side site's index, or -1
    std::string name;
    double divisor = 0;  // pulley
    std::string where;
};

struct MjcfTendon {
    std::string name;
    bool spatial = true;  // false for a fixed tendon
    std::vector<MjcfPathEntry> path;
    bool limited = false;
    double rangeMin = 0, rangeMax = 0;
    double stiffness = 0, damping = 0, frictionloss = 0, springlength = -1;
    std::string where;
};

struct MjcfActuator {
    std::string name;
    std::string tag;               // general, muscle, motor, ...
    std::string transmission;      // joint, tendon, site, body, jointinparent, cranksite, or "" for none
    std::string target;            // the transmission's object, by name
    int tendon = -1;               // index into MjcfModel::tendons for a tendon transmission
    ActuatorParams params;
    std::string where;
};

struct MjcfEquality {
    std::string tag;  // connect, weld, joint, tendon
    std::string name;
    bool active = true;
    std::string name1, name2;  // bodies, joints or tendons; name2 may be empty
    std::array<double, 5> polycoef{0, 1, 0, 0, 0};
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  // m, in body1 (connect)
    std::string where;
};

// An element the reader recognises and sinew's model has no place for.
struct MjcfUnsupported {
    std::string tag, name, where, why;
};

struct MjcfModel {
    std::string name;
    std::string file;
    CompilerSettings compiler;
    Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.81);  // m/s^2, world frame
    std::vector<MjcfBody> bodies;  // [0] is the world; parents before children (MuJoCo's body ids)
    std::vector<MjcfGeom> geoms;
    std::vector<MjcfSite> sites;
    std::vector<MjcfTendon> tendons;
    std::vector<MjcfActuator> actuators;
    std::vector<MjcfEquality> equalities;
    std::vector<MjcfUnsupported> unsupported;
};

// Throws ModelError at "file:line" naming the element and what was expected: malformed XML or numbers, a
// missing or repeated include, an unknown class, body, joint, site, geom or tendon name, a value MuJoCo's
// compiler refuses (a range without limited under autolimits="false", a repeated name).
MjcfModel readMjcfDocument(const std::string& path);

int findBody(const MjcfModel& model, const std::string& name);    // -1 when absent
// The joint's index among its body's joints, its body in `body`; -1 when absent.
int findJoint(const MjcfModel& model, const std::string& name, int& body);

}  // namespace sinew::mjcf

#pragma once
// MJCF default classes (MuJoCo 2.2.2's mjCDef and mjXReader::Default): each class holds a value for every
// attribute of joints, geoms, sites, tendons, actuators and equality constraints; a nested class starts as
// a copy of its parent, and an element starts from its class (its own class attribute, else its body's
// childclass, inherited down the body tree, else "main") and overrides what it writes. The parameter
// structs hold values as written (degrees stay degrees); the reader converts them. Private to sinew_io.
#include <Eigen/Core>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mjcf_orientation.hpp"
#include "mjcf_xml.hpp"

namespace sinew::mjcf {

enum class JointKind { Free, Ball, Slide, Hinge };  // mjtJoint's order
enum class GeomKind { Plane, HeightField, Sphere, Capsule, Ellipsoid, Cylinder, Box, Mesh };  // mjtGeom's order
const char* toString(GeomKind kind);

struct JointParams {
    JointKind type = JointKind::Hinge;
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();       // m, anchor in the body frame
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();      // in the body frame, as written
    int limited = 2;                                      // false, true, auto
    Eigen::Vector2d range = Eigen::Vector2d::Zero();      // degrees or rad (hinge), m (slide)
    double ref = 0, springref = 0;                        // qpos0 and the spring's rest value
    double stiffness = 0, damping = 0, armature = 0, frictionloss = 0;
    Eigen::Vector2d springdamper = Eigen::Vector2d::Zero();
};

struct GeomParams {
    GeomKind type = GeomKind::Sphere;
    Eigen::Vector3d size = Eigen::Vector3d::Zero();
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();
    OrientationSpec orientation;
    std::optional<Eigen::Matrix<double, 6, 1>> fromto;
    std::optional<double> mass;  // kg; absent: density times volume
    double density = 1000;       // kg/m^3
    int group = 0;
    int contype = 1, conaffinity = 1;
    std::string mesh, hfield;
};

struct SiteParams {
    GeomKind type = GeomKind::Sphere;
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();
    std::optional<Eigen::Matrix<double, 6, 1>> fromto;
};

struct TendonParams {
    int limited = 2;
    Eigen::Vector2d range = Eigen::Vector2d::Zero();  // m
    double stiffness = 0, damping = 0, frictionloss = 0;
    double springlength = -1;  // m; negative: the length at qpos0
};

enum class DynamicsKind { None, Integrator, Filter, Muscle, User };  // mjtDyn
enum class GainKind { Fixed, Affine, Muscle, User };                   // mjtGain
enum class BiasKind { None, Affine, Muscle, User };                    // mjtBias

// Every actuator element (general, motor, position, muscle, ...) writes into these; the shortcut elements
// set their implied types and parameters as MuJoCo's OneActuator does.
struct ActuatorParams {
    DynamicsKind dyntype = DynamicsKind::None;
    GainKind gaintype = GainKind::Fixed;
    BiasKind biastype = BiasKind::None;
    std::array<double, 10> dynprm{1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    std::array<double, 10> gainprm{1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    std::array<double, 10> biasprm{};
    Eigen::Vector2d lengthrange = Eigen::Vector2d::Zero();  // m (tendon actuators)
    std::array<double, 6> gear{1, 0, 0, 0, 0, 0};
};

struct EqualityParams {
    bool active = true;
};

// Reads the attributes these structs hold from `element` over `params` (the actuator's by its tag).
void readJointParams(const XmlElement& element, JointParams& params);
void readGeomParams(const XmlElement& element, GeomParams& params);
void readSiteParams(const XmlElement& element, SiteParams& params);
void readTendonParams(const XmlElement& element, TendonParams& params);
void readActuatorParams(const XmlElement& element, ActuatorParams& params);
void readEqualityParams(const XmlElement& element, EqualityParams& params);
bool isActuatorTag(const std::string& tag);

struct DefaultClass {
    std::string name;
    JointParams joint;
    GeomParams geom;
    SiteParams site;
    TendonParams tendon;
    ActuatorParams actuator;
    EqualityParams equality;
};

class DefaultClasses {
public:
    DefaultClasses();  // "main" with MuJoCo's built-in values
    // A top-level <default> section (class "main" unless it names another), with its nested classes.
    void readSection(const XmlElement& section);
    const DefaultClass& getMain() const { return classes_.front(); }
    // The class `name`; an unknown name is an error at `referrer`.
    const DefaultClass& find(const std::string& name, const XmlElement& referrer) const;
    // The class an element uses: its class attribute if it has one, else `inherited`.
    const DefaultClass& findFor(const XmlElement& element, const DefaultClass& inherited) const;

private:
    void readClass(const XmlElement& section, std::size_t index);

    std::vector<DefaultClass> classes_;  // stable indices: a child copies its parent when it is created
    std::map<std::string, std::size_t> byName_;
};

}  // namespace sinew::mjcf

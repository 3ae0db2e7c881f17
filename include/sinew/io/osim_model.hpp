#pragma once
// An OpenSim 4 model file (.osim) read into plain structs: everything a converter needs to build a sinew
// model, as OpenSim defines it, with nothing evaluated. Sockets are resolved (frames to the body they are
// fixed on, coordinates and wrap objects checked to exist); values absent from the XML take OpenSim's
// defaults; anything the reader does not capture is listed in OsimModel::unsupported, never dropped in
// silence. See docs/opensim-files.md for the conventions.
#include <Eigen/Core>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sinew/io/osim_actuator.hpp"
#include "sinew/core/spatial.hpp"
#include "sinew/io/osim_function.hpp"

namespace sinew {

// Orientations are OpenSim's body-fixed X-Y-Z angles: calcRotationFromBodyFixedXYZ (sinew/core/spatial.hpp).

// A frame, resolved to the body (or ground) it is fixed on: a point p_F in the frame is p_BF + R_BF p_F in
// the body.
struct OsimFrameRef {
    std::string path;  // the frame's absolute component path, e.g. "/jointset/knee_r/femur_r_offset"
    std::string body;  // body name, or the ground's name
    Eigen::Vector3d p_BF = Eigen::Vector3d::Zero();     // m
    Eigen::Matrix3d R_BF = Eigen::Matrix3d::Identity();
};

// A PhysicalOffsetFrame: owned by a joint, a body or the model's ComponentSet.
struct OsimFrame {
    std::string name;
    std::string parentPath;                                 // absolute path of the frame it is offset from
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // m, in the parent frame
    Eigen::Vector3d orientation = Eigen::Vector3d::Zero();  // rad, body-fixed XYZ in the parent frame
    OsimFrameRef resolved;                                  // the whole chain of offsets, down to a body
    std::string where;                                      // "file:line" of its XML element
};

struct OsimWrapObject {
    enum class Shape { Sphere, Cylinder, Ellipsoid, Torus };
    std::string name;
    std::string body;  // the body (or ground) whose WrapObjectSet holds it
    Shape shape = Shape::Sphere;
    double radius = 0;  // m: Sphere, Cylinder
    double length = 0;  // m: Cylinder (along its z axis, centred on its origin)
    Eigen::Vector3d dimensions = Eigen::Vector3d::Zero();  // m: Ellipsoid radii along its x, y, z
    double innerRadius = 0, outerRadius = 0;                // m: Torus
    Eigen::Vector3d xyzBodyRotation = Eigen::Vector3d::Zero();  // rad, body-fixed XYZ of the object in the body
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();      // m, the object's origin in the body
    std::string quadrant = "Unassigned";  // "all", "x", "-y", ...: the side the path wraps over
    bool active = true;
    std::string where;
};

struct OsimBody {
    std::string name;
    double mass = 0;                                       // kg
    Eigen::Vector3d massCenter = Eigen::Vector3d::Zero();  // m, in the body frame
    // kg m^2, [Ixx Iyy Izz Ixy Ixz Iyz] about the mass centre in body axes (OpenSim's order).
    Eigen::Matrix<double, 6, 1> inertia = Eigen::Matrix<double, 6, 1>::Zero();
    std::vector<OsimWrapObject> wrapObjects;
    std::string where;
};

enum class OsimMotionType { Rotational, Translational, Coupled };

struct OsimCoordinate {
    std::string name;
    int joint = 0;  // index into OsimModel::joints
    // Given by <motion_type> when present, else inferred as OpenSim does: CustomJoint coordinates from the
    // axes they drive with slope +-1 linear functions (rotation1-3 Rotational, translation1-3
    // Translational, other functions only: Coupled); other joints from their type.
    OsimMotionType motionType = OsimMotionType::Rotational;
    double defaultValue = 0;       // rad or m
    double defaultSpeedValue = 0;  // rad/s or m/s
    double rangeMin = -10, rangeMax = 10;
    bool clamped = false, locked = false, prescribed = false;
    std::optional<OsimFunction> prescribedFunction;  // of time
    std::string where;
};

// One of a CustomJoint's six axes: rotation1-3 turn about `axis` by f(q), translation1-3 slide along it.
struct OsimTransformAxis {
    std::vector<std::string> coordinates;  // the function's arguments, in order
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // in the joint's parent frame F, as written
    OsimFunction function;                 // OpenSim's default when absent: Constant 0
};

enum class OsimJointType { Custom, Pin, Slider, Weld, Ball, Gimbal, Universal, Planar, Free };

const char* toString(OsimJointType type);

struct OsimJoint {
    std::string name;
    OsimJointType type = OsimJointType::Custom;
    OsimFrameRef parent;  // socket_parent_frame, resolved
    OsimFrameRef child;   // socket_child_frame, resolved
    // The joint's coordinates: OsimModel::coordinates[firstCoordinate, firstCoordinate + numCoordinates),
    // in OpenSim's order (a CustomJoint's in order of first use by rotation1 ... translation3).
    int firstCoordinate = 0, numCoordinates = 0;
    // CustomJoint only: rotation1, rotation2, rotation3, translation1, translation2, translation3.
    std::array<OsimTransformAxis, 6> spatialTransform;
    std::string where;
};

// dependent = scaleFactor * function(independent...).
struct OsimCoordinateCoupler {
    std::string name;
    bool enforced = true;
    std::string dependentCoordinate;
    std::vector<std::string> independentCoordinates;
    OsimFunction function;
    double scaleFactor = 1;
    std::string where;
};

struct OsimPathPoint {
    enum class Type { Fixed, Conditional, Moving };
    std::string name;
    Type type = Type::Fixed;
    OsimFrameRef frame;                                  // socket_parent_frame, resolved
    Eigen::Vector3d location = Eigen::Vector3d::Zero();  // m, in `frame` (Fixed, Conditional)
    // Conditional: in the path only while rangeMin <= value of `coordinate` <= rangeMax (rad or m).
    std::string coordinate;
    double rangeMin = 0, rangeMax = 0;
    // Moving: location[i] = locationFunctions[i](value of locationCoordinates[i]) in `frame`, the value
    // clamped to that coordinate's range first (as OpenSim does); a function with no coordinate is
    // evaluated at 0.
    std::array<OsimFunction, 3> locationFunctions;
    std::array<std::string, 3> locationCoordinates;
    std::string where;
};

struct OsimPathWrap {
    std::string wrapObject;  // name, found on `body`
    std::string body;
    std::string method = "hybrid";  // "hybrid", "midpoint" or "axial"
    int rangeBegin = -1, rangeEnd = -1;  // 1-based path points wrapping applies between; -1: the whole path
    std::string where;
};

struct OsimGeometryPath {
    std::vector<OsimPathPoint> points;
    std::vector<OsimPathWrap> wraps;
    std::string where;
};

// A force along a GeometryPath: a muscle, a PathActuator, a Ligament or a PathSpring.
struct OsimPathForce {
    enum class Kind { Muscle, PathActuator, Ligament, PathSpring };
    std::string type;  // the XML type after OpenSim's renames, e.g. "Thelen2003Muscle"
    Kind kind = Kind::Muscle;
    std::string name;
    OsimGeometryPath path;
    // Muscles and PathActuators; minControl/maxControl default to the type's own (Thelen2003Muscle and
    // Millard2012*: minimum_activation (0.01) .. 1; other muscles 0 .. 1; PathActuator unbounded).
    OsimActuatorLimits limits;
    // Muscles (OpenSim's Muscle defaults when absent).
    double maxIsometricForce = 1000;      // N
    double optimalFiberLength = 0.1;      // m
    double tendonSlackLength = 0.2;       // m
    double pennationAngleAtOptimal = 0;   // rad
    double maxContractionVelocity = 10;   // optimal fibre lengths per second
    // Every other scalar property as written, by name; properties of nested objects (e.g. a Millard
    // muscle's ActiveForceLengthCurve) as "Object.property". Ligament: resting_length, pcsa_force;
    // PathSpring: resting_length, stiffness, dissipation.
    std::map<std::string, std::string> properties;
    // Function-valued properties by name (Ligament force_length_curve, Schutte/Delp muscle curves).
    std::map<std::string, OsimFunction> curves;
    std::string where;
};

struct OsimMarker {
    std::string name;
    OsimFrameRef frame;
    Eigen::Vector3d location = Eigen::Vector3d::Zero();  // m, in `frame`
    bool fixed = false;
    std::string where;
};

// Force elements other than path forces and actuators (docs/force-elements.md), in OpenSim's units as
// written: CoordinateLimitForce's limits and transition in degrees for a rotational coordinate, its
// stiffnesses and damping per degree.
struct OsimContactGeometry {
    std::string name;
    std::string type;  // "ContactSphere" or "ContactHalfSpace"
    OsimFrameRef frame;  // the geometry's frame: socket_frame with location and orientation applied
    double radius = 0;   // m, sphere
    std::string where;
};

struct OsimCoordinateLimitForce {
    std::string name, coordinate;
    double upperStiffness = 1, upperLimit = 0, lowerStiffness = 1, lowerLimit = 0, damping = 0.001, transition = 0.1;
    bool appliesForce = true;
    std::string where;
};

struct OsimPointToPointSpring {
    std::string name;
    OsimFrameRef point1, point2;  // each point as a frame origin on its body
    double stiffness = 1, restLength = 0;
    bool appliesForce = true;
    std::string where;
};

struct OsimBushingForce {
    std::string name;
    OsimFrameRef frame1, frame2;
    Eigen::Vector3d rotationalStiffness = Eigen::Vector3d::Zero(), translationalStiffness = Eigen::Vector3d::Zero();
    Eigen::Vector3d rotationalDamping = Eigen::Vector3d::Zero(), translationalDamping = Eigen::Vector3d::Zero();
    bool appliesForce = true;
    std::string where;
};

struct OsimHuntCrossleyForce {
    struct Parameters {
        std::vector<std::string> geometry;  // contact geometry names
        double stiffness = 0, dissipation = 0, staticFriction = 0, dynamicFriction = 0, viscousFriction = 0;
    };
    std::string name;
    std::vector<Parameters> parameters;
    double transitionVelocity = 0.01;
    bool appliesForce = true;
    std::string where;
};

// Something in the file the reader does not capture (a force, constraint, joint or wrap type, a model-level
// element it does not know), so a converter can refuse or warn.
struct OsimUnsupported {
    std::string type;  // XML element type
    std::string name;  // its name attribute, if any
    std::string where;
};

struct OsimModel {
    std::string name;
    std::string file;  // the path it was read from
    int version = 0;   // OpenSimDocument Version, e.g. 40000
    Eigen::Vector3d gravity = Eigen::Vector3d(0, -9.80665, 0);  // m/s^2, in ground
    std::string lengthUnits = "meters", forceUnits = "N";
    OsimBody ground;  // name "ground"; mass 0; may hold wrap objects
    std::vector<OsimBody> bodies;
    std::vector<OsimFrame> frames;  // every PhysicalOffsetFrame
    std::vector<OsimJoint> joints;
    std::vector<OsimCoordinate> coordinates;  // grouped by joint, in joint order
    std::vector<OsimCoordinateCoupler> couplers;
    std::vector<OsimPathForce> pathForces;
    std::vector<OsimCoordinateActuator> coordinateActuators;
    std::vector<OsimPointActuator> pointActuators;
    std::vector<OsimTorqueActuator> torqueActuators;
    std::vector<OsimMarker> markers;
    std::vector<OsimContactGeometry> contactGeometry;
    std::vector<OsimCoordinateLimitForce> coordinateLimits;
    std::vector<OsimPointToPointSpring> springs;
    std::vector<OsimBushingForce> bushings;
    std::vector<OsimHuntCrossleyForce> huntCrossley;
    std::vector<OsimUnsupported> unsupported;
};

// Throws ModelError at "file:line" naming the element and what was expected: malformed XML, a missing
// required value, a socket naming a body, frame, coordinate or wrap object that does not exist, an unknown
// function type. OpenSim 3.x files (Version < 40000) are refused with a message saying how to convert them.
OsimModel readOsimModel(const std::string& path);

// Lookups by name; nullptr when absent.
const OsimBody* findBody(const OsimModel& model, const std::string& name);
const OsimCoordinate* findCoordinate(const OsimModel& model, const std::string& name);
const OsimJoint* findJoint(const OsimModel& model, const std::string& name);
const OsimPathForce* findPathForce(const OsimModel& model, const std::string& name);

}  // namespace sinew

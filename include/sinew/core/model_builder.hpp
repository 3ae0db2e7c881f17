#pragma once
// Builds a validated, immutable Model from element descriptions that refer to each other by name. Every
// element carries `where` (e.g. "arm.yaml:14"), which prefixes the ModelError it causes.
#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

struct LinkSpec {
    std::string name;
    double mass = 0;                                         // kg
    Eigen::Vector3d com_B = Eigen::Vector3d::Zero();         // m
    Eigen::Matrix3d inertia_Bcom = Eigen::Matrix3d::Zero();  // kg m^2 about the centre of mass
    std::string where;
};

// One TransformAxis of a custom joint (OpenSim's names: rotation1-3, translation1-3).
struct TransformAxisSpec {
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // in F, non-zero; normalised at build, as Simbody does
    std::string coordinate;  // one of the joint's coordinates, or empty for none
    // Absent: linear(1, 0) of the coordinate (OpenSim's default), or constant(0) without a coordinate.
    std::optional<Function> function;
};

// A custom joint's coordinate (OpenSim's Coordinate); other joint types name theirs after the joint.
struct CoordinateSpec {
    std::string name;
    double defaultValue = 0;  // rad or m
    double rangeMin = -std::numeric_limits<double>::infinity();
    double rangeMax = std::numeric_limits<double>::infinity();
    bool clamped = false;
    bool locked = false;
    std::string where;
};

struct JointSpec {
    std::string name;
    JointType type = JointType::Ball;
    std::string parent;  // link name or "ground"
    std::string child;
    Eigen::Vector3d p_PF = Eigen::Vector3d::Zero();  // m, joint centre in the parent frame
    Eigen::Vector3d p_BM = Eigen::Vector3d::Zero();  // m, joint centre in the child frame
    std::optional<Eigen::Vector3d> axis;             // pin only: rotation axis, in the parent (and child) frame
    // Initial pose: rotation vector (rad, in F; ball and free), angle (rad; pin), position of M in F (m; free).
    std::optional<Eigen::Vector3d> initialRotation;
    std::optional<double> initialAngle;
    std::optional<Eigen::Vector3d> initialPosition;
    // Custom and weld joints: orientation of F in the parent and of M in the child (rotation matrices).
    std::optional<Eigen::Matrix3d> R_PF, R_BM;
    // Custom joints only: exactly six axes, and the coordinates they name (ordered at build by first
    // appearance in the axes, as OpenSim orders them; each must be used).
    std::vector<TransformAxisSpec> transformAxes;
    std::vector<CoordinateSpec> coordinates;
    std::string where;
};

struct VirtualLinkSpec {
    std::string name;
    Eigen::Vector3d initialPosition = Eigen::Vector3d::Zero();  // m, in ground
    std::string where;
};

struct LoopSpec {
    std::string name;
    std::string linkA;
    Eigen::Vector3d p_A = Eigen::Vector3d::Zero();
    std::string linkB;
    Eigen::Vector3d p_B = Eigen::Vector3d::Zero();
    std::string where;
};

// OpenSim's CoordinateCouplerConstraint with one independent coordinate: dependent = scaleFactor *
// function(independent). Both must be pin or custom-joint coordinates; a coordinate is dependent in one
// coupler at most, and a dependent coordinate drives no coupler (no chains).
struct CoordinateCouplerSpec {
    std::string name;
    std::string dependentCoordinate;
    std::string independentCoordinate;
    Function function = Function::linear(1, 0);
    double scaleFactor = 1;
    std::string where;
};

// OpenSim's ConditionalPathPoint: the point is on the path while `coordinate` lies in [min, max].
struct WirePointConditionSpec {
    std::string coordinate;
    double min = 0, max = 0;  // rad or m
};

// One moving component of an OpenSim MovingPathPoint: p_B[axis] = function(coordinate).
struct WirePointMotionSpec {
    int axis = 0;  // 0, 1, 2 for x, y, z
    std::string coordinate;
    Function function;
};

struct WirePointSpec {
    std::string link;
    Eigen::Vector3d p_B = Eigen::Vector3d::Zero();  // m; a moving component's entry is ignored
    std::string where;
    std::optional<WirePointConditionSpec> condition = std::nullopt;
    std::vector<WirePointMotionSpec> motions = {};  // at most one per axis
};

struct WrapObjectSpec {
    std::string name;
    WrapShape shape = WrapShape::Sphere;
    std::string link;
    Eigen::Vector3d xyzBodyRotation = Eigen::Vector3d::Zero();  // rad, body-fixed X-Y-Z
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();      // m, W's origin in the link frame
    double radius = 0;                                // m, sphere and cylinder
    double length = 0;                                // m, cylinder
    Eigen::Vector3d radii = Eigen::Vector3d::Zero();  // m, ellipsoid
    std::string quadrant = "all";                     // OpenSim's words: all, x, +x, -x, y, ..., -z
    std::string where;
};

// OpenSim's PathWrap, or one wrap of a MuJoCo spatial tendon. The range counts the wire's points from 0 and
// is inclusive; absent ends are the wire's first and last points. The MuJoCo method takes a sphere or a
// cylinder and two adjacent points (lastPoint == firstPoint + 1), the one segment MuJoCo wraps.
struct WireWrapSpec {
    std::string object;
    std::optional<int> firstPoint, lastPoint;
    WrapMethod method = WrapMethod::Hybrid;
    // MuJoCo method only: the side site (m) in the frame of link sideSiteLink, empty for the wrap object's link.
    std::optional<Eigen::Vector3d> sideSite;
    std::string sideSiteLink;
    std::string where;
};

struct WireSpec {
    std::string name;
    WireKind kind = WireKind::Muscle;
    std::vector<WirePointSpec> points;
    std::vector<WireWrapSpec> wraps;
    ForceLawSpec law;
    std::optional<double> strength;      // N, > 0 when given (Wire::strength)
    std::optional<double> crossSection;  // m^2, > 0 when given (Wire::crossSection)
    std::string where;
    std::string lawWhere;  // where the force law is written, for its errors; `where` when empty
};

// A link the model names as a foot (Contact): its sole polygon in the link frame, and mu.
struct ContactSpec {
    std::string name;
    std::string link;
    std::vector<Eigen::Vector3d> sole_B;  // m, at least one vertex
    double friction = 0.8;                // >= 0
    std::string where;
};

// Force elements (force_elements.hpp) by name: links ("ground" allowed), coordinates and contact geometry.
// Frames are a translation and body-fixed X-Y-Z angles (rad) in their link, as OpenSim's offset frames.
struct LinkFrameSpec {
    std::string link;
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();      // m
    Eigen::Vector3d xyzBodyRotation = Eigen::Vector3d::Zero();  // rad
};

struct CoordinateLimitForceSpec {
    std::string name, coordinate;
    double upperStiffness = 0, upperLimit = 0, lowerStiffness = 0, lowerLimit = 0, damping = 0, transition = 0;
    std::string where;
};

struct PointToPointSpringSpec {
    std::string name, linkA, linkB;
    Eigen::Vector3d pointA = Eigen::Vector3d::Zero(), pointB = Eigen::Vector3d::Zero();
    double stiffness = 0, restLength = 0;
    std::string where;
};

struct BushingForceSpec {
    std::string name;
    LinkFrameSpec frameA, frameB;
    Eigen::Vector3d rotationalStiffness = Eigen::Vector3d::Zero(), translationalStiffness = Eigen::Vector3d::Zero();
    Eigen::Vector3d rotationalDamping = Eigen::Vector3d::Zero(), translationalDamping = Eigen::Vector3d::Zero();
    std::string where;
};

struct ContactGeometrySpec {
    std::string name;
    ContactGeometry::Shape shape = ContactGeometry::Shape::Sphere;
    LinkFrameSpec frame;
    double radius = 0;  // m, sphere
    std::string where;
};

struct HuntCrossleySurfaceSpec {
    std::string geometry;
    double stiffness = 0, dissipation = 0, staticFriction = 0, dynamicFriction = 0, viscousFriction = 0;
};

struct HuntCrossleyForceSpec {
    std::string name;
    std::vector<HuntCrossleySurfaceSpec> surfaces;
    double transitionVelocity = 0.01;  // m/s
    std::string where;
};

class ModelBuilder {
public:
    explicit ModelBuilder(std::string modelName) : name_(std::move(modelName)) {}

    void setGravity(const Eigen::Vector3d& gravity, std::string where = {});
    void addLink(LinkSpec link) { links_.push_back(std::move(link)); }
    void addJoint(JointSpec joint) { joints_.push_back(std::move(joint)); }
    void addVirtualLink(VirtualLinkSpec link) { virtualLinks_.push_back(std::move(link)); }
    void addLoop(LoopSpec loop) { loops_.push_back(std::move(loop)); }
    void addCoupler(CoordinateCouplerSpec coupler) { couplers_.push_back(std::move(coupler)); }
    void addWire(WireSpec wire) { wires_.push_back(std::move(wire)); }
    void addWrapObject(WrapObjectSpec object) { wrapObjects_.push_back(std::move(object)); }
    void addContact(ContactSpec contact) { contacts_.push_back(std::move(contact)); }
    void addCoordinateLimitForce(CoordinateLimitForceSpec force) { coordinateLimits_.push_back(std::move(force)); }
    void addPointToPointSpring(PointToPointSpringSpec spring) { springs_.push_back(std::move(spring)); }
    void addBushingForce(BushingForceSpec bushing) { bushings_.push_back(std::move(bushing)); }
    void addContactGeometry(ContactGeometrySpec geometry) { contactGeometry_.push_back(std::move(geometry)); }
    void addHuntCrossleyForce(HuntCrossleyForceSpec force) { huntCrossley_.push_back(std::move(force)); }

    // Validates everything and builds the model; throws ModelError naming the offending element's `where`.
    Model build() const;

private:
    struct Compilation;  // build()'s stages and the state they share (model_builder.cpp)
    void buildContacts(Model& model) const;  // after the links: resolves and checks each contact
    void buildForceElements(Model& model) const;  // after the coordinates: resolves and checks each element

    std::string name_;
    Eigen::Vector3d gravity_ = Eigen::Vector3d(0, -9.80665, 0);
    std::string gravityWhere_;
    std::vector<LinkSpec> links_;
    std::vector<JointSpec> joints_;
    std::vector<VirtualLinkSpec> virtualLinks_;
    std::vector<LoopSpec> loops_;
    std::vector<CoordinateCouplerSpec> couplers_;
    std::vector<WireSpec> wires_;
    std::vector<WrapObjectSpec> wrapObjects_;
    std::vector<ContactSpec> contacts_;
    std::vector<CoordinateLimitForceSpec> coordinateLimits_;
    std::vector<PointToPointSpringSpec> springs_;
    std::vector<BushingForceSpec> bushings_;
    std::vector<ContactGeometrySpec> contactGeometry_;
    std::vector<HuntCrossleyForceSpec> huntCrossley_;
};

}  // namespace sinew

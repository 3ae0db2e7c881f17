#pragma once
// sinew's model: links in a tree of joints, loop closures, and wires. Immutable once built (ModelBuilder
// validates and builds it), shareable between threads; per-evaluation numbers live in sinew::Data.
//
// Conventions (those of Simbody, so a Simbody system built from the model has the same q and u):
// - every link i has exactly one joint, joints[i], connecting it to its parent link (or ground); links are
//   stored parents-first;
// - joint frames: F fixed on the parent at p_PF with orientation R_PF, M fixed on the child at p_BM with
//   orientation R_BM; at q = identity the two frames coincide;
// - free: q = [quaternion w x y z of R_FM, p_FM], u = [w_FM in F, v_FM in F]; ball: q = quaternion,
//   u = w_FM in F; pin: rotation about F's z axis, q = angle, u = rate; weld: nothing;
// - custom (OpenSim's CustomJoint, Simbody's MobilizedBody::FunctionBased): q = u = the joint's own
//   coordinates; R_FM = R(theta_0, a_0) R(theta_1, a_1) R(theta_2, a_2) (body-fixed sequence),
//   p_FM = sum_k theta_k a_k (k = 3..5, in F), theta_k = f_k(q_c(k)); see docs/opensim-joints.md;
// - spatial vectors are [angular; linear]; G is ground.
#include <Eigen/Core>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sinew/core/force_elements.hpp"
#include "sinew/core/force_law.hpp"
#include "sinew/core/function.hpp"

namespace sinew {

constexpr int kGround = -1;  // parent index of a joint attached to ground

enum class JointType { Free, Ball, Pin, Weld, Custom };
enum class WireKind { Muscle, Tendon, Ligament, Cartilage };

const char* toString(JointType type);
const char* toString(WireKind kind);
// 7, 4, 1, 0; a custom joint has as many as it has coordinates (Joint::nq), so these throw for it.
int getNumQ(JointType type);
int getNumU(JointType type);  // 6, 3, 1, 0; throws for custom

// How a coordinate moves its joint, as OpenSim decides it (CustomJoint::constructCoordinates): rotational
// or translational when some axis of its is driven by it with slope +-1, coupled otherwise.
enum class MotionType { Rotational, Translational, Coupled };
const char* toString(MotionType type);

constexpr int kNoCoordinate = -1;

// One of a custom joint's six TransformAxes: displacement theta = function(q of `coordinate`) along a
// unit axis of F (a rotation angle in rad for the first three, a translation in m for the last three).
struct TransformAxis {
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit, in F
    int coordinate = kNoCoordinate;  // index among the joint's own coordinates (0 .. nq-1), or none
    Function function = Function::constant(0);  // of that coordinate; constant when there is none
};

// One entry of the model's q (nq of them, all joints, in q order).
struct Coordinate {
    std::string name;  // column name: a custom joint's coordinate names; see getCoordinateNames otherwise
    MotionType motionType = MotionType::Rotational;
    int joint = 0;            // index of the joint (= link) it belongs to
    double defaultValue = 0;  // rad or m (a quaternion entry for ball/free), the model's default q
    double rangeMin = -std::numeric_limits<double>::infinity();  // rad or m
    double rangeMax = std::numeric_limits<double>::infinity();
    // OpenSim's flags. Forward dynamics holds a locked coordinate at its default value, as OpenSim's lock (a
    // prescribed constant) does; inverse dynamics ignores the lock, as OpenSim's does. `clamped` is kept for
    // importers and writers.
    bool clamped = false;
    bool locked = false;
};

// OpenSim's CoordinateCouplerConstraint: q[dependentQ] = scaleFactor * function(q[independentQ]), both
// coordinates with qdot = u (pin or custom joints). The algorithms that take the tree's q as free (inverse
// dynamics, as OpenSim's, and the wire Jacobian) ignore it; moment arms follow it (core/moment_arms.hpp),
// forward dynamics enforces it (both engines), and applyCoordinateCouplers fills the dependent coordinates.
struct CoordinateCoupler {
    std::string name;
    int dependentQ = 0, dependentU = 0;      // the dependent coordinate's index in q and in u
    int independentQ = 0, independentU = 0;  // the independent one's
    Function function = Function::linear(1, 0);  // of the independent coordinate (rad or m)
    double scaleFactor = 1;
};

struct Link {
    std::string name;
    double mass = 0;                                    // kg
    Eigen::Vector3d com_B = Eigen::Vector3d::Zero();    // m, centre of mass in the link frame B
    Eigen::Matrix3d inertia_Bcom = Eigen::Matrix3d::Zero();  // kg m^2, about the centre of mass, B axes
    bool isVirtual = false;  // massless 6-DOF link on which forked wires meet (paper's "virtual link")
};

struct Joint {
    std::string name;
    JointType type = JointType::Ball;
    int parent = kGround;                               // parent link index or kGround
    Eigen::Vector3d p_PF = Eigen::Vector3d::Zero();     // m, joint frame origin in the parent frame
    Eigen::Matrix3d R_PF = Eigen::Matrix3d::Identity();
    Eigen::Vector3d p_BM = Eigen::Vector3d::Zero();     // m, joint frame origin in this link's frame
    Eigen::Matrix3d R_BM = Eigen::Matrix3d::Identity();
    int qStart = 0, nq = 0;  // slice of the model's q
    int uStart = 0, nu = 0;  // slice of the model's u
    // Custom joints: rotation1, rotation2, rotation3, translation1, translation2, translation3 (6); empty
    // for the other types.
    std::vector<TransformAxis> transformAxes;
};

// A ball-joint loop closure: point p_A on link A and point p_B on link B stay together.
struct Loop {
    std::string name;
    int linkA = 0;
    Eigen::Vector3d p_A = Eigen::Vector3d::Zero();  // m, in link A's frame
    int linkB = 0;
    Eigen::Vector3d p_B = Eigen::Vector3d::Zero();  // m, in link B's frame
};

struct WirePoint {
    int link = 0;                                   // link (or virtual link) the point is fixed on
    Eigen::Vector3d p_B = Eigen::Vector3d::Zero();  // m, in that link's frame
};

// A wire point that is on the path only while a coordinate lies in [min, max] (OpenSim's
// ConditionalPathPoint, whose test widens the range by 1e-5 on each side, as sinew's does).
struct WirePointCondition {
    int point = 0;  // the wire's point, counted from 0 along the wire
    int q = 0;      // index of the coordinate in q (a coordinate with qdot = u: pin or custom joint)
    double min = 0, max = 0;  // rad or m
};

// One moving component of a wire point (OpenSim's MovingPathPoint): p_B[axis] = function(q[q]), with the
// coordinate clamped to its range (Coordinate::rangeMin/Max) as OpenSim clamps it; the point's other
// components are the fixed WirePoint::p_B ones. Outside the range the component stops, so its rate is 0.
struct WirePointMotion {
    int point = 0;      // the wire's point, counted from 0 along the wire
    int axis = 0;       // 0, 1, 2: x, y, z of the point in its link's frame
    int q = 0, u = 0;   // the coordinate's index in q, and in u (qdot = u for it)
    Function function;  // m, of the coordinate (rad or m)
};

// A smooth obstacle fixed on a link that wires wrap over (OpenSim's WrapSphere, WrapCylinder, WrapEllipsoid).
// Its frame W sits at the shape's centre; a cylinder's axis is W's z. docs/wire-paths.md has the geometry.
enum class WrapShape { Sphere, Cylinder, Ellipsoid };
const char* toString(WrapShape shape);

struct WrapObject {
    std::string name;
    WrapShape shape = WrapShape::Sphere;
    int link = 0;
    Eigen::Vector3d xyzBodyRotation = Eigen::Vector3d::Zero();  // rad, OpenSim's body-fixed X-Y-Z angles, as given
    Eigen::Matrix3d R_BW = Eigen::Matrix3d::Identity();         // = Rx Ry Rz of those angles
    Eigen::Vector3d p_BW = Eigen::Vector3d::Zero();             // m, W's origin in the link frame
    double radius = 0;                                  // m, sphere and cylinder
    double length = 0;                                  // m, cylinder: its extent along z, centred on W
    Eigen::Vector3d radii = Eigen::Vector3d::Zero();    // m, ellipsoid: semi-axes along W's x, y, z
    // OpenSim's quadrant: wrapping kept to the side of W where coordinate `quadrantAxis` (0, 1, 2) has the
    // sign `quadrantSign` (+1, -1); quadrantSign 0 (quadrant "all") leaves both sides free.
    int quadrantAxis = 0;
    int quadrantSign = 0;
};

// How a wrap is computed. Hybrid, Midpoint, Axial: OpenSim's PathWrap methods, which choose an ellipsoid's
// wrapping plane (spheres and cylinders wrap along exact shortest paths whatever they say). MuJoCo: MuJoCo's
// spatial-tendon wrapping (mju_wrap) over a sphere or an infinite cylinder, its side chosen by the optional
// side site (docs/wire-paths.md, "MuJoCo wrapping").
enum class WrapMethod { Hybrid, Midpoint, Axial, MuJoCo };
const char* toString(WrapMethod method);

// One entry of a wire's wrap list (OpenSim's PathWrap): the wire may wrap over `object` between its points
// firstPoint and lastPoint (inclusive, counted from 0 along the wire).
struct WireWrap {
    int object = 0;  // index into Model::getWrapObjects()
    int firstPoint = 0, lastPoint = 0;
    WrapMethod method = WrapMethod::Hybrid;
    // MuJoCo's sidesite (MuJoCo method only): a point fixed on link sideSiteLink (the wrap object's link
    // unless given otherwise), which moves with that link; it only picks the side.
    bool hasSideSite = false;
    int sideSiteLink = 0;
    Eigen::Vector3d sideSite_B = Eigen::Vector3d::Zero();  // m, in sideSiteLink's frame, as given
};

struct ForceLawSpec {
    std::string type;               // registry name
    ForceLawParameters parameters;  // as given, kept so the model can be written back
};

struct Wire {
    std::string name;
    WireKind kind = WireKind::Muscle;
    int firstPoint = 0;  // index into Model::getWirePoints()
    int numPoints = 0;   // >= 2: origin, via-points..., insertion
    ForceLawSpec lawSpec;
    std::shared_ptr<const ForceLaw> law;
    // N: the most tension a tension distribution may give the wire, for wires whose law has no max isometric
    // force (passive ligaments, cartilage); getWireStrength() is the one place that chooses between the two.
    std::optional<double> strength;
    // m^2: the physiological (muscle) or anatomical (ligament, tendon) cross-section, for stress = tension / area.
    std::optional<double> crossSection;
    // OpenSim's path features; a wire with none of them is a plain polyline, evaluated on a faster path.
    std::vector<WirePointCondition> conditions;
    std::vector<WirePointMotion> motions;  // ordered by point
    std::vector<WireWrap> wraps;           // in the order OpenSim applies them
    // The support links: the links whose joints move at least one of the wire's points, wrap objects or side
    // sites, children before parents, at Model::getSupportLinks()[firstSupportLink ...]; Jacobian and force
    // passes visit only these (derived at build). All wires' lie in one array because the Jacobian's sweep
    // reads them wire after wire, and a heap block per wire cost it a cache miss each (docs/performance.md).
    int firstSupportLink = 0;
    int numSupportLinks = 0;
    // The first numSpanLinks support links lie below the lowest link that carries all of those anchors: the
    // joints that change the wire's length. That link's joint and those above it move every anchor rigidly,
    // so their columns of J are zero (derived at build).
    int numSpanLinks = 0;

    bool isPolyline() const { return conditions.empty() && motions.empty() && wraps.empty(); }
};

// The wire's `strength` when given, else its force law's max isometric force; none when neither is.
std::optional<double> getWireStrength(const Wire& wire);

// A link that may touch the ground (a foot): when the tension analysis finds it in contact (contact_detection.hpp),
// the ground pushes on its sole with forces inside a friction cone (docs/tensions-from-motion.md, "Contact").
struct Contact {
    std::string name;
    int link = 0;
    std::vector<Eigen::Vector3d> sole_B;  // m, the sole polygon's vertices in the link frame (>= 1)
    double friction = 0.8;                // Coulomb coefficient mu, >= 0
};

class Model {
public:
    const std::string& getName() const { return name_; }
    int getNumLinks() const { return static_cast<int>(links_.size()); }
    int getNumQ() const { return nq_; }
    int getNumU() const { return nu_; }
    int getNumWires() const { return static_cast<int>(wires_.size()); }
    int getNumLoops() const { return static_cast<int>(loops_.size()); }
    int getNumCouplers() const { return static_cast<int>(couplers_.size()); }

    const Link& getLink(int i) const { return links_[static_cast<std::size_t>(i)]; }
    const Joint& getJoint(int i) const { return joints_[static_cast<std::size_t>(i)]; }
    const Wire& getWire(int i) const { return wires_[static_cast<std::size_t>(i)]; }
    const Loop& getLoop(int i) const { return loops_[static_cast<std::size_t>(i)]; }
    const std::vector<Link>& getLinks() const { return links_; }
    const std::vector<Joint>& getJoints() const { return joints_; }
    const std::vector<Wire>& getWires() const { return wires_; }
    const std::vector<Loop>& getLoops() const { return loops_; }
    const std::vector<CoordinateCoupler>& getCouplers() const { return couplers_; }
    const std::vector<WirePoint>& getWirePoints() const { return wirePoints_; }  // all wires' points, flat
    const std::vector<int>& getSupportLinks() const { return supportLinks_; }   // all wires' support links, flat
    // Wire w's support links (Wire::firstSupportLink ...), as a vector for callers off the hot paths.
    std::vector<int> getSupportLinks(const Wire& wire) const;
    const std::vector<WrapObject>& getWrapObjects() const { return wrapObjects_; }
    const std::vector<Contact>& getContacts() const { return contacts_; }  // the links the model names as feet
    const ForceElements& getForceElements() const { return forceElements_; }  // forces other than wires

    const Eigen::Vector3d& getGravity() const { return gravity_; }  // m/s^2, in ground
    const Eigen::VectorXd& getDefaultQ() const { return defaultQ_; }  // the model file's initial pose (nq)
    const std::vector<Coordinate>& getCoordinates() const { return coordinates_; }  // one per q entry (nq)

    static constexpr int kNotFound = -2;
    // kGround for "ground", kNotFound when there is no such link.
    int findLinkIndex(const std::string& name) const;
    int findWireIndex(const std::string& name) const;  // kNotFound when absent
    int findCoordinateIndex(const std::string& name) const;  // its index in q; kNotFound when absent

private:
    friend class ModelBuilder;
    std::string name_;
    std::vector<Link> links_;
    std::vector<Joint> joints_;
    std::vector<Loop> loops_;
    std::vector<CoordinateCoupler> couplers_;
    std::vector<Wire> wires_;
    std::vector<WirePoint> wirePoints_;
    std::vector<int> supportLinks_;
    std::vector<WrapObject> wrapObjects_;
    std::vector<Contact> contacts_;
    ForceElements forceElements_;
    Eigen::Vector3d gravity_ = Eigen::Vector3d(0, -9.80665, 0);
    Eigen::VectorXd defaultQ_;
    std::vector<Coordinate> coordinates_;
    int nq_ = 0, nu_ = 0;
};

// Column names for q and u, per joint in model order: a free joint "j" gives j_qw j_qx j_qy j_qz j_x j_y j_z
// and j_wx j_wy j_wz j_vx j_vy j_vz; a ball the quaternion and angular parts; a pin just "j"; a custom
// joint its coordinates' names (for both).
std::vector<std::string> getCoordinateNames(const Model& model);
std::vector<std::string> getSpeedNames(const Model& model);

}  // namespace sinew

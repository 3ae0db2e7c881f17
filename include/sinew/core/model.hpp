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
// - spatial vectors are [angular; linear]; G is ground.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "sinew/core/force_law.hpp"

namespace sinew {

constexpr int kGround = -1;  // parent index of a joint attached to ground

enum class JointType { Free, Ball, Pin, Weld };
enum class WireKind { Muscle, Tendon, Ligament, Cartilage };

const char* toString(JointType type);
const char* toString(WireKind kind);
int getNumQ(JointType type);  // 7, 4, 1, 0
int getNumU(JointType type);  // 6, 3, 1, 0

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
    // Links whose joints move at least one of the wire's points, children before parents; Jacobian and
    // force passes visit only these (derived at build).
    std::vector<int> supportLinks;
};

class Model {
public:
    const std::string& getName() const { return name_; }
    int getNumLinks() const { return static_cast<int>(links_.size()); }
    int getNumQ() const { return nq_; }
    int getNumU() const { return nu_; }
    int getNumWires() const { return static_cast<int>(wires_.size()); }
    int getNumLoops() const { return static_cast<int>(loops_.size()); }

    const Link& getLink(int i) const { return links_[static_cast<std::size_t>(i)]; }
    const Joint& getJoint(int i) const { return joints_[static_cast<std::size_t>(i)]; }
    const Wire& getWire(int i) const { return wires_[static_cast<std::size_t>(i)]; }
    const Loop& getLoop(int i) const { return loops_[static_cast<std::size_t>(i)]; }
    const std::vector<Link>& getLinks() const { return links_; }
    const std::vector<Joint>& getJoints() const { return joints_; }
    const std::vector<Wire>& getWires() const { return wires_; }
    const std::vector<Loop>& getLoops() const { return loops_; }
    const std::vector<WirePoint>& getWirePoints() const { return wirePoints_; }  // all wires' points, flat

    const Eigen::Vector3d& getGravity() const { return gravity_; }  // m/s^2, in ground
    const Eigen::VectorXd& getDefaultQ() const { return defaultQ_; }  // the model file's initial pose (nq)

    static constexpr int kNotFound = -2;
    // kGround for "ground", kNotFound when there is no such link.
    int findLinkIndex(const std::string& name) const;
    int findWireIndex(const std::string& name) const;  // kNotFound when absent

private:
    friend class ModelBuilder;
    std::string name_;
    std::vector<Link> links_;
    std::vector<Joint> joints_;
    std::vector<Loop> loops_;
    std::vector<Wire> wires_;
    std::vector<WirePoint> wirePoints_;
    Eigen::Vector3d gravity_ = Eigen::Vector3d(0, -9.80665, 0);
    Eigen::VectorXd defaultQ_;
    int nq_ = 0, nu_ = 0;
};

// Column names for q and u, per joint in model order: a free joint "j" gives j_qw j_qx j_qy j_qz j_x j_y j_z
// and j_wx j_wy j_wz j_vx j_vy j_vz; a ball the quaternion and angular parts; a pin just "j".
std::vector<std::string> getCoordinateNames(const Model& model);
std::vector<std::string> getSpeedNames(const Model& model);

}  // namespace sinew

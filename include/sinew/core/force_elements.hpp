#pragma once
// Force elements that are not wires, as OpenSim's models carry them (docs/force-elements.md): a coordinate's
// limit springs (CoordinateLimitForce), a spring between two points (PointToPointSpring), a six-axis
// bushing between two frames (BushingForce), and Hunt-Crossley contact between spheres and half-spaces
// (HuntCrossleyForce with ContactSphere, ContactHalfSpace). Each follows the formula of the element OpenSim
// builds (Simbody's Force::TwoPointLinearSpring, Force::LinearBushing, HuntCrossleyForce; OpenSim's own
// CoordinateLimitForce), so the Simbody plugin can build Simbody's own elements and the two engines check
// each other. Links are indices (kGround for ground); every other quantity is SI (rad, N m/rad, ...).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sinew/core/spatial.hpp"

namespace sinew {

class Model;
struct Data;

// A frame fixed on a link: its origin and axes in the link frame.
struct LinkFrame {
    int link = -1;
    Eigen::Vector3d p_BF = Eigen::Vector3d::Zero();             // m
    Eigen::Matrix3d R_BF = Eigen::Matrix3d::Identity();
    Eigen::Vector3d xyzBodyRotation = Eigen::Vector3d::Zero();  // rad, the angles R_BF was given as
};

// Springs that hold a scalar coordinate (pin or custom joint: qdot = u) inside [lower, upper]: past a limit
// the stiffness rises from 0 to its value over `transition` (a quintic step), the damping with it.
struct CoordinateLimitForce {
    std::string name;
    int q = 0, u = 0;  // the coordinate's index in q and in u
    double upperStiffness = 0, upperLimit = 0;  // N m/rad (N/m), rad (m)
    double lowerStiffness = 0, lowerLimit = 0;
    double damping = 0;                         // N m s/rad (N s/m), at full stiffness
    double transition = 0;                      // rad (m), > 0
};

// f = stiffness (distance - restLength) along the line between the points: pulls and pushes.
struct PointToPointSpring {
    std::string name;
    int linkA = 0, linkB = 0;
    Eigen::Vector3d pointA = Eigen::Vector3d::Zero(), pointB = Eigen::Vector3d::Zero();  // m, in their links
    double stiffness = 0;   // N/m
    double restLength = 0;  // m
};

// Frame B's deflection from frame A, [body-fixed X-Y-Z angles of R_AB; p_AB in A], held by linear springs
// and dampers on those six numbers (their rates through the X-Y-Z kinematics).
struct BushingForce {
    std::string name;
    LinkFrame frameA, frameB;
    Eigen::Vector3d rotationalStiffness = Eigen::Vector3d::Zero();     // N m/rad
    Eigen::Vector3d translationalStiffness = Eigen::Vector3d::Zero();  // N/m
    Eigen::Vector3d rotationalDamping = Eigen::Vector3d::Zero();       // N m s/rad
    Eigen::Vector3d translationalDamping = Eigen::Vector3d::Zero();    // N s/m
};

// A sphere (centre at the frame's origin) or a half-space (the solid is x > 0 of its frame, its surface the
// frame's y-z plane, as Simbody's ContactGeometry::HalfSpace).
struct ContactGeometry {
    enum class Shape { Sphere, HalfSpace };
    std::string name;
    Shape shape = Shape::Sphere;
    LinkFrame frame;
    double radius = 0;  // m, sphere
};

// One surface's material in a Hunt-Crossley force (HuntCrossleyForce::ContactParameters).
struct HuntCrossleySurface {
    int geometry = 0;  // index into ForceElements::contactGeometry
    double stiffness = 0, dissipation = 0;
    double staticFriction = 0, dynamicFriction = 0, viscousFriction = 0;
};

// Every sphere-half-space pair of its surfaces on different links touches when the sphere dips below the
// surface: Hertz force 4/3 k x sqrt(R k x) (1 + 3/2 c xdot) along the half-space's outward normal (k from the
// surfaces' stiffness^(2/3), so a surface's stiffness is Hertz's E), with Stribeck friction, as Simbody's
// HuntCrossleyForce computes it.
struct HuntCrossleyForce {
    std::string name;
    std::vector<HuntCrossleySurface> surfaces;
    double transitionVelocity = 0.01;  // m/s
    // Every half-space and sphere among the surfaces on different links, as indices into `surfaces`: the
    // pairs that can touch (derived at build; both engines use them).
    struct Pair {
        int halfSpace = 0, sphere = 0;
    };
    std::vector<Pair> pairs;
};

struct ForceElements {
    std::vector<CoordinateLimitForce> coordinateLimits;
    std::vector<PointToPointSpring> springs;
    std::vector<BushingForce> bushings;
    std::vector<ContactGeometry> contactGeometry;
    std::vector<HuntCrossleyForce> huntCrossley;

    bool empty() const {
        return coordinateLimits.empty() && springs.empty() && bushings.empty() && huntCrossley.empty();
    }
};

// Adds every force element's forces at the state in `data` (position and velocity kinematics done) to
// linkForces (one per link, Data::F_G convention: moment about the link origin, force; ground axes) and to
// tau (nu, generalized forces of the coordinate limits).
void addForceElementForces(const Model& model, const Data& data, std::vector<SpatialVector>& linkForces,
                           Eigen::Ref<Eigen::VectorXd> tau);
// The energy the elements store at the pose in `data` (position kinematics done), J: springs, bushings,
// limit springs and the contacts' Hertz energy 2/5 f x.
double calcForceElementPotentialEnergy(const Model& model, const Data& data);

// The force (N m or N) on `limit`'s coordinate at q and qdot (OpenSim's CoordinateLimitForce::calcLimitForce).
double calcCoordinateLimitForce(const CoordinateLimitForce& limit, double q, double qdot);
double calcCoordinateLimitEnergy(const CoordinateLimitForce& limit, double q);

// Body-fixed X-Y-Z angles of R (the inverse of calcRotationFromBodyFixedXYZ away from cos(b) = 0).
Eigen::Vector3d calcBodyFixedXYZ(const Eigen::Matrix3d& R);

}  // namespace sinew

#pragma once
// What a picture of the body shows at one instant, in ground coordinates: the links as capsules and every
// wire's path as evaluated by core (calcWirePaths: via-points, active conditional and moving points, the
// wraps' tangent points and arcs), with its tension and, for ligaments with a rest length, its strain.
// Pictures (picture.hpp) and the browser viewer (html_viewer.hpp) draw these; neither computes any geometry
// itself.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

// A link drawn as a capsule between two points fixed in its frame B. Sized from the model alone: from the
// joint centre of the link (p_BM) to each child's joint centre at the default pose (p_PF, unless a custom
// joint translates it), or, for a leaf, to twice its centre of mass. The limb's radius is that of a solid cylinder with the link's smallest principal moment
// of inertia about its axis, r = sqrt(2 I_min / m); the bone is drawn at 0.4 r (the rest is the flesh the
// wires stand for), kept between 3% and 12% of the capsule's length.
struct BoneCapsule {
    int link = 0;
    Eigen::Vector3d a_B = Eigen::Vector3d::Zero(), b_B = Eigen::Vector3d::Zero();  // m, in the link frame
    double radius = 0;                                                             // m
};

// Every real link's capsules (virtual links, massless and with no bone, get none); a link with neither
// children nor a centre of mass off its joint centre is a sphere (a_B == b_B).
std::vector<BoneCapsule> calcBoneCapsules(const Model& model);

// Wire w's rest length l0 (m), where its force law has one (spring_damper's rest_length), else NaN: strain
// (l - l0) / l0 needs it.
double findRestLength(const Wire& wire);

// Whether wire w is shaded by strain rather than tension: a ligament with a rest length.
bool isShadedByStrain(const Wire& wire);

struct SceneCapsule {
    int link = 0;
    Eigen::Vector3d a_G = Eigen::Vector3d::Zero(), b_G = Eigen::Vector3d::Zero();  // m, in ground
    double radius = 0;                                                             // m
};

struct SceneWire {
    std::vector<Eigen::Vector3d> path_G;  // m, the evaluated path's points in order (>= 2)
    double tension = 0;                   // N, >= 0
    double strain = 0;                    // (l - l0) / l0 for isShadedByStrain wires, else 0
};

// One instant: time, bones (capsules from calcBoneCapsules) and wires (numWires, model order).
struct BodyFrame {
    double time = 0;  // s
    std::vector<SceneCapsule> bones;
    std::vector<SceneWire> wires;
};

// Wire w's path as calcWirePaths left it in `data` (calcWirePathSamples): Data::p_GP of its points for a
// polyline wire, the Data::wirePath slice (active points and tangent points) for the others, with points
// along each wrap's arc on the object's surface between its tangent points, at most 5 degrees apart.
void getWirePath_G(const Model& model, const Data& data, int w, std::vector<Eigen::Vector3d>& path_G);

// The frame at the poses and paths in `data` (calcPositionKinematics and calcWirePaths done) with the given
// tensions (numWires, N): capsules placed by Data::R_GB and p_GB, paths from getWirePath_G, strains from
// Data::wireLength. Throws sinew::Error naming the wire for a negative or non-finite tension.
BodyFrame calcBodyFrame(const Model& model, const Data& data, const std::vector<BoneCapsule>& capsules,
                        double time, const Eigen::VectorXd& tensions);

}  // namespace sinew

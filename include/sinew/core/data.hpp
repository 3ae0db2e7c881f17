#pragma once
// Per-evaluation buffers for one Model, sized once at construction; the calc* algorithms fill them and
// allocate nothing. One Data per thread.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"

namespace sinew {

// A joint's motion subspace (hinge matrix): nu columns [angular; linear] in F, at most 6; fixed storage.
using JointMotion = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;

struct Data {
    explicit Data(const Model& model);

    // The coordinates (nq) and speeds (nu) calcPositionKinematics and calcVelocityKinematics were last given;
    // moving and conditional wire points read them.
    Eigen::VectorXd q, u;

    // calcPositionKinematics, per link (numLinks):
    std::vector<Eigen::Matrix3d> R_GB;  // link frame orientation in ground
    std::vector<Eigen::Vector3d> p_GB;  // m, link frame origin in ground
    std::vector<Eigen::Matrix3d> R_GF;  // orientation of the link's joint frame F (on the parent) in ground
    std::vector<Eigen::Vector3d> p_GM;  // m, origin of the joint's M frame (the joint centre) in ground
    // Custom joints: H_FM (6 x nu), with V_FM = H_FM u the velocity of M in F (w_FM; velocity of M's origin,
    // both in F); 6 x 0 for the other joint types, whose subspaces are closed forms.
    std::vector<JointMotion> H_FM;

    // calcVelocityKinematics, per link (numLinks):
    std::vector<Eigen::Vector3d> w_GB;  // rad/s, angular velocity in ground
    std::vector<Eigen::Vector3d> v_GB;  // m/s, velocity of the link frame origin in ground

    // calcInverseDynamics, per link (numLinks):
    std::vector<Eigen::Vector3d> alpha_GB;  // rad/s^2, angular acceleration in ground
    std::vector<Eigen::Vector3d> a_GB;      // m/s^2, acceleration of the link frame origin in ground

    // calcWirePaths / calcWireSpeeds, per wire point (Model::getWirePoints().size()):
    std::vector<Eigen::Vector3d> p_GP;  // m, point position in ground
    std::vector<Eigen::Vector3d> v_GP;  // m/s, point velocity in ground
    // d(wire length)/d(p_GP) = e_in - e_out, the unit directions of the segments arriving at and leaving the
    // point (zero at the wire's ends and for zero-length segments); dimensionless.
    std::vector<Eigen::Vector3d> dLdp_GP;
    // Per wire (numWires):
    Eigen::VectorXd wireLength;  // m
    Eigen::VectorXd wireSpeed;   // m/s, positive when lengthening

    // calcWirePaths, for the wires that are not plain polylines (Wire::isPolyline() false): the path as
    // evaluated, i.e. the active points and the wraps' tangent points in order. Wire w's entries are
    // wirePath[wirePathStart[w] + i] for i < wirePathSize[w]; its slice holds numPoints + 2 * wraps.size().
    struct WirePathPoint {
        int link = 0;    // the link it moves with (a tangent point: the wrap object's link)
        int point = -1;  // the wire's point (from 0), or -1 for a tangent point
        int wrap = -1;   // index into Wire::wraps for a tangent point, else -1
        Eigen::Vector3d p_G = Eigen::Vector3d::Zero();     // m, in ground
        Eigen::Vector3d dLdp_G = Eigen::Vector3d::Zero();  // d(wire length)/d(p_G) with the point fixed on its link
        double arcLength = 0;  // m, on a wrap's second tangent point: the length over the surface from the first
    };
    std::vector<WirePathPoint> wirePath;
    std::vector<int> wirePathStart;  // numWires
    std::vector<int> wirePathSize;   // numWires

    // calcWirePaths, for the wires over an ellipsoid (isLengthDifferentiatedNumerically): dL/du (nu) in row
    // wireGradientRow[w] (-1 for the other wires), by central differences of the whole path. Their J rows,
    // speeds and generalized forces come from these rows, not from the path's point derivatives.
    Eigen::MatrixXd wireLengthGradient;
    std::vector<int> wireGradientRow;  // numWires
    // Workspace for those differences: the link poses, points and coordinates displaced, and one path.
    std::vector<Eigen::Matrix3d> displacedR_GB;
    std::vector<Eigen::Vector3d> displacedP_GB, displacedP_GP;
    Eigen::VectorXd displacedQ;
    std::vector<WirePathPoint> displacedPath;

    // Per link: the wires' spatial forces [moment about the link's origin p_GB; force], ground axes, filled
    // by calcWireLinkForces (and calcWireGeneralizedForces) and nothing else. Moments about the link rather
    // than the ground origin keep their digits when the model is far from the origin.
    std::vector<SpatialVector> F_G;
    // Per link, in F_G's convention: scratch for the tip-to-base passes that accumulate subtree forces in
    // place (calcGeneralizedForcesFromLinkForces, addToParent): the wire Jacobian's unit forces, the tension
    // problem's loop columns and inverse dynamics' net forces. Holds nothing between calls.
    std::vector<SpatialVector> scratchF_G;
};

}  // namespace sinew

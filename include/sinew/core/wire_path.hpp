#pragma once
// Wire geometry: a wire is a polyline through its points (origin, via-points, insertion), each fixed on a
// link; OpenSim's paths add points active over a coordinate range, points whose position in their link
// follows a coordinate, and wraps over spheres, cylinders and ellipsoids (docs/wire-paths.md). Length,
// lengthening speed, and tension from the wire's force law.
#include <Eigen/Core>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

// Fills Data::p_GP and wireLength, and the path as evaluated: dLdp_GP for polyline wires, Data::wirePath
// for the others, and Data::wireLengthGradient for wires over an ellipsoid. Needs calcPositionKinematics.
void calcWirePaths(const Model& model, Data& data);

// Whether wire w's dL/du is taken by central differences of its whole path rather than from its points:
// true for wires over an ellipsoid. OpenSim's ellipsoid path lies in a plane its heuristics turn with the
// path's ends, so it is no shortest path and holding its tangent points fixed (the envelope derivative
// that is exact for spheres and cylinders) misses how the plane turns; with more wraps on the wire the
// tangent points of the others move with it too (docs/wire-paths.md).
bool isLengthDifferentiatedNumerically(const Model& model, int w);

// Fills Data::v_GP and wireSpeed (the time derivative of wireLength). Needs calcVelocityKinematics and
// calcWirePaths.
void calcWireSpeeds(const Model& model, Data& data);

// Point `point` (counted from 0) of `wire` in its link's frame at coordinates q, moving components
// included (m).
Eigen::Vector3d calcWirePointLocation(const Model& model, const Wire& wire, int point, const Eigen::VectorXd& q);

// d(p_B[axis])/dq of a moving component at coordinates q: the function's slope, 0 where the coordinate
// is clamped to its range (m per rad or m/m).
double calcWirePointMotionRate(const Model& model, const WirePointMotion& motion, const Eigen::VectorXd& q);

// What moving component `motion` of wire w adds to dL/du at its coordinate's u beyond the motion of its link:
// dL/dp . R_GB e_axis dp_B/dq at the point's place on the path, 0 while the point is off it. A tension f
// pushes that coordinate by -f times it. Needs calcWirePaths; for wires whose dL/du is not differentiated
// numerically (their rows of Data::wireLengthGradient hold the whole dL/du).
double calcWirePointMotionTerm(const Model& model, const Data& data, int w, const WirePointMotion& motion);

// Tension of every wire (N, >= 0) from its force law at the lengths and speeds in `data`.
void calcWireTensions(const Model& model, const Data& data, double time, Eigen::Ref<Eigen::VectorXd> tensions);

// Energy stored in the wires' conservative force laws (J) at the lengths in `data`.
double calcWirePotentialEnergy(const Model& model, const Data& data);

}  // namespace sinew

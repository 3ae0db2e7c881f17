#pragma once
// Points along a wire's path as calcWirePaths evaluated it, its wraps' arcs included, for drawing the path
// and for turning a wrapped path into via points (docs/wire-paths.md, "Sampling the path").
#include <Eigen/Core>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

struct WirePathSample {
    int link = 0;  // the link the point moves with: its wire point's, or a wrap's object's on the arc
    int wrap = -1;  // index into Wire::wraps for a tangent point or a point on that wrap's arc, else -1
    Eigen::Vector3d p_G = Eigen::Vector3d::Zero();  // m, in ground
};

// Wire w's path in order: its active points and its wraps' tangent points, exactly as in Data (p_GP for a
// polyline wire, the Data::wirePath slice otherwise), and between a wrap's two tangent points, points on
// the object's surface along the arc whose length calcWirePaths counted: a helix round a cylinder, the
// plane section of a sphere (a great circle) or an ellipsoid (OpenSim's wrapping plane), the way round
// whose length that is (on half a turn, where both are as long, the way the straight segments run on). Arc
// points are spaced evenly in angle round the object, at most maxStepAngle (rad, > 0) apart; a polyline
// through the samples is shorter than the wire by about L_arc * step^2 / 24 per arc. A wrap touching its
// object at a path point repeats that point. Needs calcWirePaths; clears `samples` and fills it.
void calcWirePathSamples(const Model& model, const Data& data, int w, double maxStepAngle,
                         std::vector<WirePathSample>& samples);

}  // namespace sinew

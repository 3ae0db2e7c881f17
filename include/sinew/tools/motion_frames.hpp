#pragma once
// The one per-frame loop over a motion that the tools share (inverse dynamics, tensions, moment arms):
// each row's coordinates, speeds and accelerations and the measured external loads at that instant,
// handed to a visitor, with progress after each frame.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"
#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/tools/measured_loads.hpp"

namespace sinew {

struct MotionFrame {
    int index;     // from 0
    double time;   // s
    const Eigen::VectorXd& q;     // (nq)
    const Eigen::VectorXd& u;     // (nu) the trajectory's qdot row; empty when it has no speeds
    const Eigen::VectorXd& udot;  // (nu) its qddot row; empty when it has no accelerations
    // One spatial force per link (Data::F_G convention): the measured loads at (time, q), zero without.
    const std::vector<SpatialVector>& appliedLinkForces;
    // The loop's buffers, which the visitor may use as its own: where loads were evaluated, they hold the
    // position kinematics at q (positionsAtQ), which the visitor then need not compute again.
    Data& data;
    bool positionsAtQ;
};

// For each row of `trajectory` in order: visit(frame), then onFrame(index + 1, frames) when given. The
// trajectory's qdot and qddot may have no rows (a motion of coordinates alone: u and udot are then empty).
// The visitor's sinew::Error propagates. Rows [firstFrame, endFrame) only when given (endFrame < 0: to the
// last), so that independent frames can be shared among threads, each with its own call.
void forEachMotionFrame(const Model& model, const CoordinateTrajectory& trajectory, const MeasuredLoads* loads,
                        const std::function<void(const MotionFrame&)>& visit,
                        const std::function<void(int frame, int frames)>& onFrame = {}, int firstFrame = 0,
                        int endFrame = -1);

}  // namespace sinew

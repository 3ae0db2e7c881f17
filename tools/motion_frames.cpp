#include "sinew/tools/motion_frames.hpp"

#include <algorithm>

#include "sinew/core/data.hpp"

namespace sinew {

void forEachMotionFrame(const Model& model, const CoordinateTrajectory& trajectory, const MeasuredLoads* loads,
                        const std::function<void(const MotionFrame&)>& visit,
                        const std::function<void(int frame, int frames)>& onFrame, int firstFrame, int endFrame) {
    Data data(model);
    std::vector<SpatialVector> linkForces(static_cast<std::size_t>(model.getNumLinks()));
    Eigen::VectorXd q(trajectory.q.cols()), u(trajectory.qdot.cols()), udot(trajectory.qddot.cols());
    const bool hasSpeeds = trajectory.qdot.rows() > 0, hasAccelerations = trajectory.qddot.rows() > 0;
    const int frames = static_cast<int>(trajectory.times.size());
    const int endRow = endFrame < 0 ? frames : std::min(endFrame, frames);
    for (int i = firstFrame; i < endRow; ++i) {
        const double t = trajectory.times[i];
        q = trajectory.q.row(i).transpose();
        if (hasSpeeds) u = trajectory.qdot.row(i).transpose();
        if (hasAccelerations) udot = trajectory.qddot.row(i).transpose();
        calcAppliedLinkForces(model, loads, data, t, q, linkForces);
        visit(MotionFrame{i, t, q, u, udot, linkForces, data, loads != nullptr});
        if (onFrame) onFrame(i + 1, frames);
    }
}

}  // namespace sinew

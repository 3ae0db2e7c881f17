#include "sinew/tools/bvh_inverse_kinematics.hpp"

#include "sinew/tools/bvh_targets.hpp"
#include "sinew/tools/model_scaling.hpp"

namespace sinew {
namespace {

Model scaleIf(const Model& model, const std::optional<BvhSegmentScales>& scales) {
    return scales ? scaleModel(model, scales->linkFactors) : model;
}

}  // namespace

BvhInverseKinematics runBvhInverseKinematics(const Model& model, const BvhMotion& motion, const BvhMap& map, bool scale,
                                             InverseKinematicsRequest request,
                                             const std::function<void(const std::string&)>& notes,
                                             const std::function<void(int frame, int frames)>& onFrame) {
    const double unit = map.unit > 0 ? map.unit : inferBvhLengthUnit(motion);
    std::optional<BvhSegmentScales> scales;
    if (scale) scales = estimateBvhSegmentScales(motion, map, model, unit);
    BvhInverseKinematics fit{scales, scaleIf(model, scales), unit, {}};
    BvhTargets targets = makeBvhTargets(motion, scales ? scaleBvhMapPoints(map, model, scales->linkFactors) : map, fit.model);
    request.markerTasks.clear();
    request.coordinateTasks.clear();
    request.orientationTasks = std::move(targets.orientationTasks);
    request.orientations = std::move(targets.orientations);
    fit.result = runInverseKinematics(fit.model, targets.markers, targets.capture, request, notes, onFrame);
    return fit;
}

}  // namespace sinew

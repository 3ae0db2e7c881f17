#include "sinew/tools/bvh_inverse_kinematics.hpp"

#include "sinew/tools/model_scaling.hpp"

namespace sinew {
namespace {

Model scaleIf(const Model& model, const std::optional<BvhSegmentScales>& scales) {
    return scales ? scaleModel(model, scales->linkFactors) : model;
}

}  // namespace

BvhFit prepareBvhFit(const Model& model, const BvhMotion& motion, const BvhMap& map, bool scale) {
    const double unit = map.unit > 0 ? map.unit : inferBvhLengthUnit(motion);
    std::optional<BvhSegmentScales> scales;
    if (scale) scales = estimateBvhSegmentScales(motion, map, model, unit);
    BvhFit fit{scales, scaleIf(model, scales), unit, {}};
    fit.targets = makeBvhTargets(motion, scales ? scaleBvhMapPoints(map, model, scales->linkFactors) : map, fit.model);
    return fit;
}

BvhInverseKinematics runBvhInverseKinematics(const Model& model, const BvhMotion& motion, const BvhMap& map, bool scale,
                                             InverseKinematicsRequest request,
                                             const std::function<void(const std::string&)>& notes,
                                             const std::function<void(int frame, int frames)>& onFrame) {
    return runBvhInverseKinematics(prepareBvhFit(model, motion, map, scale), std::move(request), notes, onFrame);
}

BvhInverseKinematics runBvhInverseKinematics(BvhFit prepared, InverseKinematicsRequest request,
                                             const std::function<void(const std::string&)>& notes,
                                             const std::function<void(int frame, int frames)>& onFrame) {
    BvhInverseKinematics fit{prepared.scales, std::move(prepared.model), prepared.unit, {}};
    request.markerTasks.clear();
    request.coordinateTasks.clear();
    request.orientationTasks = std::move(prepared.targets.orientationTasks);
    request.orientations = std::move(prepared.targets.orientations);
    fit.result = runInverseKinematics(fit.model, prepared.targets.markers, prepared.targets.capture, request, notes, onFrame);
    return fit;
}

}  // namespace sinew

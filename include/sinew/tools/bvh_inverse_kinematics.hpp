#pragma once
// A BVH capture through inverse kinematics, as `sinew ik MODEL CAPTURE.bvh` runs it (docs/inverse-kinematics.md,
// "BVH captures"): the model scaled to the skeleton (bvh_segment_scales.hpp, model_scaling.hpp), the
// mapped joints' centres and frames as targets (bvh_targets.hpp), every frame fitted in order.
#include <functional>
#include <optional>
#include <string>

#include "sinew/core/model.hpp"
#include "sinew/io/bvh_file.hpp"
#include "sinew/io/bvh_map.hpp"
#include "sinew/tools/bvh_segment_scales.hpp"
#include "sinew/tools/bvh_targets.hpp"
#include "sinew/tools/inverse_kinematics_tool.hpp"

namespace sinew {

struct BvhInverseKinematics {
    std::optional<BvhSegmentScales> scales;  // absent when not scaled
    Model model;                             // the model fitted: scaled, or the one given
    double unit = 0;                         // m per BVH unit
    InverseKinematicsResult result;
};

// The fit's model and targets as runBvhInverseKinematics poses them: the model scaled to the skeleton (when
// `scale`), the map's points scaled with it, the mapped joints' centres and frames per BVH frame.
struct BvhFit {
    std::optional<BvhSegmentScales> scales;
    Model model;
    double unit = 0;
    BvhTargets targets;
};
BvhFit prepareBvhFit(const Model& model, const BvhMotion& motion, const BvhMap& map, bool scale);

// request: its time range and accuracy are used; its tasks are the BVH's. Throws what the steps throw.
BvhInverseKinematics runBvhInverseKinematics(const Model& model, const BvhMotion& motion, const BvhMap& map, bool scale,
                                             InverseKinematicsRequest request,
                                             const std::function<void(const std::string&)>& notes = {},
                                             const std::function<void(int frame, int frames)>& onFrame = {});
// The same from a prepared fit (prepareBvhFit), which is consumed.
BvhInverseKinematics runBvhInverseKinematics(BvhFit prepared, InverseKinematicsRequest request,
                                             const std::function<void(const std::string&)>& notes = {},
                                             const std::function<void(int frame, int frames)>& onFrame = {});

}  // namespace sinew

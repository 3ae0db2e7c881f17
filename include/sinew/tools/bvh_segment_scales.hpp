#pragma once
// Per-subject segment scale factors from a BVH skeleton (docs/inverse-kinematics.md, "Scaling to the
// subject"): each mapped BVH joint's segment, to its mapped children, against the same segment of the model
// between the mapped links' origins, for scaleModel (model_scaling.hpp).
#include <string>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/io/bvh_file.hpp"
#include "sinew/io/bvh_map.hpp"

namespace sinew {

// One segment: from a mapped BVH joint to a mapped child (its nearest mapped descendant).
struct BvhSegment {
    std::string parent, child;  // BVH joints
    double bvhLength = 0;       // m, between the joint centres in the BVH rest pose (every channel 0)
    double modelLength = 0;     // m, between the mapped links' points (the map's `at`) at the default pose
};

struct BvhSegmentScales {
    std::vector<BvhSegment> segments;
    // Per mapped BVH joint (map order): the factor of its segment, the least-squares ratio
    // sum(bvh * model) / sum(model^2) over its child segments; a joint without mapped children (a hand, a
    // foot, the head) takes its mapped parent's, the root without any 1.
    std::vector<double> jointFactors;
    // Per model link (numLinks): the factor of the nearest mapped link at or above it, 1 where there is
    // none and for virtual links. The links between two mapped ones (the vertebrae between `abdomen` and
    // `chest`) share the upper one's factor, so that the model's segment scales by it exactly.
    std::vector<double> linkFactors;
};

// unit: m per BVH unit. Throws ModelError at the map's line for a BVH joint or link that is missing, or a
// mapped child whose link is not below its mapped parent's link in the model, or a segment of zero length.
BvhSegmentScales estimateBvhSegmentScales(const BvhMotion& motion, const BvhMap& map, const Model& model, double unit);

// The map for the model scaled by linkFactors (scaleModel): each target point moved with its link's lengths.
BvhMap scaleBvhMapPoints(const BvhMap& map, const Model& model, const std::vector<double>& linkFactors);

}  // namespace sinew

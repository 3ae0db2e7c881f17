#pragma once
// A BVH capture as inverse-kinematics targets (docs/inverse-kinematics.md, "BVH captures"): each mapped BVH
// joint's centre, in the model's ground and in metres, is a marker at its point on its model link (the map's
// `at`; by default the link's origin, its joint centre), and, with the map's orientation_weight > 0, the joint's frame a target for a frame
// fixed on the link.
#include <vector>

#include "sinew/core/marker.hpp"
#include "sinew/core/model.hpp"
#include "sinew/io/bvh_file.hpp"
#include "sinew/io/bvh_map.hpp"
#include "sinew/io/trc_file.hpp"
#include "sinew/tools/inverse_kinematics.hpp"

namespace sinew {

struct BvhTargets {
    std::vector<Marker> markers;  // one per mapped joint, named after it, at its point on its link
    MarkerTable capture;          // the joint centres per frame, m, model ground axes
    // One per mapped joint when the map's orientation_weight > 0: the frame F on the link that follows the
    // BVH joint's frame, F = the link frame at the model's default pose as the BVH frame at its rest pose,
    // turned (for a joint with one mapped child) by the least rotation that lays the model's segment along
    // the BVH's, so that a T-pose rest and an arms-down default pose still agree.
    std::vector<OrientationTask> orientationTasks;
    std::vector<std::vector<Eigen::Matrix3d>> orientations;  // per frame: R_GF per task, model ground axes
    double unit = 0;              // m per BVH unit, as used
};

// Throws ModelError at the map's line for a BVH joint the motion lacks or a link the model lacks.
BvhTargets makeBvhTargets(const BvhMotion& motion, const BvhMap& map, const Model& model);

}  // namespace sinew

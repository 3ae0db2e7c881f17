#pragma once
// A BVH capture as inverse-kinematics targets (docs/inverse-kinematics.md, "BVH captures"): each mapped BVH
// joint's centre, in the model's ground and in metres, is a marker at the origin of its model link (that
// link's joint centre).
#include <vector>

#include "sinew/core/marker.hpp"
#include "sinew/core/model.hpp"
#include "sinew/io/bvh_file.hpp"
#include "sinew/io/bvh_map.hpp"
#include "sinew/io/trc_file.hpp"

namespace sinew {

struct BvhTargets {
    std::vector<Marker> markers;  // one per mapped joint, named after it, at its link's origin
    MarkerTable capture;          // the joint centres per frame, m, model ground axes
    double unit = 0;              // m per BVH unit, as used
};

// Throws ModelError at the map's line for a BVH joint the motion lacks or a link the model lacks.
BvhTargets makeBvhTargets(const BvhMotion& motion, const BvhMap& map, const Model& model);

}  // namespace sinew

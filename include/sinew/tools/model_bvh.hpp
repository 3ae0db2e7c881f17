#pragma once
// A model's motion as a BVH skeleton through a BVH map (docs/inverse-kinematics.md, "BVH captures"): the
// inverse of makeBvhTargets, for exporting a fit and for captures whose true pose is known. One BVH joint per
// mapped link, its parent the nearest mapped link above it; its rest pose (every channel 0) is the model's
// default pose, its frame there the BVH axes, so that at a pose q its rotation is its link's rotation since
// the default pose and its centre its link's point (the map's `at`). Every joint has position channels and rotation
// channels (Xposition Yposition Zposition Zrotation Xrotation Yrotation), so that links between two mapped
// ones, which no BVH joint follows, still leave every centre where the model puts it.
#include <Eigen/Core>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/io/bvh_file.hpp"
#include "sinew/io/bvh_map.hpp"

namespace sinew {

// frames: q (nq) per frame; unit: m per BVH unit to write (0: the map's, or 0.01 for `auto`). Throws
// ModelError at the map's line for a link the model lacks, and sinew::Error when the mapped links have
// other than one topmost link (the BVH root).
BvhMotion makeModelBvh(const Model& model, const BvhMap& map, const std::vector<Eigen::VectorXd>& frames,
                       double frameTime, double unit = 0);

}  // namespace sinew

#pragma once
// Which BVH joints are targets for which model links, and how the BVH frame sits in the model's ground: the
// map `sinew ik` needs for a BVH capture (docs/inverse-kinematics.md, "BVH captures"; the whole-body model's
// is models/whole_body/bvh_map.yaml).
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace sinew {

struct BvhMap {
    std::string source;
    double unit = 0;  // m per BVH unit; 0: inferred from the skeleton (inferBvhLengthUnit)
    Eigen::Matrix3d R_GB = Eigen::Matrix3d::Identity();  // the BVH frame's axes in the model's ground
    std::vector<std::pair<std::string, std::string>> joints;  // (BVH joint, model link), in file order
    std::vector<std::string> where;                           // "file:line" of each pair
};

// Throws ModelError at "file:line" for an unknown key, a unit that is neither `auto` nor a positive
// number, axes that are no rotation, a joint named twice or no joint at all.
BvhMap readBvhMap(const std::string& path);

}  // namespace sinew

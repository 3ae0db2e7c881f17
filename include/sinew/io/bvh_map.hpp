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
    // m^2/rad^2: the weight of each mapped joint's orientation as a target for its link's (a joint
    // centre's is 1); 0 fits the joint centres alone.
    double orientationWeight = 0;
    std::vector<std::pair<std::string, std::string>> joints;  // (BVH joint, model link), in file order
    // Per pair: the point of the link (m, link frame) that follows the BVH joint's centre; 0, the link's
    // origin, unless the map gives `at`.
    std::vector<Eigen::Vector3d> points;
    std::vector<std::string> where;                           // "file:line" of each pair
};

// A joint maps to a link name, or to {link: NAME, at: [x, y, z]}.
// Throws ModelError at "file:line" for an unknown key, a unit that is neither `auto` nor a positive
// number, an orientation_weight that is negative or not finite, axes that are no rotation, a joint named twice or no joint at all.
BvhMap readBvhMap(const std::string& path);

}  // namespace sinew

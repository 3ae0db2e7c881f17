#include "sinew/tools/bvh_targets.hpp"


#include "sinew/core/error.hpp"

namespace sinew {

BvhTargets makeBvhTargets(const BvhMotion& motion, const BvhMap& map, const Model& model) {
    BvhTargets targets;
    targets.unit = map.unit > 0 ? map.unit : inferBvhLengthUnit(motion);
    std::vector<int> joints;
    for (std::size_t k = 0; k < map.joints.size(); ++k) {
        const auto& [bvh, link] = map.joints[k];
        const int joint = findBvhJoint(motion, bvh);
        if (joint < 0) throw ModelError(map.where[k], "BVH joint '" + bvh + "' is not in " + motion.source);
        const int index = model.findLinkIndex(link);
        if (index == Model::kNotFound || index == kGround)
            throw ModelError(map.where[k], "BVH joint '" + bvh + "': model '" + model.getName() + "' has no link '" + link + "'");
        joints.push_back(joint);
        targets.markers.push_back({bvh, index, Eigen::Vector3d::Zero(), map.where[k]});
        targets.capture.markers.push_back(bvh);
    }
    targets.capture.source = motion.source;
    targets.capture.dataRate = 1 / motion.frameTime;
    for (Eigen::Index frame = 0; frame < motion.values.rows(); ++frame) {
        const std::vector<BvhPose> poses = calcBvhPoses(motion, static_cast<int>(frame));
        Eigen::Matrix3Xd positions(3, static_cast<Eigen::Index>(joints.size()));
        for (std::size_t k = 0; k < joints.size(); ++k)
            positions.col(static_cast<Eigen::Index>(k)) = targets.unit * map.R_GB * poses[static_cast<std::size_t>(joints[k])].p_GJ;
        targets.capture.frameNumbers.push_back(static_cast<int>(frame) + 1);
        targets.capture.times.push_back(static_cast<double>(frame) * motion.frameTime);
        targets.capture.positions.push_back(positions);
    }
    return targets;
}

}  // namespace sinew

#include "sinew/tools/bvh_targets.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"

namespace sinew {
namespace {

Eigen::Vector3d calcMappedPoint_G(const Data& data, const BvhMap& map, const std::vector<int>& links, std::size_t k) {
    const std::size_t b = static_cast<std::size_t>(links[k]);
    return data.p_GB[b] + data.R_GB[b] * map.points[k];
}

// R_BF of each mapped joint's orientation task (bvh_targets.hpp): R_BF = R_GB0^T M Q^T, with M the BVH axes in
// ground and Q the least rotation (in BVH axes) from the model's segment to the BVH rest pose's.
std::vector<OrientationTask> makeOrientationTasks(const BvhMotion& motion, const BvhMap& map, const Model& model,
                                                  const std::vector<int>& joints, const std::vector<int>& links) {
    BvhMotion rest = motion;
    rest.values = Eigen::MatrixXd::Zero(1, motion.values.cols());
    const std::vector<BvhPose> poses = calcBvhPoses(rest, 0);
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    const Eigen::Matrix3d& M = map.R_GB;
    std::vector<OrientationTask> tasks;
    for (std::size_t k = 0; k < joints.size(); ++k) {
        // The mapped children: the mapped joints whose nearest mapped BVH ancestor is this one.
        std::vector<std::size_t> children;
        for (std::size_t c = 0; c < joints.size(); ++c) {
            int j = motion.joints[static_cast<std::size_t>(joints[c])].parent;
            while (j >= 0 && std::find(joints.begin(), joints.end(), j) == joints.end())
                j = motion.joints[static_cast<std::size_t>(j)].parent;
            if (j == joints[k]) children.push_back(c);
        }
        const std::size_t b = static_cast<std::size_t>(links[k]);
        Eigen::Matrix3d Q = Eigen::Matrix3d::Identity();
        if (children.size() == 1) {
            const std::size_t c = children[0];
            const Eigen::Vector3d segment = M.transpose() * (calcMappedPoint_G(data, map, links, c) - calcMappedPoint_G(data, map, links, k));
            const Eigen::Vector3d bvh = poses[static_cast<std::size_t>(joints[c])].p_GJ - poses[static_cast<std::size_t>(joints[k])].p_GJ;
            Q = Eigen::Quaterniond::FromTwoVectors(segment, bvh).toRotationMatrix();
        }
        tasks.push_back({model.getLink(links[k]).name, data.R_GB[b].transpose() * M * Q.transpose(), map.orientationWeight});
    }
    return tasks;
}

}  // namespace

BvhTargets makeBvhTargets(const BvhMotion& motion, const BvhMap& map, const Model& model) {
    BvhTargets targets;
    targets.unit = map.unit > 0 ? map.unit : inferBvhLengthUnit(motion);
    std::vector<int> joints, links;
    for (std::size_t k = 0; k < map.joints.size(); ++k) {
        const auto& [bvh, link] = map.joints[k];
        const int joint = findBvhJoint(motion, bvh);
        if (joint < 0) throw ModelError(map.where[k], "BVH joint '" + bvh + "' is not in " + motion.source);
        const int index = model.findLinkIndex(link);
        if (index == Model::kNotFound || index == kGround)
            throw ModelError(map.where[k], "BVH joint '" + bvh + "': model '" + model.getName() + "' has no link '" + link + "'");
        joints.push_back(joint);
        links.push_back(index);
        targets.markers.push_back({bvh, index, map.points[k], map.where[k]});
        targets.capture.markers.push_back(bvh);
    }
    if (map.orientationWeight > 0) targets.orientationTasks = makeOrientationTasks(motion, map, model, joints, links);
    targets.capture.source = motion.source;
    targets.capture.dataRate = 1 / motion.frameTime;
    for (Eigen::Index frame = 0; frame < motion.values.rows(); ++frame) {
        const std::vector<BvhPose> poses = calcBvhPoses(motion, static_cast<int>(frame));
        Eigen::Matrix3Xd positions(3, static_cast<Eigen::Index>(joints.size()));
        std::vector<Eigen::Matrix3d> orientations;
        for (std::size_t k = 0; k < joints.size(); ++k) {
            const BvhPose& pose = poses[static_cast<std::size_t>(joints[k])];
            positions.col(static_cast<Eigen::Index>(k)) = targets.unit * map.R_GB * pose.p_GJ;
            if (!targets.orientationTasks.empty()) orientations.push_back(map.R_GB * pose.R_GJ);
        }
        targets.capture.frameNumbers.push_back(static_cast<int>(frame) + 1);
        targets.capture.times.push_back(static_cast<double>(frame) * motion.frameTime);
        targets.capture.positions.push_back(positions);
        if (!targets.orientationTasks.empty()) targets.orientations.push_back(std::move(orientations));
    }
    return targets;
}

}  // namespace sinew

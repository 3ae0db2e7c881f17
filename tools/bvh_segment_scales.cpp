#include "sinew/tools/bvh_segment_scales.hpp"

#include <map>

#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"

namespace sinew {
namespace {

bool isBelow(const Model& model, int link, int ancestor) {
    for (int i = link; i != kGround; i = model.getJoint(i).parent)
        if (i == ancestor) return true;
    return false;
}

}  // namespace

BvhSegmentScales estimateBvhSegmentScales(const BvhMotion& motion, const BvhMap& map, const Model& model, double unit) {
    const std::size_t mapped = map.joints.size();
    std::vector<int> bvhJoint(mapped), link(mapped);
    std::map<int, std::size_t> mappedOfBvh;
    std::map<int, std::size_t> mappedOfLink;
    for (std::size_t k = 0; k < mapped; ++k) {
        bvhJoint[k] = findBvhJoint(motion, map.joints[k].first);
        link[k] = model.findLinkIndex(map.joints[k].second);
        if (bvhJoint[k] < 0) throw ModelError(map.where[k], "BVH joint '" + map.joints[k].first + "' is not in " + motion.source);
        if (link[k] < 0)
            throw ModelError(map.where[k], "model '" + model.getName() + "' has no link '" + map.joints[k].second + "'");
        mappedOfBvh[bvhJoint[k]] = k;
        mappedOfLink.emplace(link[k], k);
    }
    // The rest pose: the skeleton as its offsets draw it, whatever the motion does.
    BvhMotion rest = motion;
    rest.values = Eigen::MatrixXd::Zero(1, motion.values.cols());
    const std::vector<BvhPose> poses = calcBvhPoses(rest, 0);
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    BvhSegmentScales scales;
    std::vector<int> mappedParent(mapped, -1);
    std::vector<double> crossed(mapped, 0), squared(mapped, 0);
    for (std::size_t k = 0; k < mapped; ++k) {
        int j = motion.joints[static_cast<std::size_t>(bvhJoint[k])].parent;
        while (j >= 0 && !mappedOfBvh.count(j)) j = motion.joints[static_cast<std::size_t>(j)].parent;
        if (j < 0) continue;
        const std::size_t p = mappedOfBvh[j];
        mappedParent[k] = static_cast<int>(p);
        if (!isBelow(model, link[k], link[p]))
            throw ModelError(map.where[k], "link '" + map.joints[k].second + "' of BVH joint '" + map.joints[k].first +
                                               "' is not below link '" + map.joints[p].second + "' of its BVH parent '" +
                                               map.joints[p].first + "' in model '" + model.getName() + "'");
        BvhSegment segment{map.joints[p].first, map.joints[k].first, 0, 0};
        segment.bvhLength = unit * (poses[static_cast<std::size_t>(bvhJoint[k])].p_GJ - poses[static_cast<std::size_t>(j)].p_GJ).norm();
        const auto point_G = [&](std::size_t m) {
            const std::size_t b = static_cast<std::size_t>(link[m]);
            return Eigen::Vector3d(data.p_GB[b] + data.R_GB[b] * map.points[m]);
        };
        segment.modelLength = (point_G(k) - point_G(p)).norm();
        if (!(segment.bvhLength > 0) || !(segment.modelLength > 0))
            throw ModelError(map.where[k], "the segment from '" + segment.parent + "' to '" + segment.child +
                                               "' has zero length in the BVH rest pose or the model");
        crossed[p] += segment.bvhLength * segment.modelLength;
        squared[p] += segment.modelLength * segment.modelLength;
        scales.segments.push_back(segment);
    }
    scales.jointFactors.assign(mapped, 1);
    for (std::size_t k = 0; k < mapped; ++k) {
        // A joint without mapped children: its nearest mapped ancestor's segment that has some.
        int from = static_cast<int>(k);
        while (from >= 0 && squared[static_cast<std::size_t>(from)] == 0) from = mappedParent[static_cast<std::size_t>(from)];
        if (from >= 0) scales.jointFactors[k] = crossed[static_cast<std::size_t>(from)] / squared[static_cast<std::size_t>(from)];
    }
    scales.linkFactors.assign(static_cast<std::size_t>(model.getNumLinks()), 1);
    for (int i = 0; i < model.getNumLinks(); ++i) {
        if (model.getLink(i).isVirtual) continue;
        for (int a = i; a != kGround; a = model.getJoint(a).parent)
            if (const auto found = mappedOfLink.find(a); found != mappedOfLink.end()) {
                scales.linkFactors[static_cast<std::size_t>(i)] = scales.jointFactors[found->second];
                break;
            }
    }
    return scales;
}

BvhMap scaleBvhMapPoints(const BvhMap& map, const Model& model, const std::vector<double>& linkFactors) {
    BvhMap scaled = map;
    for (std::size_t k = 0; k < map.joints.size(); ++k) {
        const int link = model.findLinkIndex(map.joints[k].second);
        if (link >= 0) scaled.points[k] *= linkFactors[static_cast<std::size_t>(link)];
    }
    return scaled;
}

}  // namespace sinew

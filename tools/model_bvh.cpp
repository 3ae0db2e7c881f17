#include "sinew/tools/model_bvh.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <functional>

#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"

namespace sinew {
namespace {

constexpr double kDegrees = 180 / M_PI;
const std::vector<BvhChannel> kChannels = {BvhChannel::Xposition, BvhChannel::Yposition, BvhChannel::Zposition,
                                           BvhChannel::Zrotation, BvhChannel::Xrotation, BvhChannel::Yrotation};

}  // namespace

BvhMotion makeModelBvh(const Model& model, const BvhMap& map, const std::vector<Eigen::VectorXd>& frames,
                       double frameTime, double unit) {
    if (unit <= 0) unit = map.unit > 0 ? map.unit : 0.01;
    const std::size_t mapped = map.joints.size();
    std::vector<int> link(mapped), parent(mapped, -1);
    for (std::size_t k = 0; k < mapped; ++k) {
        link[k] = model.findLinkIndex(map.joints[k].second);
        if (link[k] < 0) throw ModelError(map.where[k], "model '" + model.getName() + "' has no link '" + map.joints[k].second + "'");
    }
    std::vector<int> roots;
    for (std::size_t k = 0; k < mapped; ++k) {
        for (int a = model.getJoint(link[k]).parent; a != kGround && parent[k] < 0; a = model.getJoint(a).parent)
            for (std::size_t p = 0; p < mapped; ++p)
                if (link[p] == a) parent[k] = static_cast<int>(p);
        if (parent[k] < 0) roots.push_back(static_cast<int>(k));
    }
    if (roots.size() != 1)
        throw Error(map.source + ": " + std::to_string(roots.size()) + " mapped links have no mapped link above them; a "
                                 "BVH skeleton needs one root");
    Data rest(model), data(model);
    calcPositionKinematics(model, rest, model.getDefaultQ());
    // The centre of BVH joint k: its point on its link.
    const auto centre_G = [&](const Data& d, std::size_t k) {
        const std::size_t b = static_cast<std::size_t>(link[k]);
        return Eigen::Vector3d(d.p_GB[b] + d.R_GB[b] * map.points[k]);
    };
    const Eigen::Matrix3d& M = map.R_GB;  // BVH axes in ground
    BvhMotion motion;
    motion.frameTime = frameTime;
    std::vector<int> order;  // map index of each BVH joint, depth first
    const std::function<void(int, int)> add = [&](int k, int bvhParent) {
        BvhJoint joint;
        joint.name = map.joints[static_cast<std::size_t>(k)].first;
        joint.parent = bvhParent;
        if (bvhParent >= 0)
            joint.offset = M.transpose() *
                           (centre_G(rest, static_cast<std::size_t>(k)) -
                            centre_G(rest, static_cast<std::size_t>(order[static_cast<std::size_t>(bvhParent)]))) / unit;
        joint.channels = kChannels;
        joint.firstChannel = 6 * static_cast<int>(motion.joints.size());
        const int self = static_cast<int>(motion.joints.size());
        motion.joints.push_back(joint);
        order.push_back(k);
        for (std::size_t c = 0; c < mapped; ++c)
            if (parent[c] == k) add(static_cast<int>(c), self);
    };
    add(roots[0], -1);
    motion.values.resize(static_cast<Eigen::Index>(frames.size()), 6 * static_cast<Eigen::Index>(motion.joints.size()));
    for (std::size_t f = 0; f < frames.size(); ++f) {
        calcPositionKinematics(model, data, frames[f]);
        std::vector<Eigen::Matrix3d> R_BvhJ(motion.joints.size());  // each joint's axes in the BVH frame
        for (std::size_t j = 0; j < motion.joints.size(); ++j) {
            const std::size_t k = static_cast<std::size_t>(order[j]);
            const std::size_t b = static_cast<std::size_t>(link[k]);
            R_BvhJ[j] = M.transpose() * data.R_GB[b] * rest.R_GB[b].transpose() * M;
            const int p = motion.joints[j].parent;
            Eigen::Vector3d p_PJ = M.transpose() * centre_G(data, k) / unit;
            Eigen::Matrix3d R_PJ = R_BvhJ[j];
            if (p >= 0) {
                const std::size_t a = static_cast<std::size_t>(order[static_cast<std::size_t>(p)]);
                const Eigen::Matrix3d& R_BvhP = R_BvhJ[static_cast<std::size_t>(p)];
                p_PJ = R_BvhP.transpose() * M.transpose() * (centre_G(data, k) - centre_G(data, a)) / unit;
                R_PJ = R_BvhP.transpose() * R_BvhJ[j];
            }
            // Zrotation Xrotation Yrotation: R_PJ = Rz(a) Rx(b) Ry(c), Eigen's eulerAngles(2, 0, 1).
            const Eigen::Vector3d angles = R_PJ.eulerAngles(2, 0, 1) * kDegrees;
            auto row = motion.values.row(static_cast<Eigen::Index>(f));
            row.segment<3>(static_cast<Eigen::Index>(6 * j)) = (p_PJ - motion.joints[j].offset).transpose();
            row.segment<3>(static_cast<Eigen::Index>(6 * j + 3)) = angles.transpose();
        }
    }
    return motion;
}

}  // namespace sinew

#pragma once
// A subject of known proportions for the BVH tests: the whole-body model scaled by known factors per
// mapped BVH joint (models/whole_body/bvh_map.yaml), and random poses of it.
#include <map>
#include <random>
#include <string>
#include <vector>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/model.hpp"
#include "sinew/io/bvh_map.hpp"

namespace sinew::test {

// Per mapped BVH joint: its segment's factor (to its mapped children); a joint without mapped children
// (the head, hands, feet) has its mapped parent's, which is what a skeleton shows of it.
inline std::map<std::string, double> knownBvhFactors() {
    return {{"hip", 1.08},      {"abdomen", 0.93}, {"chest", 1.04},  {"neck", 1.07},    {"head", 1.07},   {"rCollar", 1.15},
            {"rShldr", 0.97},   {"rForeArm", 1.1}, {"rHand", 1.1},   {"lCollar", 1.12}, {"lShldr", 0.99},
            {"lForeArm", 1.06}, {"lHand", 1.06},   {"rThigh", 1.11}, {"rShin", 0.95},   {"rFoot", 0.95},
            {"lThigh", 1.09},   {"lShin", 0.96},   {"lFoot", 0.96}};
}

// Per link: the factor of the nearest mapped link at or above it (the definition in bvh_segment_scales.hpp).
inline std::vector<double> linkFactorsOf(const Model& model, const BvhMap& map, const std::map<std::string, double>& perJoint) {
    std::vector<double> factors(static_cast<std::size_t>(model.getNumLinks()), 1.0);
    for (int i = 0; i < model.getNumLinks(); ++i) {
        bool found = false;
        for (int a = i; a != kGround && !found; a = model.getJoint(a).parent)
            for (const auto& [bvh, link] : map.joints)
                if (model.getLink(a).name == link) {
                    factors[static_cast<std::size_t>(i)] = perJoint.at(bvh);
                    found = true;
                }
    }
    return factors;
}

// Speeds (nu) turning every ball joint by up to `size` rad per axis; free joints (the root, the virtual
// links) still.
inline Eigen::VectorXd randomBallSpeeds(const Model& model, double size, std::mt19937& rng) {
    std::uniform_real_distribution<double> uniform(-size, size);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(model.getNumU());
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Joint& joint = model.getJoint(i);
        if (joint.type != JointType::Ball) continue;
        for (int k = 0; k < 3; ++k) u[joint.uStart + k] = uniform(rng);
    }
    return u;
}

// The default pose turned so.
inline Eigen::VectorXd randomBallPose(const Model& model, double size, std::mt19937& rng) {
    return integrateCoordinates(model, model.getDefaultQ(), randomBallSpeeds(model, size, rng), 1.0);
}

}  // namespace sinew::test

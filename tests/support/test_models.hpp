#pragma once
// Models the tests sweep: random trees, chains and binary trees with loops, virtual links and wires, plus
// the shipped arm. Each is built from a seed, so a failure names a reproducible case.
#include <string>
#include <vector>

#include "sinew/core/random_model.hpp"
#include "sinew/io/model_file.hpp"

namespace sinew::test {

struct NamedModel {
    std::string name;
    Model model;
};

inline std::string describe(const RandomModelOptions& o) {
    return "random(links=" + std::to_string(o.numLinks) + ", loops=" + std::to_string(o.numLoops) +
           ", virtual=" + std::to_string(o.numVirtualLinks) + ", seed=" + std::to_string(o.seed) + ")";
}

// Random models of 1 to 40 links; `withVirtualLinks` false for systems Simbody must integrate.
inline std::vector<NamedModel> makeRandomModels(int count, bool withVirtualLinks, double damping = 1.0) {
    std::vector<NamedModel> models;
    const RandomModelOptions::Topology topologies[] = {RandomModelOptions::Topology::RandomTree,
                                                       RandomModelOptions::Topology::Chain,
                                                       RandomModelOptions::Topology::BinaryTree};
    const JointType roots[] = {JointType::Free, JointType::Ball, JointType::Weld};
    for (int i = 0; i < count; ++i) {
        RandomModelOptions o;
        o.seed = static_cast<unsigned>(1000 + i);
        o.numLinks = 1 + (i * 7) % 40;
        o.topology = topologies[i % 3];
        o.rootJoint = roots[(i / 3) % 3];
        o.numLoops = o.numLinks >= 2 ? i % 5 : 0;
        o.numWires = 2 + 3 * o.numLinks;
        o.maxViaPoints = i % 4;
        o.numVirtualLinks = withVirtualLinks ? i % 3 : 0;
        o.damping = damping;
        models.push_back({describe(o), generateRandomModel(o)});
    }
    return models;
}

inline std::string sourcePath(const std::string& relative) { return std::string(SINEW_SOURCE_DIR) + "/" + relative; }

inline NamedModel loadArm26() { return {"arm26", readModelFile(sourcePath("models/arm26.yaml"))}; }

}  // namespace sinew::test

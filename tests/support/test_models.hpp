#pragma once
// Models the tests sweep: random trees, chains and binary trees with loops, virtual links and wires, plus
// the shipped arm. Each is built from a seed, so a failure names a reproducible case.
#include <string>
#include <vector>

#include "support/random_model.hpp"
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

// A family of random models: model i has firstLinks + (i * linkStride) % linkRange links, i % loopCycle
// loops, wiresBase + wiresPerLink * links wires with up to i % viaCycle via-points, i % 3 virtual links
// (when allowed), cycling through random trees, chains and binary trees, free, ball and weld roots.
struct RandomModelSweep {
    int count = 30;
    int firstLinks = 1, linkStride = 7, linkRange = 40;
    int loopCycle = 5;
    int wiresBase = 2, wiresPerLink = 3;
    int viaCycle = 4;
    bool virtualLinks = true;
    double damping = 1.0;
    unsigned seedBase = 1000;
};

inline std::vector<NamedModel> makeRandomModels(const RandomModelSweep& sweep) {
    std::vector<NamedModel> models;
    const RandomModelOptions::Topology topologies[] = {RandomModelOptions::Topology::RandomTree,
                                                       RandomModelOptions::Topology::Chain,
                                                       RandomModelOptions::Topology::BinaryTree};
    const JointType roots[] = {JointType::Free, JointType::Ball, JointType::Weld};
    for (int i = 0; i < sweep.count; ++i) {
        RandomModelOptions o;
        o.seed = sweep.seedBase + static_cast<unsigned>(i);
        o.numLinks = sweep.firstLinks + (i * sweep.linkStride) % sweep.linkRange;
        o.topology = topologies[i % 3];
        o.rootJoint = roots[(i / 3) % 3];
        o.numLoops = o.numLinks >= 2 ? i % sweep.loopCycle : 0;
        o.numWires = sweep.wiresBase + sweep.wiresPerLink * o.numLinks;
        o.maxViaPoints = i % sweep.viaCycle;
        o.numVirtualLinks = sweep.virtualLinks ? i % 3 : 0;
        o.damping = sweep.damping;
        models.push_back({describe(o), generateRandomModel(o)});
    }
    return models;
}

// Random models of 1 to 40 links with 0 to 4 loops; `withVirtualLinks` false for systems Simbody must
// integrate.
inline std::vector<NamedModel> makeRandomModels(int count, bool withVirtualLinks, double damping = 1.0) {
    RandomModelSweep sweep;
    sweep.count = count;
    sweep.virtualLinks = withVirtualLinks;
    sweep.damping = damping;
    return makeRandomModels(sweep);
}

inline std::string sourcePath(const std::string& relative) { return std::string(SINEW_SOURCE_DIR) + "/" + relative; }

inline NamedModel loadArm26() { return {"arm26", readModelFile(sourcePath("models/arm26.yaml"))}; }

}  // namespace sinew::test

#pragma once
// Models whose virtual links stay pulled: a chain of links hanging along -y with forks of three short
// spring-damper wires, each fork's branches anchored on three different links around its virtual link, with
// rest lengths half the default ones (by default), so that no pose lets all three go slack. (generateRandomModel's forks
// have rest lengths near their default lengths, and their virtual links mostly find a pose where every
// branch is slack.) Reproducible from a seed.
#include <random>
#include <string>

#include "sinew/core/model_builder.hpp"

namespace sinew::test {

struct ForkedModelOptions {
    int numLinks = 6;              // >= 3
    JointType rootJoint = JointType::Free;
    int numForks = 2;              // virtual links, on links (i, i+1, i+2) for i = 0, 1, ...
    bool loop = false;             // a ball loop between links 0 and 2
    double damping = 1.0;          // N s/m on every wire
    double forkRestFraction = 0.5;  // fork branches' rest lengths over their default lengths
    double forkStiffness = 0;       // N/m of the fork branches; 0: random in [300, 1000]
    // > 0: the heads are muscles pulling with this constant tension (N, "prescribed_tension", as an active
    // biceps's heads), only the tail a spring-damper, which the heads keep taut: no wire of the fork slacks.
    double headTension = 0;
    bool jointWires = true;  // spring-dampers across each joint besides the forks
    unsigned seed = 1;
};

inline Model makeForkedModel(const ForkedModelOptions& o) {
    std::mt19937 rng(o.seed);
    auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    auto jitter = [&](double scale) { return Eigen::Vector3d(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)); };
    const double spacing = 0.3;  // m between link origins along -y at the default pose (all joints at identity)
    auto linkName = [](int i) { return "link" + std::to_string(i); };
    ModelBuilder builder("forked" + std::to_string(o.seed));
    for (int i = 0; i < o.numLinks; ++i) {
        LinkSpec link;
        link.name = linkName(i);
        link.mass = uniform(0.5, 2.0);
        link.com_B = Eigen::Vector3d(0, -0.5 * spacing, 0) + jitter(0.02);
        link.inertia_Bcom = Eigen::Vector3d(uniform(0.012, 0.015), uniform(0.006, 0.008), uniform(0.012, 0.015)).asDiagonal();
        builder.addLink(link);
        JointSpec joint;
        joint.name = "joint" + std::to_string(i);
        joint.child = link.name;
        joint.parent = i == 0 ? "ground" : linkName(i - 1);
        joint.type = i == 0 ? o.rootJoint : (i % 3 == 2 ? JointType::Pin : JointType::Ball);
        if (joint.type == JointType::Pin) joint.axis = Eigen::Vector3d(1, uniform(-0.3, 0.3), uniform(-0.3, 0.3));
        if (i > 0) joint.p_PF = Eigen::Vector3d(0, -spacing, 0);
        if (i > 0 && joint.type == JointType::Ball && !o.loop) joint.initialRotation = jitter(0.05);  // loop closed at identity
        builder.addJoint(joint);
    }
    // A spring-damper (stiffness > 0) or a muscle pulling with headTension (stiffness 0).
    auto addWire = [&](const std::string& name, const std::string& linkA, const Eigen::Vector3d& pA,
                       const std::string& linkB, const Eigen::Vector3d& pB, double stiffness, double restLength) {
        WireSpec wire;
        wire.name = name;
        for (const auto& [link, p_B] : {std::pair(linkA, pA), std::pair(linkB, pB)}) {
            WirePointSpec point;
            point.link = link;
            point.p_B = p_B;
            wire.points.push_back(point);
        }
        if (stiffness > 0) {
            wire.law.type = "spring_damper";
            wire.law.parameters.set("stiffness", {stiffness});
            wire.law.parameters.set("damping", {o.damping});
            wire.law.parameters.set("rest_length", {restLength});
        } else {
            wire.law.type = "prescribed_tension";
            wire.law.parameters.set("tension", {o.headTension});
        }
        builder.addWire(wire);
    };
    // Ordinary wires across each joint, taut at the default pose.
    for (int i = 1; i < o.numLinks && o.jointWires; ++i) {
        const Eigen::Vector3d a = Eigen::Vector3d(0.05, -0.6 * spacing, 0.02) + jitter(0.02);
        const Eigen::Vector3d b = Eigen::Vector3d(0.05, -0.4 * spacing, 0.02) + jitter(0.02);
        const double length = (Eigen::Vector3d(0, -spacing, 0) + b - a).norm();
        addWire("wire" + std::to_string(i), linkName(i - 1), a, linkName(i), b, uniform(300, 1000), 0.8 * length);
    }
    // Forks: heads on links i and i+2 (on opposite sides), tail on link i+1, virtual link between them.
    for (int f = 0; f < o.numForks && f + 2 < o.numLinks; ++f) {
        const std::string name = "virtual" + std::to_string(f);
        const Eigen::Vector3d fork_G = Eigen::Vector3d(0.08, -spacing * (f + 1), 0.05) + jitter(0.02);
        VirtualLinkSpec link;
        link.name = name;
        link.initialPosition = fork_G;
        builder.addVirtualLink(link);
        const Eigen::Vector3d anchors_B[3] = {Eigen::Vector3d(0.1, -0.1, 0.1) + jitter(0.02),
                                              Eigen::Vector3d(0.2, -0.15, 0.0) + jitter(0.02),
                                              Eigen::Vector3d(0.1, 0.1, -0.05) + jitter(0.02)};
        const char* parts[3] = {"_head0", "_tail", "_head1"};
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d onVirtual = jitter(0.015);
            const Eigen::Vector3d anchor_G = Eigen::Vector3d(0, -spacing * (f + k), 0) + anchors_B[k];
            const double rest = o.forkRestFraction * (anchor_G - (fork_G + onVirtual)).norm();
            const double stiffness = uniform(300, 1000) * (o.forkStiffness > 0 ? 0 : 1) + o.forkStiffness;
            if (k == 1)
                addWire(name + parts[k], name, onVirtual, linkName(f + k), anchors_B[k], stiffness, rest);
            else
                addWire(name + parts[k], linkName(f + k), anchors_B[k], name, onVirtual,
                        o.headTension > 0 ? 0.0 : stiffness, rest);
        }
    }
    if (o.loop && o.numLinks >= 3) {
        // Links 0 and 2 meet at a point beside link 1 at the default pose (joint rotations small there).
        LoopSpec loop;
        loop.name = "loop0";
        loop.linkA = linkName(0);
        loop.linkB = linkName(2);
        const Eigen::Vector3d p_G(-0.1, -1.5 * spacing, 0);
        loop.p_A = p_G;
        loop.p_B = p_G - Eigen::Vector3d(0, -2 * spacing, 0);
        builder.addLoop(loop);
    }
    return builder.build();
}

}  // namespace sinew::test

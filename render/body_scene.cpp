#include "sinew/render/body_scene.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path_samples.hpp"

namespace sinew {
namespace {

// A massless link with no extent still shows where it is.
constexpr double kMarkerRadius = 0.02;  // m
// A bone's share of its limb's radius (the rest is flesh that the wires are).
constexpr double kBoneFraction = 0.4;
// A wrap's arc is drawn as chords of at most 5 degrees: within 0.1% of the radius of the surface.
constexpr double kWrapStepAngle = M_PI / 36;  // rad

// Smallest principal moment of inertia about the centre of mass (kg m^2), 0 for a massless link.
double calcSmallestMoment(const Link& link) {
    if (!(link.mass > 0)) return 0;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(link.inertia_Bcom, Eigen::EigenvaluesOnly);
    return std::max(solver.eigenvalues().minCoeff(), 0.0);
}

BoneCapsule makeCapsule(const Link& link, int index, const Eigen::Vector3d& a_B, const Eigen::Vector3d& b_B) {
    const double length = (b_B - a_B).norm();
    const double moment = calcSmallestMoment(link);
    BoneCapsule capsule{index, a_B, b_B, 0};
    if (length > 0) {
        // A solid cylinder about its axis, I = m r^2 / 2, gives the limb's girth; the bone is drawn at
        // kBoneFraction of it so that the wires over it stay in sight.
        const double r = link.mass > 0 ? kBoneFraction * std::sqrt(2 * moment / link.mass) : 0;
        capsule.radius = std::clamp(r, 0.03 * length, 0.12 * length);
    } else {
        // A solid sphere: I = 2 m r^2 / 5.
        capsule.radius = link.mass > 0 && moment > 0 ? kBoneFraction * std::sqrt(2.5 * moment / link.mass) : kMarkerRadius;
    }
    return capsule;
}

}  // namespace

std::vector<BoneCapsule> calcBoneCapsules(const Model& model) {
    // Joint centres where the default pose puts them: a custom joint (OpenSim's knee) may translate its
    // child's frame away from p_PF as it turns.
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    std::vector<std::vector<Eigen::Vector3d>> childJoints_B(static_cast<std::size_t>(model.getNumLinks()));
    for (int c = 0; c < model.getNumLinks(); ++c) {
        const std::size_t parent = static_cast<std::size_t>(model.getJoint(c).parent);
        if (model.getJoint(c).parent != kGround && !model.getLink(c).isVirtual)
            childJoints_B[parent].push_back(data.R_GB[parent].transpose() *
                                            (data.p_GM[static_cast<std::size_t>(c)] - data.p_GB[parent]));
    }
    std::vector<BoneCapsule> capsules;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Link& link = model.getLink(i);
        if (link.isVirtual) continue;
        const Eigen::Vector3d& joint_B = model.getJoint(i).p_BM;
        const std::vector<Eigen::Vector3d>& children = childJoints_B[static_cast<std::size_t>(i)];
        for (const Eigen::Vector3d& child_B : children) capsules.push_back(makeCapsule(link, i, joint_B, child_B));
        if (children.empty()) capsules.push_back(makeCapsule(link, i, joint_B, joint_B + 2 * (link.com_B - joint_B)));
    }
    return capsules;
}

double findRestLength(const Wire& wire) {
    const auto& parameters = wire.lawSpec.parameters.getAll();
    const auto rest = parameters.find("rest_length");
    if (rest == parameters.end() || rest->second.size() != 1) return std::numeric_limits<double>::quiet_NaN();
    return rest->second[0];
}

bool isShadedByStrain(const Wire& wire) { return wire.kind == WireKind::Ligament && findRestLength(wire) > 0; }

void getWirePath_G(const Model& model, const Data& data, int w, std::vector<Eigen::Vector3d>& path_G) {
    std::vector<WirePathSample> samples;
    calcWirePathSamples(model, data, w, kWrapStepAngle, samples);
    path_G.clear();
    for (const WirePathSample& sample : samples) path_G.push_back(sample.p_G);
}

BodyFrame calcBodyFrame(const Model& model, const Data& data, const std::vector<BoneCapsule>& capsules,
                        double time, const Eigen::VectorXd& tensions) {
    BodyFrame frame;
    frame.time = time;
    for (const BoneCapsule& c : capsules) {
        const Eigen::Matrix3d& R_GB = data.R_GB[static_cast<std::size_t>(c.link)];
        const Eigen::Vector3d& p_GB = data.p_GB[static_cast<std::size_t>(c.link)];
        frame.bones.push_back({c.link, p_GB + R_GB * c.a_B, p_GB + R_GB * c.b_B, c.radius});
    }
    frame.wires.resize(static_cast<std::size_t>(model.getNumWires()));
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        SceneWire& scene = frame.wires[static_cast<std::size_t>(w)];
        getWirePath_G(model, data, w, scene.path_G);
        if (!std::isfinite(tensions[w]) || tensions[w] < 0)
            throw Error("wire '" + wire.name + "': tension " + std::to_string(tensions[w]) + " N at t = " +
                        std::to_string(time) + " s is not a finite number >= 0");
        scene.tension = tensions[w];
        if (isShadedByStrain(wire)) {
            const double restLength = findRestLength(wire);
            scene.strain = (data.wireLength[w] - restLength) / restLength;
        }
    }
    return frame;
}

}  // namespace sinew

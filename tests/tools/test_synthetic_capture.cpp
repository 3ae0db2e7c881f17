// Issue 18's synthetic capture: a motion whose generalized forces are known, because a simulation made it,
// goes through what a user's capture goes through (a BVH file and `sinew ik`'s BVH fit, or a TRC file and the
// marker fit; the fit's .mot; inverse dynamics with OpenSim's processing) and its joint torques come back.
// A body with hips and knees stands on one planted foot (the contact: its shank welded to the floor, as `simulate --hang-by` welds a link) and
// falls under gravity and its spring-damper wires (the known tensions), every joint moving: the free root
// through the stance leg, the swing leg on its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sinew/core/assembly_schedule.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/marker.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/bvh_file.hpp"
#include "sinew/io/bvh_map.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/io/trc_file.hpp"
#include "sinew/tools/bvh_inverse_kinematics.hpp"
#include "sinew/tools/inverse_dynamics_tool.hpp"
#include "sinew/tools/inverse_kinematics_tool.hpp"
#include "sinew/tools/model_bvh.hpp"

namespace sinew {
namespace {

std::string testPath(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sinew_synthetic_capture";
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

constexpr double kRate = 240;       // Hz, the capture's frame rate (and the simulation's report rate)
constexpr double kDuration = 0.6;   // s
const char* const kStanceLeg = "shank_r";

// A trunk on a free joint, ball hips, pin knees (the pins matter: with ball and free joints alone, every
// velocity product in the equations of motion is one of two angular speeds, so speeds of the wrong sign
// would go unseen), and spring-damper wires round every hip and knee, taut at the default pose.
Model makeTwoLeggedModel() {
    std::string text = R"(sinew_model: 1
name: one_leg_stance
gravity: [0, 0, -9.81]
links:
  - {name: trunk, mass: 40, com: [0.02, 0, 0.3], inertia: [2, 2, 0.5, 0, 0, 0]}
  - {name: thigh_r, mass: 8, com: [0, 0, -0.2], inertia: [0.12, 0.12, 0.03, 0, 0, 0]}
  - {name: shank_r, mass: 4, com: [0, 0, -0.22], inertia: [0.07, 0.07, 0.01, 0, 0, 0]}
  - {name: thigh_l, mass: 8, com: [0, 0, -0.2], inertia: [0.12, 0.12, 0.03, 0, 0, 0]}
  - {name: shank_l, mass: 4, com: [0, 0, -0.22], inertia: [0.07, 0.07, 0.01, 0, 0, 0]}
joints:
  - {name: root, type: free, parent: ground, child: trunk, initial_position: [0, 0, 0.9]}
  - {name: hip_r, type: ball, parent: trunk, child: thigh_r, parent_point: [0, -0.1, 0], child_point: [0, 0, 0]}
  - {name: knee_r, type: pin, parent: thigh_r, child: shank_r, parent_point: [0, 0, -0.45], child_point: [0, 0, 0], axis: [0, 1, 0], initial_angle: 0.3}
  - {name: hip_l, type: ball, parent: trunk, child: thigh_l, parent_point: [0, 0.1, 0], child_point: [0, 0, 0]}
  - {name: knee_l, type: pin, parent: thigh_l, child: shank_l, parent_point: [0, 0, -0.45], child_point: [0, 0, 0], axis: [0, 1, 0], initial_angle: 0.3}
loops: []
wires:
)";
    const auto point = [](const std::string& link, const Eigen::Vector3d& p) {
        return "      - {link: " + link + ", at: [" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " +
               std::to_string(p.z()) + "]}\n";
    };
    const auto wire = [&](const std::string& name, const std::string& from, const Eigen::Vector3d& a,
                          const std::string& to, const Eigen::Vector3d& b, double stiffness) {
        text += "  - name: " + name + "\n    kind: muscle\n    points:\n" + point(from, a) + point(to, b);
        text += "    force_law: {type: spring_damper, stiffness: " + std::to_string(stiffness) +
                ", damping: 1, rest_length: 0.25}\n";
    };
    for (const double side : {-1.0, 1.0}) {
        const std::string s = side < 0 ? "_r" : "_l";
        // Four round the hip (front, back, outside, inside), two over the knee (front and back).
        const double at[4][2][2] = {
            {{0.1, 0}, {0.06, 0}}, {{-0.1, 0}, {-0.06, 0}}, {{0, 0.1}, {0, 0.06}}, {{0, -0.1}, {0, -0.06}}};
        for (int w = 0; w < 4; ++w)
            wire("hip" + s + "_" + std::to_string(w), "trunk", {at[w][0][0], side * (0.1 + at[w][0][1]), 0.1}, "thigh" + s,
                 {at[w][1][0], side * at[w][1][1], -0.25}, 300);
        wire("knee" + s + "_front", "thigh" + s, {0.06, 0, -0.2}, "shank" + s, {0.05, 0, -0.1}, 500);
        wire("knee" + s + "_back", "thigh" + s, {-0.06, 0, -0.2}, "shank" + s, {-0.05, 0, -0.1}, 500);
    }
    return readModelText(text, "one_leg_stance.yaml");
}

// The skeleton as a capture would name it, y up as BVH has it: the thighs' joints at the hips, the shins' at
// the ankles, so that the centres alone fix each leg's swing and the frames its twist.
const char* const kMapText = R"(unit: 0.01
axes: [[0, 0, 1], [1, 0, 0], [0, 1, 0]]
orientation_weight: 0.0004
joints:
  hips: trunk
  rThigh: thigh_r
  rShin: {link: shank_r, at: [0, 0, -0.45]}
  lThigh: thigh_l
  lShin: {link: shank_l, at: [0, 0, -0.45]}
)";

// One reported frame of the simulation, and the generalized forces (nu) that made its motion: the wires'
// (-J^T f of the recorded tensions) and the planted foot's (the weld's wrench on the stance leg, as the
// forward dynamics solved it at that state). Gravity is no generalized force here: inverse dynamics, like
// the simulation, has it on its own side (M u̇ + C = tau + gravity).
struct TrueFrame {
    double time = 0;
    Eigen::VectorXd q, u, udot, tau;
};

std::vector<TrueFrame> simulateStandingOnOneFoot(const Model& model, SimulationSummary& summary) {
    ForwardSimulationOptions options;
    options.hangBy = kStanceLeg;
    options.duration = kDuration;
    options.reportInterval = 1 / kRate;
    options.accuracy = 1e-10;
    // A push that turns the trunk over the stance leg and swings the free leg out of line with it.
    options.initialSpeeds = Eigen::VectorXd::Zero(model.getNumU());
    const auto speedsOf = [&](const char* link) { return model.getJoint(model.findLinkIndex(link)).uStart; };
    options.initialSpeeds.segment<3>(speedsOf("thigh_l")) << 1.5, -0.8, 1.0;
    options.initialSpeeds[speedsOf("shank_l")] = 2.0;
    options.initialSpeeds.segment<3>(speedsOf("thigh_r")) << 0.4, 0.6, -0.3;
    options.initialSpeeds[speedsOf("shank_r")] = -1.0;
    std::vector<TrueFrame> frames;
    Data data(model);
    const int hangLink = model.findLinkIndex(kStanceLeg);
    const AssemblySchedule schedule(model, AssemblySchedule::Kind::Automatic, hangLink);
    ForwardDynamicsData fd(model, schedule);
    const Eigen::VectorXd noTau = Eigen::VectorXd::Zero(model.getNumU());
    summary = simulateForwardSinew(model, options, [&](const SimulationFrame& frame) {
        TrueFrame truth;
        truth.time = frame.time;
        truth.q = frame.q;
        truth.u = frame.u;
        calcPositionKinematics(model, data, frame.q);
        calcVelocityKinematics(model, data, frame.u);
        calcWirePaths(model, data);
        truth.tau.resize(model.getNumU());
        calcWireGeneralizedForces(model, data, frame.tensions, truth.tau);  // leaves the wires' F_G
        calcForwardDynamics(model, schedule, data, noTau, data.F_G, fd);
        truth.udot = fd.udot;
        for (SpatialVector& F : data.scratchF_G) F.setZero();
        data.scratchF_G[static_cast<std::size_t>(hangLink)] = fd.hangForce;
        Eigen::VectorXd contact(model.getNumU());
        calcGeneralizedForcesFromLinkForces(model, data, contact);
        truth.tau += contact;
        frames.push_back(truth);
    });
    return frames;
}

// Per joint (the free root split into its moments and its forces): its speeds, u[start, start + size).
struct DofGroup {
    std::string name;
    int start = 0, size = 0;
};

std::vector<DofGroup> makeDofGroups(const Model& model) {
    std::vector<DofGroup> groups;
    for (const Joint& joint : model.getJoints()) {
        if (joint.type == JointType::Free) {
            groups.push_back({joint.name + " moments", joint.uStart, 3});
            groups.push_back({joint.name + " forces", joint.uStart + 3, 3});
        } else if (joint.nu > 0) {
            groups.push_back({joint.name, joint.uStart, joint.nu});
        }
    }
    return groups;
}

// The capture's generalized forces against the simulation's, per DOF group: RMS error over the interior
// frames (the splines' end conditions bend the first and last ones, for OpenSim's tools as for sinew's)
// relative to the RMS of the true forces there.
std::vector<double> compareGeneralizedForces(const Model& model, const std::vector<TrueFrame>& truth,
                                             const StorageTable& forces, int margin, const char* label) {
    const std::vector<DofGroup> groups = makeDofGroups(model);
    std::vector<double> error(groups.size(), 0), size(groups.size(), 0);
    EXPECT_EQ(forces.rows.size(), truth.size());
    const int rows = static_cast<int>(std::min(forces.rows.size(), truth.size()));
    for (int r = margin; r < rows - margin; ++r) {
        const std::size_t f = static_cast<std::size_t>(r);
        EXPECT_NEAR(forces.times[f], truth[f].time, 1e-12);
        for (std::size_t g = 0; g < groups.size(); ++g)
            for (int k = groups[g].start; k < groups[g].start + groups[g].size; ++k) {
                const double ours = forces.rows[f][static_cast<std::size_t>(k)], known = truth[f].tau[k];
                error[g] += (ours - known) * (ours - known);
                size[g] += known * known;
            }
    }
    std::vector<double> relative;
    std::printf("%s, frames %d to %d of %d:\n", label, margin, rows - margin - 1, rows);
    for (std::size_t g = 0; g < groups.size(); ++g) {
        relative.push_back(std::sqrt(error[g] / size[g]));
        const double n = groups[g].size * (rows - 2 * margin);
        std::printf("  %-14s true RMS %9.4g, error RMS %9.3g (%.3g %%)\n", groups[g].name.c_str(), std::sqrt(size[g] / n),
                    std::sqrt(error[g] / n), 100 * relative.back());
    }
    return relative;
}

// The truth is what the simulation's forces were: at every frame, the inverse dynamics of the simulated
// state and its forward-dynamics accelerations gives back the wires' and the planted foot's generalized
// forces, to roundoff.
TEST(SyntheticCapture, TheTrueForcesAreTheWiresAndThePlantedFoot) {
    const Model model = makeTwoLeggedModel();
    SimulationSummary summary;
    const std::vector<TrueFrame> truth = simulateStandingOnOneFoot(model, summary);
    ASSERT_EQ(truth.size(), static_cast<std::size_t>(std::lround(kDuration * kRate)) + 1);
    Data data(model);
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    Eigen::VectorXd tau(model.getNumU());
    double worst = 0, largest = 0;
    for (const TrueFrame& frame : truth) {
        calcInverseDynamics(model, data, frame.q, frame.u, frame.udot, noLoads, tau);
        worst = std::max(worst, (tau - frame.tau).lpNorm<Eigen::Infinity>());
        largest = std::max(largest, frame.tau.lpNorm<Eigen::Infinity>());
    }
    EXPECT_GT(largest, 100.0);  // the body's weight, carried through the root
    EXPECT_LE(worst, 1e-9 * largest);
}

// What a fit of the capture gives back: the simulated poses, and, through the fit's .mot file and inverse
// dynamics as `sinew inverse-dynamics` runs it, the true generalized forces within the issue's 1 % RMS per
// joint, away from the ends. Prints the figures. The captures are fitted at `sinew ik`'s default accuracy
// (1e-5; both files carry 17 digits, so the fit's residual is that of the solve) and processed as OpenSim
// processes coordinates, without a low-pass filter (sinew's default, and OpenSim's: on a noiseless capture
// whose torques are small differences of large inertial and gravity terms, a filter would measure its own
// bias on the accelerations, not the path). The error left is the quintic splines' second derivatives at
// 240 Hz, largest where a wire goes slack or taut (a kink in its force).
void expectTheTrueForces(const Model& model, const std::vector<TrueFrame>& truth, const Model& fitted,
                         const InverseKinematicsResult& fit, const std::string& stem) {
    ASSERT_EQ(fit.motion.q.size(), truth.size());
    double worstFit = 0, worstQ = 0;
    for (std::size_t f = 0; f < truth.size(); ++f) {
        const InverseKinematicsReport& report = fit.motion.reports[f];
        EXPECT_TRUE(report.converged) << stem << ", frame " << f;
        worstFit = std::max(worstFit, report.maxMarkerError);
        // The same pose (a quaternion and its negative are one rotation).
        Eigen::VectorXd q = fit.motion.q[f];
        for (const Joint& joint : model.getJoints())
            if (joint.type == JointType::Ball || joint.type == JointType::Free)
                if (q.segment<4>(joint.qStart).dot(truth[f].q.segment<4>(joint.qStart)) < 0) q.segment<4>(joint.qStart) *= -1;
        worstQ = std::max(worstQ, (q - truth[f].q).lpNorm<Eigen::Infinity>());
    }
    std::printf("%s fit: largest marker (or joint-centre) error %.3g m, largest coordinate error %.3g\n", stem.c_str(),
                worstFit, worstQ);
    EXPECT_LE(worstQ, 1e-6) << stem;

    const std::string motionPath = testPath(stem + "_ik.mot");
    writeInverseKinematicsFiles(fitted, fit, motionPath, testPath(stem + "_ik_marker_errors.sto"));
    const StorageTable forces = runInverseDynamics(model, readStorageFile(motionPath), nullptr, {});
    const int margin = static_cast<int>(0.05 * kRate);
    for (double relative : compareGeneralizedForces(model, truth, forces, margin, ("inverse dynamics of the " + stem + " fit").c_str()))
        EXPECT_LE(relative, 0.01) << stem;
}

// A BVH capture: the mapped links' frames, through `sinew ik`'s BVH path (targets, unscaled model).
TEST(SyntheticCapture, InverseDynamicsOfABvhFitRecoversTheTrueForces) {
    const Model model = makeTwoLeggedModel();
    SimulationSummary summary;
    const std::vector<TrueFrame> truth = simulateStandingOnOneFoot(model, summary);
    std::printf("simulation: %d frames, %d steps, %d wire switches, weld drift %.3g m\n", summary.frames, summary.steps,
                summary.wireSwitches, summary.maxConstraintViolation);
    const std::string mapPath = testPath("one_leg_stance_map.yaml");
    std::ofstream(mapPath) << kMapText;
    const BvhMap map = readBvhMap(mapPath);
    std::vector<Eigen::VectorXd> poses;
    for (const TrueFrame& frame : truth) poses.push_back(frame.q);
    const std::string bvhPath = testPath("one_leg_stance.bvh");
    writeBvhFile(bvhPath, makeModelBvh(model, map, poses, 1 / kRate));
    const BvhMotion capture = readBvhFile(bvhPath);
    ASSERT_EQ(capture.values.rows(), static_cast<Eigen::Index>(truth.size()));
    const BvhInverseKinematics fit = runBvhInverseKinematics(model, capture, map, false, InverseKinematicsRequest{});
    expectTheTrueForces(model, truth, fit.model, fit.result, "bvh");
}

// A marker capture: three markers on every link, through a TRC file and the OpenSim-style marker fit.
TEST(SyntheticCapture, InverseDynamicsOfAMarkerFitRecoversTheTrueForces) {
    const Model model = makeTwoLeggedModel();
    SimulationSummary summary;
    const std::vector<TrueFrame> truth = simulateStandingOnOneFoot(model, summary);
    std::vector<Marker> markers;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const std::string& link = model.getLink(i).name;
        markers.push_back({link + "_front", i, {0.08, 0, -0.1}, ""});
        markers.push_back({link + "_side", i, {0, 0.07, -0.2}, ""});
        markers.push_back({link + "_low", i, {-0.03, -0.02, -0.35}, ""});
    }
    MarkerTable capture;
    capture.dataRate = kRate;
    for (const Marker& marker : markers) capture.markers.push_back(marker.name);
    Data data(model);
    for (std::size_t f = 0; f < truth.size(); ++f) {
        calcPositionKinematics(model, data, truth[f].q);
        Eigen::Matrix3Xd positions(3, static_cast<Eigen::Index>(markers.size()));
        for (std::size_t k = 0; k < markers.size(); ++k)
            positions.col(static_cast<Eigen::Index>(k)) = calcMarkerLocation_G(data, markers[k]);
        capture.frameNumbers.push_back(static_cast<int>(f) + 1);
        capture.times.push_back(truth[f].time);
        capture.positions.push_back(positions);
    }
    const std::string trcPath = testPath("one_leg_stance.trc");
    writeTrcFile(trcPath, capture);
    const InverseKinematicsResult fit = runInverseKinematics(model, markers, readTrcFile(trcPath), InverseKinematicsRequest{}, {});
    expectTheTrueForces(model, truth, model, fit, "trc");
}

}  // namespace
}  // namespace sinew

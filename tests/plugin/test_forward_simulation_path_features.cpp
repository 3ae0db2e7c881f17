// Simbody's forward simulation with wires over a sphere, a cylinder and an ellipsoid, one of them to a
// moving point: springs store energy V(L(q)), so an undamped swing conserves energy only if every part of
// -dV/dq reaches Simbody: the forces at the path points and tangent points, the moving point's push on its
// coordinate (without it the drift below was 0.35 J), and the ellipsoid-wrapped wire's whole -f dL/du. The
// same swing by sinew's own engine must follow the same trajectory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/plugin/simbody_simulation.hpp"

namespace sinew {
namespace {

// The ellipsoid, its wire and the shoulder's start are those of tests/core/test_forward_simulation_path_features.cpp
// (a swing where OpenSim's ellipsoid path stays smooth); the sphere has no quadrant, whose forced wraps
// would make the length jump.
const char* const kSpringWrapArm = R"(sinew_model: 1
name: spring_wrap_arm
gravity: [0, 0, 0]
links:
  - {name: base, mass: 0, inertia: [0, 0, 0, 0, 0, 0]}
  - {name: upper, mass: 2, com: [0, -0.15, 0], inertia: [0.02, 0.002, 0.02, 0, 0, 0]}
  - {name: lower, mass: 1, com: [0, -0.15, 0], inertia: [0.01, 0.001, 0.01, 0, 0, 0]}
joints:
  - {name: mount, type: weld, parent: ground, child: base}
  - {name: shoulder, type: ball, parent: base, child: upper, initial_rotation: [0.40, -0.22, 0.44]}
  - {name: elbow, type: pin, parent: upper, child: lower, parent_point: [0, -0.3, 0], axis: [0, 0, 1], initial_angle: 0.8}
wrap_objects:
  - {name: elbow_cylinder, type: cylinder, link: upper, translation: [0, -0.3, 0], radius: 0.02, length: 0.1}
  - {name: head, type: sphere, link: upper, radius: 0.03}
  - {name: head_ellipsoid, type: ellipsoid, link: upper, rotation: [0.3, -0.2, 0.5], translation: [0, -0.01, 0], radii: [0.035, 0.02, 0.025], quadrant: -y}
wires:
  - name: over_ellipsoid
    kind: muscle
    points:
      - {link: base, at: [0.01, 0.06, 0.05]}
      - {link: upper, at: [-0.01, -0.08, -0.04]}
    wraps: [{object: head_ellipsoid, method: hybrid}]
    force_law: {type: spring_damper, stiffness: 100, rest_length: 0.05}
  - name: over_sphere
    kind: muscle
    points:
      - {link: base, at: [-0.06, 0.05, 0.01]}
      - {link: upper, at: [0.02, -0.09, -0.005]}
    wraps: [{object: head}]
    force_law: {type: spring_damper, stiffness: 200, rest_length: 0.1}
  - name: over_cylinder_to_moving_point
    kind: muscle
    points:
      - {link: upper, at: [-0.03, -0.1, 0]}
      - link: lower
        at: [0, -0.04, 0]
        moving:
          x: {coordinate: elbow, function: {type: simm_spline, x: [-1, 0, 1, 2, 3], y: [-0.02, -0.025, -0.035, -0.03, -0.02]}}
    wraps: [{object: elbow_cylinder}]
    force_law: {type: spring_damper, stiffness: 400, rest_length: 0.1}
)";

TEST(ForwardSimulationPathFeatures, SimbodyConservesEnergyOverWrapsAndMovingPoints) {
    const Model model = readModelText(kSpringWrapArm, "spring_wrap_arm.yaml");
    ForwardSimulationOptions options;
    options.duration = 1;
    options.reportInterval = 0.01;
    options.accuracy = 1e-10;
    options.initialSpeeds = Eigen::Vector4d(0.23, -0.13, 0.17, 1.0);  // shoulder (rad/s, in its F frame), elbow
    Data data(model);
    std::vector<int> wrappedFrames(static_cast<std::size_t>(model.getNumWires()), 0);
    std::vector<Eigen::VectorXd> simbodyQ;
    const SimulationSummary simbody = simulateForward(model, options, [&](const SimulationFrame& frame) {
        simbodyQ.push_back(frame.q);
        calcPositionKinematics(model, data, frame.q);
        calcWirePaths(model, data);
        for (int w = 0; w < model.getNumWires(); ++w)
            if (data.wirePathSize[static_cast<std::size_t>(w)] == 4) ++wrappedFrames[static_cast<std::size_t>(w)];
    });
    std::size_t frame = 0;
    double dq = 0;
    const SimulationSummary sinew = simulateForwardSinew(model, options, [&](const SimulationFrame& f) {
        dq = std::max(dq, (f.q - simbodyQ.at(frame++)).lpNorm<Eigen::Infinity>());
    });
    std::printf("spring wrap arm, 1 s: energy drift Simbody %.2e J, sinew %.2e J of peak kinetic energy %.3f J; "
                "max |q_sinew - q_simbody| %.1e; frames wrapped (of %d): ellipsoid %d, sphere %d, cylinder %d\n",
                simbody.maxEnergyDrift, sinew.maxEnergyDrift, simbody.peakKineticEnergy, dq, simbody.frames,
                wrappedFrames[0], wrappedFrames[1], wrappedFrames[2]);
    EXPECT_GT(simbody.peakKineticEnergy, 1.0);
    EXPECT_LE(simbody.maxEnergyDrift, 1e-6 * simbody.peakKineticEnergy);
    EXPECT_LE(sinew.maxEnergyDrift, 1e-6 * sinew.peakKineticEnergy);
    EXPECT_EQ(frame, simbodyQ.size());
    EXPECT_LE(dq, 1e-7);
    // Each wrap engages and lets go during the swing, so both sides of each switch are in the comparison.
    for (int w = 0; w < model.getNumWires(); ++w) {
        EXPECT_GE(wrappedFrames[static_cast<std::size_t>(w)], 5) << model.getWire(w).name;
        EXPECT_LT(wrappedFrames[static_cast<std::size_t>(w)], simbody.frames) << model.getWire(w).name;
    }
}

}  // namespace
}  // namespace sinew

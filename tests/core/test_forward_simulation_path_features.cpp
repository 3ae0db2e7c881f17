// sinew's engine with OpenSim path features: a spring through a moving point and over a cylinder or an
// ellipsoid stores energy V(L(q)), so an undamped swing conserves energy only if the moving point's push on
// its coordinate and the ellipsoid-wrapped wire's generalized forces (addWireCoordinateForces) and the
// cylinder's contact forces all reach the dynamics, and only if the ellipsoid's forces are -dV/dq: the
// envelope forces of its plane-section path are not (docs/wire-paths.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

#include "sinew/core/data.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"

namespace sinew {
namespace {

const char* const kArm = R"(sinew_model: 1
name: moving_point_arm
links:
  - {name: base, mass: 0, inertia: [0, 0, 0, 0, 0, 0]}
  - {name: upper, mass: 2, com: [0, -0.15, 0], inertia: [0.02, 0.002, 0.02, 0, 0, 0]}
  - {name: lower, mass: 1, com: [0, -0.15, 0], inertia: [0.01, 0.001, 0.01, 0, 0, 0]}
joints:
  - {name: mount, type: weld, parent: ground, child: base}
  - {name: shoulder, type: pin, parent: base, child: upper, axis: [0, 0, 1], initial_angle: 0.4}
  - {name: elbow, type: pin, parent: upper, child: lower, parent_point: [0, -0.3, 0], axis: [0, 0, 1], initial_angle: 0.8}
wrap_objects:
  - {name: elbow_cylinder, type: cylinder, link: upper, translation: [0, -0.3, 0], radius: 0.02, length: 0.1}
wires:
  - name: moving_insertion
    kind: muscle
    points:
      - {link: base, at: [0.05, 0.02, 0]}
      - link: lower
        at: [0, -0.04, 0]
        moving:
          x: {coordinate: elbow, function: {type: simm_spline, x: [-1, 0, 1, 2, 3], y: [0.01, 0.02, 0.035, 0.03, 0.02]}}
    force_law: {type: spring_damper, stiffness: 400, rest_length: 0.1}
  - name: over_cylinder
    kind: muscle
    points:
      - {link: upper, at: [-0.03, -0.1, 0]}
      - {link: lower, at: [-0.03, -0.08, 0]}
    wraps: [{object: elbow_cylinder}]
    force_law: {type: spring_damper, stiffness: 800, rest_length: 0.1}
)";

// One undamped second at accuracy 1e-10 from `initialSpeeds` (empty: rest), printed; `onFrame` sees each
// report. Energy must hold to 1e-6 of the peak kinetic energy.
SimulationSummary expectEnergyConserved(const Model& model, const Eigen::VectorXd& initialSpeeds, double minKineticEnergy,
                                        const std::function<void(const SimulationFrame&)>& onFrame) {
    ForwardSimulationOptions options;
    options.duration = 1;
    options.reportInterval = 0.01;
    options.accuracy = 1e-10;
    options.initialSpeeds = initialSpeeds;
    const SimulationSummary summary = simulateForwardSinew(model, options, onFrame);
    std::printf("%s, 1 s: energy drift %.2e J of peak kinetic energy %.3f J\n", model.getName().c_str(),
                summary.maxEnergyDrift, summary.peakKineticEnergy);
    EXPECT_GT(summary.peakKineticEnergy, minKineticEnergy);
    EXPECT_LE(summary.maxEnergyDrift, 1e-6 * summary.peakKineticEnergy);
    return summary;
}

TEST(ForwardSimulationSinew, ConservesEnergyThroughMovingPointsAndWraps) {
    expectEnergyConserved(readModelText(kArm, "moving_point_arm.yaml"), Eigen::VectorXd(), 0.1, [](const SimulationFrame&) {});
}

// The ellipsoid of tests/support/wrap_test_model.hpp at a ball shoulder, with a spring over it, without
// gravity. A swing chosen where OpenSim's ellipsoid path stays smooth: elsewhere its length can change by
// 0.6 m/rad as the heuristics swing the section plane, which stalls an integrator at 1e-10.
const char* const kEllipsoidArm = R"(sinew_model: 1
name: ellipsoid_arm
gravity: [0, 0, 0]
links:
  - {name: base, mass: 0, inertia: [0, 0, 0, 0, 0, 0]}
  - {name: upper, mass: 2, com: [0, -0.15, 0], inertia: [0.02, 0.002, 0.02, 0, 0, 0]}
joints:
  - {name: mount, type: weld, parent: ground, child: base}
  - {name: shoulder, type: ball, parent: base, child: upper, initial_rotation: [0.40, -0.22, 0.44]}
wrap_objects:
  - {name: head_ellipsoid, type: ellipsoid, link: upper, rotation: [0.3, -0.2, 0.5], translation: [0, -0.01, 0], radii: [0.035, 0.02, 0.025], quadrant: -y}
wires:
  - name: over_ellipsoid
    kind: muscle
    points:
      - {link: base, at: [0.01, 0.06, 0.05]}
      - {link: upper, at: [-0.01, -0.08, -0.04]}
    wraps: [{object: head_ellipsoid, method: hybrid}]
    force_law: {type: spring_damper, stiffness: 100, rest_length: 0.05}
)";

TEST(ForwardSimulationSinew, ConservesEnergyOverAnEllipsoid) {
    const Model model = readModelText(kEllipsoidArm, "ellipsoid_arm.yaml");
    Data data(model);
    int frames = 0, wrapped = 0;
    // With the envelope forces instead (sinew before it differentiated the whole path) the drift was 3.3e-5 J.
    expectEnergyConserved(model, Eigen::Vector3d(0.23, -0.13, 0.17), 0.01, [&](const SimulationFrame& frame) {
        calcPositionKinematics(model, data, frame.q);
        calcWirePaths(model, data);
        ++frames;
        if (data.wirePathSize[0] == 4) ++wrapped;
    });
    std::printf("wrapped in %d of %d frames\n", wrapped, frames);
    EXPECT_GE(wrapped, 5);
    EXPECT_LT(wrapped, frames);
}

}  // namespace
}  // namespace sinew

#pragma once
// An arm with OpenSim's path features: wires over a cylinder at the elbow, a sphere (kept to +x) and an
// ellipsoid at the shoulder, two wraps on one wire, a conditional point and a moving point, each wire on
// its own so a failure names the feature.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <random>
#include <string>

#include "sinew/io/model_file.hpp"

namespace sinew::test {

inline const char* const kWrapArmYaml = R"(sinew_model: 1
name: wrap_arm
links:
  - {name: base, mass: 0, inertia: [0, 0, 0, 0, 0, 0]}
  - {name: upper, mass: 2, com: [0, -0.15, 0], inertia: [0.02, 0.002, 0.02, 0, 0, 0]}
  - {name: lower, mass: 1, com: [0, -0.15, 0], inertia: [0.01, 0.001, 0.01, 0, 0, 0]}
joints:
  - {name: mount, type: weld, parent: ground, child: base}
  - {name: shoulder, type: ball, parent: base, child: upper}
  - {name: elbow, type: pin, parent: upper, child: lower, parent_point: [0, -0.3, 0], axis: [0, 0, 1]}
wrap_objects:
  - {name: elbow_cylinder, type: cylinder, link: upper, rotation: [0.1, -0.05, 0], translation: [0, -0.3, 0], radius: 0.02, length: 0.1}
  - {name: head, type: sphere, link: upper, radius: 0.03, quadrant: +x}
  - {name: head_ellipsoid, type: ellipsoid, link: upper, rotation: [0.3, -0.2, 0.5], translation: [0, -0.01, 0], radii: [0.035, 0.02, 0.025], quadrant: -y}
wires:
  - name: over_cylinder
    kind: muscle
    points:
      - {link: upper, at: [-0.03, -0.1, 0.01]}
      - {link: lower, at: [-0.03, -0.05, -0.01]}
    wraps: [{object: elbow_cylinder}]
    force_law: {type: prescribed_tension, tension: 10}
  - name: over_sphere
    kind: muscle
    points:
      - {link: base, at: [-0.06, 0.05, 0.01]}
      - {link: upper, at: [0.02, -0.09, -0.005]}
    wraps: [{object: head}]
    force_law: {type: prescribed_tension, tension: 20}
  - name: over_ellipsoid
    kind: muscle
    points:
      - {link: base, at: [0.01, 0.06, 0.05]}
      - {link: upper, at: [-0.01, -0.08, -0.04]}
    wraps: [{object: head_ellipsoid, method: hybrid}]
    force_law: {type: prescribed_tension, tension: 30}
  - name: two_wraps
    kind: muscle
    points:
      - {link: base, at: [-0.05, 0.04, 0]}
      - {link: upper, at: [-0.035, -0.15, 0.005]}
      - {link: lower, at: [-0.025, -0.06, 0]}
    wraps: [{object: head, range: [0, 1]}, {object: elbow_cylinder}]
    force_law: {type: prescribed_tension, tension: 40}
  - name: conditional_and_moving
    kind: muscle
    points:
      - {link: base, at: [0.02, 0.02, 0]}
      - {link: upper, at: [0.03, -0.2, 0.01], active_when: {coordinate: elbow, range: [0.5, 2.0]}}
      - link: lower
        at: [0, -0.04, 0.005]
        moving:
          x: {coordinate: elbow, function: {type: simm_spline, x: [-1, 0, 1, 2, 3], y: [0.01, 0.02, 0.035, 0.03, 0.02]}}
          y: {coordinate: elbow, function: {type: linear, coefficients: [0.01, -0.05], scale: 0.9}}
    force_law: {type: prescribed_tension, tension: 50}
)";

inline Model loadWrapArm() { return readModelText(kWrapArmYaml, "wrap_arm.yaml"); }

// A pose of the wrap arm: the shoulder turned up to 0.8 rad about a random axis, the elbow bent 0.05-2.6 rad.
inline Eigen::VectorXd randomWrapArmPose(const Model& model, std::mt19937& rng) {
    std::uniform_real_distribution<double> uniform(-1, 1);
    Eigen::VectorXd q = model.getDefaultQ();
    const Eigen::Vector3d axis = Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng)).normalized();
    const Eigen::Quaterniond rotation(Eigen::AngleAxisd(0.8 * std::abs(uniform(rng)), axis));
    const int shoulder = model.getJoint(model.findLinkIndex("upper")).qStart;
    q.segment<4>(shoulder) << rotation.w(), rotation.x(), rotation.y(), rotation.z();
    q[model.getJoint(model.findLinkIndex("lower")).qStart] = 1.325 + 1.275 * uniform(rng);
    return q;
}

}  // namespace sinew::test

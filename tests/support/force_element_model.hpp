#pragma once
// A block on a free joint with a two-link leg, carrying one force element of each kind: a knee limit, a
// spring from block to foot, a bushing from block to thigh and Hunt-Crossley contact of a heel sphere with
// the floor (a half-space below y = 0), each surface with its own material.
#include <Eigen/Core>
#include <algorithm>
#include <string>

#include "sinew/core/data.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/io/model_file.hpp"

namespace sinew::test {

inline const std::string kForceElementModelText = R"(sinew_model: 1
name: elements
links:
  - {name: block, mass: 20, com: [0, 0, 0], inertia: [0.2, 0.3, 0.25, 0.01, 0, 0.02]}
  - {name: thigh, mass: 5, com: [0, -0.25, 0], inertia: [0.1, 0.02, 0.1, 0, 0, 0]}
  - {name: foot, mass: 5, com: [0, -0.25, 0.01], inertia: [0.1, 0.02, 0.1, 0, 0, 0.001]}
joints:
  - {name: ground_block, type: free, parent: ground, child: block, initial_position: [0, 1.1, 0]}
  - {name: pin1, type: pin, parent: block, child: thigh, axis: [0, 0, 1]}
  - {name: pin2, type: pin, parent: thigh, child: foot, parent_point: [0, -0.5, 0], axis: [0, 0, 1]}
contact_geometry:
  - {name: floor, shape: half_space, link: ground, rotation: [0, 0, -1.5707963267948966]}
  - {name: heel, shape: sphere, link: foot, translation: [0.02, -0.5, 0], radius: 0.05}
force_elements:
  - {type: coordinate_limit, name: knee_limit, coordinate: pin2, upper_stiffness: 20, upper_limit: 0, lower_stiffness: 20, lower_limit: -2.4, damping: 1, transition: 0.09}
  - {type: point_to_point_spring, name: spring, link_a: block, point_a: [0.1, 0, 0], link_b: foot, point_b: [0, -0.2, 0], stiffness: 2000, rest_length: 0.8}
  - {type: bushing, name: hip, link_a: block, translation_a: [0, 0, 0.05], rotation_a: [0.1, 0.2, 0.3], link_b: thigh, translation_b: [0, 0.02, 0], rotation_b: [0, 0.1, 0], rotational_stiffness: [10, 12, 14], translational_stiffness: [100, 200, 300], rotational_damping: [0.1, 0.2, 0.3], translational_damping: [1, 2, 3]}
  - {type: hunt_crossley, name: foot_contact, transition_velocity: 0.1, surfaces: [{geometry: floor, stiffness: 1e7, dissipation: 0.5, static_friction: 0.9, dynamic_friction: 0.8, viscous_friction: 0.6}, {geometry: heel, stiffness: 2e7, dissipation: 0.3, static_friction: 0.7, dynamic_friction: 0.5, viscous_friction: 0.4}]}
)";

inline Model makeForceElementModel() { return readModelText(kForceElementModelText, "force_elements.yaml"); }

// The default pose with coordinate q[heightQ] (a vertical translation) moved until contact sphere
// `sphere` is `depth` (m) into the floor at y = 0.
inline Eigen::VectorXd placeSphereInFloor(const Model& model, const std::string& sphere, int heightQ, double depth) {
    const auto& geometry = model.getForceElements().contactGeometry;
    const auto it = std::find_if(geometry.begin(), geometry.end(), [&](const ContactGeometry& g) { return g.name == sphere; });
    Eigen::VectorXd q = model.getDefaultQ();
    Data data(model);
    calcPositionKinematics(model, data, q);
    const std::size_t b = static_cast<std::size_t>(it->frame.link);
    const double centreY = (data.p_GB[b] + data.R_GB[b] * it->frame.p_BF).y();
    q[heightQ] -= centreY - it->radius + depth;
    return q;
}

inline Eigen::VectorXd placeHeelInFloor(const Model& model, double depth) {
    return placeSphereInFloor(model, "heel", model.getJoint(model.findLinkIndex("block")).qStart + 5, depth);
}

}  // namespace sinew::test

#pragma once
// A knee whose forward slide follows its angle, knee_tx = 2 (0.01 knee^2 - 0.02 knee): a coupler on a custom
// joint below a pinned hip, for the coupler tests of both engines.
namespace sinew::test {

inline const char* const kCoupledKnee = R"(sinew_model: 1
name: coupled_knee
links:
  - {name: thigh, mass: 8, com: [0, -0.17, 0], inertia: [0.11, 0.03, 0.11, 0, 0, 0]}
  - {name: shank, mass: 3.5, com: [0.01, -0.18, 0], inertia: [0.05, 0.005, 0.05, 0, 0, 0]}
joints:
  - {name: hip, type: pin, parent: ground, child: thigh, parent_point: [0, 1, 0], axis: [0, 0, 1]}
  - name: knee
    type: custom
    parent: thigh
    child: shank
    parent_point: [0, -0.4, 0]
    coordinates: [{name: knee_angle}, {name: knee_tx}]
    transform:
      rotation1: {axis: [0, 0, 1], coordinate: knee_angle}
      rotation2: {axis: [1, 0, 0]}
      rotation3: {axis: [0, 1, 0]}
      translation1: {axis: [1, 0, 0], coordinate: knee_tx}
couplers:
  - {name: knee_tx_coupler, dependent: knee_tx, independent: knee_angle, scale_factor: 2,
     function: {type: polynomial, coefficients: [0.01, -0.02, 0]}}
)";

}  // namespace sinew::test

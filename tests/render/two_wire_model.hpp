#pragma once
// A hand-made model for checking colours: a post welded to ground, a bar pinned below it, and two wires
// from the post to the bar, 0.5 m long at the default pose, offset to either side so that no view draws one
// over the other or over a bone: "slack" (rest length 1 m: no tension) and "loaded" (rest length 0.25 m,
// stiffness 1000 N/m: 250 N).
#include "sinew/io/model_file.hpp"

namespace sinew::test {

inline Model makeTwoWireModel() {
    return readModelText(R"(sinew_model: 1
name: two_wires
gravity: [0, -9.81, 0]
links:
  - {name: post, mass: 2.0, com: [0, -0.25, 0], inertia: [0.04, 0.002, 0.04, 0, 0, 0]}
  - {name: bar, mass: 1.0, com: [0, -0.25, 0], inertia: [0.02, 0.001, 0.02, 0, 0, 0]}
joints:
  - {name: fix, type: weld, parent: ground, child: post, parent_point: [0, 1, 0], child_point: [0, 0, 0]}
  - {name: hinge, type: pin, parent: post, child: bar, parent_point: [0, -0.5, 0], child_point: [0, 0, 0], axis: [0, 0, 1]}
wires:
  - name: slack
    kind: muscle
    points:
      - {link: post, at: [0.2, 0, 0.3]}
      - {link: bar, at: [0.2, 0, 0.3]}
    force_law: {type: spring_damper, stiffness: 1000, damping: 10, rest_length: 1.0}
  - name: loaded
    kind: muscle
    points:
      - {link: post, at: [-0.2, 0, -0.3]}
      - {link: bar, at: [-0.2, 0, -0.3]}
    force_law: {type: spring_damper, stiffness: 1000, damping: 10, rest_length: 0.25}
)",
                         "two_wire_model.hpp");
}

}  // namespace sinew::test

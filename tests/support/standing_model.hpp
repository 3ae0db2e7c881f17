#pragma once
// A body standing on two feet, z up: a trunk on a free joint and two legs on ball hips, each leg ending in a
// foot with a rectangular sole, and wires around both hips. For the contact tests (contact detection, the
// contact columns, the tension problem with contact).
#include <string>

#include "sinew/io/model_file.hpp"

namespace sinew::test {

// The model's text; `contacts` false leaves out its contacts section.
inline std::string standingModelText(bool contacts = true) {
    std::string text = R"(sinew_model: 1
name: stander
gravity: [0, 0, -9.81]
links:
  - {name: trunk, mass: 40, com: [0.02, 0, 0.3], inertia: [2, 2, 0.5, 0, 0, 0]}
  - {name: leg_r, mass: 8, com: [0.01, 0, -0.45], inertia: [0.5, 0.5, 0.05, 0, 0, 0]}
  - {name: leg_l, mass: 8, com: [0.01, 0, -0.45], inertia: [0.5, 0.5, 0.05, 0, 0, 0]}
joints:
  - {name: root, type: free, parent: ground, child: trunk, initial_position: [0, 0, 0.9]}
  - {name: hip_r, type: ball, parent: trunk, child: leg_r, parent_point: [0, -0.1, 0], child_point: [0, 0, 0]}
  - {name: hip_l, type: ball, parent: trunk, child: leg_l, parent_point: [0, 0.1, 0], child_point: [0, 0, 0]}
loops: []
wires:
)";
    // Six wires round each hip: front, back, outside, inside and two diagonals.
    const char* const sides[] = {"r", "l"};
    const double ys[] = {-0.1, 0.1};
    const double at[6][2][3] = {{{0.1, 0, 0.1}, {0.08, 0, -0.3}},   {{-0.1, 0, 0.1}, {-0.08, 0, -0.3}},
                                {{0, -0.1, 0.1}, {0, -0.08, -0.3}}, {{0, 0.1, 0.1}, {0, 0.08, -0.3}},
                                {{0.1, 0.1, 0.1}, {-0.06, -0.06, -0.3}}, {{-0.1, -0.1, 0.1}, {0.06, 0.06, -0.3}}};
    for (int s = 0; s < 2; ++s)
        for (int w = 0; w < 6; ++w) {
            const auto number = [](double v) { return std::to_string(v); };
            text += "  - name: hip_" + std::string(sides[s]) + "_" + std::to_string(w) + "\n    kind: muscle\n    points:\n";
            text += "      - {link: trunk, at: [" + number(at[w][0][0]) + ", " + number(ys[s] + at[w][0][1]) + ", " +
                    number(at[w][0][2]) + "]}\n";
            text += "      - {link: leg_" + std::string(sides[s]) + ", at: [" + number(at[w][1][0]) + ", " +
                    number(at[w][1][1]) + ", " + number(at[w][1][2]) + "]}\n";
            text += "    force_law: {type: spring_damper, stiffness: 100, damping: 1, rest_length: 0.3}\n";
        }
    if (contacts)
        text += R"(contacts:
  - {name: foot_r, link: leg_r, friction: 0.8, sole: [[-0.05, -0.04, -0.9], [0.15, -0.04, -0.9], [0.15, 0.04, -0.9], [-0.05, 0.04, -0.9]]}
  - {name: foot_l, link: leg_l, friction: 0.8, sole: [[-0.05, -0.04, -0.9], [0.15, -0.04, -0.9], [0.15, 0.04, -0.9], [-0.05, 0.04, -0.9]]}
)";
    return text;
}

inline Model makeStandingModel() { return readModelText(standingModelText(), "stander.yaml"); }

}  // namespace sinew::test

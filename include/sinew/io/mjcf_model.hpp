#pragma once
// MuJoCo's MJCF models (.xml) as sinew models: bodies become links with the mass properties MuJoCo's
// compiler gives them (from <inertial>, or from their geoms), each body's joints one sinew joint whose
// coordinates equal MuJoCo's qpos, spatial tendons wires over their sites with MuJoCo's wrapping, muscle
// actuators a Thelen muscle law fitted to MuJoCo's muscle, joint equalities couplers and connects loops.
// The semantics are MuJoCo 2.2.2's; includes may also follow newer MuJoCo's path rule. What sinew does not
// model is listed in MjcfConversion::notImported by name and file:line, never dropped in silence. The
// mapping, what is left out and the muscle approximation: docs/mjcf-import.md.
#include <string>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

struct MjcfConversion {
    Model model;
    // One line per MJCF element left out of `model`, or imported with a change: "<element> '<name>'
    // (<file:line>): <why>".
    std::vector<std::string> notImported;
};

// Throws ModelError "file:line: <element> 'name': what was expected" for malformed XML or numbers, NaN or
// infinite values, negative masses, a missing include, an unknown body, joint, site, geom, tendon or class,
// and a joint layout or tendon path sinew cannot represent.
MjcfConversion readMjcfModel(const std::string& path);

}  // namespace sinew

#pragma once
// Turns an OpenSim model read by readOsimModel into a sinew Model: bodies become links, every joint a
// custom joint reproducing OpenSim's kinematics (weld joints stay welds), muscles become wires with their
// fixed, conditional and moving path points and wrap lists, and a rigid-tendon Thelen 2003 force law;
// enforced CoordinateCouplerConstraints become couplers.
// What sinew does not model is listed in OsimConversion::notImported by name and file:line, never dropped
// in silence. Conventions and the per-joint axis tables: docs/opensim-import.md.
#include <functional>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/io/osim_model.hpp"

namespace sinew {

struct OsimConversion {
    Model model;
    // One line per OpenSim element left out of `model`: "<type> '<name>' (<file:line>): <why>".
    std::vector<std::string> notImported;
    // One line per quirk OpenSim accepts and sinew imports as OpenSim does (an invalid inertia reset, path
    // points on ground): "<type> '<name>' (<file:line>): <what was done>".
    std::vector<std::string> warnings;
};

// Throws ModelError at the OpenSim element's file:line for what cannot be represented at all (a function
// type sinew lacks, a moving point on a rotated frame, a massless body on a moving joint).
OsimConversion convertOsimModel(const OsimModel& osim);

// Passes each of the conversion's lines to `notes` (may be empty): "warning: ..." lines first, then
// "not imported: ..." ones.
void reportOsimConversion(const OsimConversion& conversion, const std::function<void(const std::string&)>& notes);

// The sinew function for an OpenSim one (MultiplierFunctions folded into the scale).
Function convertOsimFunction(const OsimFunction& function);

}  // namespace sinew

#pragma once
// OpenSim ExternalLoads files (.xml): measured loads such as ground reactions, each an ExternalForce naming
// the body it acts on and the columns of a storage file that hold its force, point and torque over time.
#include <array>
#include <string>
#include <vector>

#include "sinew/io/osim_model.hpp"
#include "sinew/io/storage_file.hpp"

namespace sinew {

struct ExternalForce {
    std::string name;
    bool appliesForce = true;  // <appliesForce>, or not <isDisabled>
    std::string appliedToBody;
    std::string forceExpressedInBody = "ground";
    std::string pointExpressedInBody = "ground";
    // Column-label prefixes in the data file; empty: no force / point (then the body origin) / torque.
    std::string forceIdentifier, pointIdentifier, torqueIdentifier;
    std::string dataSourceName;  // as written; the loads' datafile is the source either way
    // Indices into ExternalLoads::data.columns of the x, y, z components; -1 without an identifier.
    std::array<int, 3> forceColumns{-1, -1, -1};   // N, in forceExpressedInBody
    std::array<int, 3> pointColumns{-1, -1, -1};   // m, in pointExpressedInBody
    std::array<int, 3> torqueColumns{-1, -1, -1};  // N m, in forceExpressedInBody
    std::string where;  // "file:line" of its XML element
};

struct ExternalLoads {
    std::string name;
    std::string file;      // the XML read
    std::string dataFile;  // <datafile>, made absolute against the XML's folder
    StorageTable data;     // its contents
    // Older setups name a motion to express the loads' points in bodies and a cut-off frequency for it;
    // absolute path, empty when absent; Hz, negative when absent (no filtering).
    std::string modelKinematicsFile;
    double lowpassCutoffFrequencyForLoadKinematics = -1;
    std::vector<ExternalForce> forces;
};

// Reads the XML and its data file. Each identifier is resolved as OpenSim does: the columns whose labels
// start with it, in file order, must be exactly three (x, y, z); anything else throws an Error naming the
// XML file and line, the identifier and the columns found.
ExternalLoads readExternalLoads(const std::string& path);

// Throws ModelError at the force's line when a body it names (applied to, or expressed in) is not in the
// model. (OpenSim falls back to ground for the expressed-in bodies with a warning; sinew refuses.)
void checkExternalLoadsBodies(const ExternalLoads& loads, const OsimModel& model);

}  // namespace sinew

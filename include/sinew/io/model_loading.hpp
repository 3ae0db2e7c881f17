#pragma once
// One entry point for every model format sinew reads, chosen by the file's content (not its name): an MJCF
// file (root element <mujoco>) and an OpenSim model (<OpenSimDocument>) are converted, with what was left
// out reported through `notes`; anything else is read as a sinew YAML model.
#include <functional>
#include <string>

#include <vector>

#include "sinew/core/marker.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

enum class ModelFormat { SinewYaml, OpenSim, Mjcf };
const char* toString(ModelFormat format);

// The format of the file at `path`, from its first element: XML whose root is neither <mujoco> nor
// <OpenSimDocument> is an error naming the root; a file that is not XML is taken for YAML.
ModelFormat detectModelFormat(const std::string& path);

// Reads the model; `notes` (may be empty) receives one "not imported: ..." line per element a converter
// left out, and one "warning: ..." line per OpenSim quirk imported as OpenSim handles it.
Model loadModel(const std::string& path, const std::function<void(const std::string&)>& notes);

// The motion-capture markers the model file defines, on the links of `model` (loaded from the same file):
// an OpenSim model's MarkerSet; none for the other formats.
std::vector<Marker> loadMarkers(const std::string& path, const Model& model);

}  // namespace sinew

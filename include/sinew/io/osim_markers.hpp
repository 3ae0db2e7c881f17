#pragma once
// An OpenSim model's MarkerSet (or a MarkerSet file's) as markers on the links of the model converted from it.
#include <string>
#include <vector>

#include "sinew/core/marker.hpp"
#include "sinew/core/model.hpp"
#include "sinew/io/osim_model.hpp"

namespace sinew {

// Each marker on the link of its frame's body (or on ground), its location moved through the frame's offset.
// Throws ModelError at the marker's file:line when its body is no link of `model`.
std::vector<Marker> convertOsimMarkers(const std::vector<OsimMarker>& markers, const Model& model);

}  // namespace sinew

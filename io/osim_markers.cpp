#include "sinew/io/osim_markers.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

std::vector<Marker> convertOsimMarkers(const std::vector<OsimMarker>& markers, const Model& model) {
    std::vector<Marker> converted;
    for (const OsimMarker& m : markers) {
        const int link = model.findLinkIndex(m.frame.body);  // kGround for "ground"
        if (link == Model::kNotFound)
            throw ModelError(m.where, "marker '" + m.name + "': body '" + m.frame.body + "' is not a link of model '" +
                                          model.getName() + "'");
        converted.push_back({m.name, link, m.frame.p_BF + m.frame.R_BF * m.location, m.where});
    }
    return converted;
}

}  // namespace sinew

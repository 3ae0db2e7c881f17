#pragma once
// A motion-capture marker fixed on a link (OpenSim's Marker): what inverse kinematics fits to measured
// positions. Kept beside the model rather than in it, since a model is fitted to many marker sets.
#include <Eigen/Core>
#include <string>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

struct Marker {
    std::string name;
    int link = kGround;                             // link index, or kGround for a marker fixed in ground
    Eigen::Vector3d p_B = Eigen::Vector3d::Zero();  // m, in that link's frame
    std::string where;                              // "file:line" it came from, for messages
};

// The marker's position in ground, m. Needs calcPositionKinematics.
inline Eigen::Vector3d calcMarkerLocation_G(const Data& data, const Marker& marker) {
    if (marker.link == kGround) return marker.p_B;
    const std::size_t b = static_cast<std::size_t>(marker.link);
    return data.p_GB[b] + data.R_GB[b] * marker.p_B;
}

}  // namespace sinew

#pragma once
// MJCF spatial tendons as sinew wires (docs/mjcf-import.md, "Tendons and muscles"): sites become wire
// points, sphere and cylinder geoms wrap objects wrapped the MuJoCo way between the two sites around them,
// a tendon pulled by a muscle actuator a muscle with Thelen's law fitted to MuJoCo's muscle, any other a
// tendon with its spring and damper. Private to sinew_io.
#include <optional>
#include <string>
#include <vector>

#include "mjcf_document.hpp"
#include "sinew/core/model_builder.hpp"

namespace sinew::mjcf {

// One wire: a whole tendon, or one branch of a tendon split at its pulleys.
struct TendonWire {
    WireSpec spec;
    int tendon = 0;  // index into MjcfModel::tendons
    // Values MuJoCo computes at qpos0, which the converter fills once the model is built:
    bool restLengthAtQpos0 = false;     // spring_damper rest_length: the tendon's length at qpos0
    std::optional<double> forceScale;   // muscle max_isometric_force = scale / acc0 (MuJoCo's force < 0)
};

struct TendonConversion {
    std::vector<TendonWire> wires;
    std::vector<WrapObjectSpec> wrapObjects;  // one per geom a tendon wraps, named after the geom
};

// Throws ModelError at the actuator for a muscle sinew cannot fit (an operating range that does not
// increase). Lines for `notImported`: fixed tendons, actuators that give no muscle, muscles fitted with a
// change, tendon limits and friction, pulleys.
TendonConversion convertTendons(const MjcfModel& model, std::vector<std::string>& notImported);

}  // namespace sinew::mjcf

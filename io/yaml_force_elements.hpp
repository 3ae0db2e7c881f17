#pragma once
// The model file's force elements (docs/model-format.md, "Force elements"): `force_elements` (coordinate
// limits, point-to-point springs, bushings, Hunt-Crossley contact) and the `contact_geometry` they touch with.
#include <yaml-cpp/yaml.h>

#include "sinew/core/model.hpp"
#include "sinew/core/model_builder.hpp"
#include "yaml_fields.hpp"

namespace sinew {

// Reads root's force_elements and contact_geometry into `builder`; every problem a ModelError at file:line.
void readForceElements(const YamlFields& fields, const YAML::Node& root, ModelBuilder& builder);
// Writes them back (nothing when the model has none).
void emitForceElements(YAML::Emitter& out, const Model& model);

}  // namespace sinew

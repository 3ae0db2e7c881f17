#pragma once
// Small pieces the model file's writers share.
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <string>

#include "sinew/core/model.hpp"

namespace sinew {

inline void emitVector(YAML::Emitter& out, const Eigen::Vector3d& v) {
    out << YAML::Flow << YAML::BeginSeq << v[0] << v[1] << v[2] << YAML::EndSeq;
}

inline std::string linkName(const Model& model, int link) {
    return link == kGround ? "ground" : model.getLink(link).name;
}

}  // namespace sinew

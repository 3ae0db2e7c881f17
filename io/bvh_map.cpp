#include "sinew/io/bvh_map.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <set>

#include "sinew/core/error.hpp"
#include "yaml_fields.hpp"

namespace sinew {

BvhMap readBvhMap(const std::string& path) {
    const YAML::Node root = loadYamlFile(path);
    const YamlFields fields(path);
    if (!root.IsMap()) throw ModelError(path + ":1", "a BVH map is a mapping with unit, axes and joints");
    fields.requireKeys(root, "BVH map", {"unit", "axes", "orientation_weight", "joints"});
    BvhMap map;
    map.source = path;
    if (const YAML::Node unit = root["unit"]; unit && unit.Scalar() != "auto") {
        map.unit = fields.readNumber(unit, "unit");
        if (!(map.unit > 0)) fields.fail(unit, "unit must be 'auto' or metres per BVH unit (> 0)");
    }
    if (const YAML::Node weight = root["orientation_weight"]) {
        map.orientationWeight = fields.readNumber(weight, "orientation_weight");
        if (!(map.orientationWeight >= 0) || !std::isfinite(map.orientationWeight))
            fields.fail(weight, "orientation_weight must be a finite number >= 0 (m^2 per rad^2)");
    }
    if (const YAML::Node axes = root["axes"]) {
        if (!axes.IsSequence() || axes.size() != 3) fields.fail(axes, "axes must be three rows of three numbers");
        for (std::size_t r = 0; r < 3; ++r) {
            if (!axes[r].IsSequence() || axes[r].size() != 3) fields.fail(axes[r], "an axes row needs three numbers");
            for (std::size_t c = 0; c < 3; ++c) {
                try {
                    map.R_GB(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = axes[r][c].as<double>();
                } catch (const YAML::Exception&) {
                    fields.fail(axes[r][c], "expected a number in axes");
                }
            }
        }
        if (!(map.R_GB * map.R_GB.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-9) || map.R_GB.determinant() < 0)
            fields.fail(axes, "axes must be a rotation (orthonormal rows, determinant +1)");
    }
    const YAML::Node joints = fields.field(root, "joints", "BVH map");
    if (!joints.IsMap() || joints.size() == 0) fields.fail(joints, "joints must map BVH joint names to model links");
    std::set<std::string> seen;
    for (const auto& entry : joints) {
        const std::string bvh = entry.first.Scalar();
        if (!seen.insert(bvh).second) fields.fail(entry.first, "BVH joint '" + bvh + "' is mapped twice");
        std::string link = entry.second.IsScalar() ? entry.second.Scalar() : "";
        Eigen::Vector3d point = Eigen::Vector3d::Zero();
        if (entry.second.IsMap()) {
            fields.requireKeys(entry.second, "BVH joint '" + bvh + "'", {"link", "at"});
            link = fields.readString(fields.field(entry.second, "link", "BVH joint '" + bvh + "'"), "link");
            if (entry.second["at"]) point = fields.readVector3(entry.second["at"], "at");
        }
        if (link.empty()) fields.fail(entry.second, "BVH joint '" + bvh + "' needs a model link");
        map.joints.emplace_back(bvh, link);
        map.points.push_back(point);
        map.where.push_back(fields.where(entry.first));
    }
    return map;
}

}  // namespace sinew

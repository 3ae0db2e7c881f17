#include "yaml_fields.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "sinew/core/error.hpp"

namespace sinew {

void YamlFields::fail(const YAML::Node& node, const std::string& message) const { throw ModelError(where(node), message); }

void YamlFields::requireKeys(const YAML::Node& map, const std::string& what, const std::set<std::string>& allowed) const {
    for (const auto& entry : map) {
        const std::string key = entry.first.Scalar();
        if (allowed.count(key)) continue;
        std::string list;
        for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(entry.first, "unknown field '" + key + "' in " + what + " (expected one of: " + list + ")");
    }
}

std::vector<YAML::Node> YamlFields::sequence(const YAML::Node& root, const std::string& key) const {
    std::vector<YAML::Node> items;
    const YAML::Node node = root[key];
    if (!node || node.IsNull()) return items;
    if (!node.IsSequence()) fail(node, "field '" + key + "' must be a list");
    for (const YAML::Node& item : node) {
        if (!item.IsMap()) fail(item, "each entry of '" + key + "' must be a mapping of fields");
        items.push_back(item);
    }
    return items;
}

YAML::Node YamlFields::field(const YAML::Node& map, const std::string& key, const std::string& owner) const {
    const YAML::Node node = map[key];
    if (!node || node.IsNull()) fail(map, owner + ": missing field '" + key + "'");
    return node;
}

std::string YamlFields::readString(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, "field '" + key + "' must be a single word or string");
    return node.Scalar();
}

std::vector<std::string> YamlFields::readStrings(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence()) fail(node, "field '" + key + "' must be a list of names");
    std::vector<std::string> values;
    for (const YAML::Node& item : node) values.push_back(readString(item, key));
    return values;
}

double YamlFields::readNumber(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, "field '" + key + "' must be a number");
    double value = 0;
    try {
        value = node.as<double>();
    } catch (const YAML::Exception&) {
        fail(node, "field '" + key + "' must be a number, got '" + node.Scalar() + "'");
    }
    if (!std::isfinite(value)) fail(node, "field '" + key + "' must be finite, got '" + node.Scalar() + "'");
    if (std::abs(value) > kMaxFieldMagnitude)
        fail(node, "field '" + key + "' = " + node.Scalar() + " is beyond the magnitude 1e9 a model file's numbers "
                   "are bounded to (docs/model-format.md, \"Bounds\")");
    return value;
}

int YamlFields::readInt(const YAML::Node& node, const std::string& key) const {
    const double value = readNumber(node, key);
    if (value != std::floor(value) || std::abs(value) > 1e9) fail(node, "field '" + key + "' must be a whole number");
    return static_cast<int>(value);
}

std::vector<double> YamlFields::readNumbers(const YAML::Node& node, const std::string& key) const {
    if (node.IsScalar()) return {readNumber(node, key)};
    if (!node.IsSequence()) fail(node, "field '" + key + "' must be a number or a list of numbers");
    std::vector<double> values;
    for (const YAML::Node& item : node) values.push_back(readNumber(item, key));
    return values;
}

Eigen::Vector3d YamlFields::readVector3(const YAML::Node& node, const std::string& key) const {
    const std::vector<double> v = readNumbers(node, key);
    if (v.size() != 3 || !node.IsSequence()) fail(node, "field '" + key + "' must be a list of 3 numbers");
    return Eigen::Vector3d(v[0], v[1], v[2]);
}

YAML::Node parseYamlText(const std::string& text, const std::string& source) {
    try {
        return YAML::Load(text);
    } catch (const YAML::ParserException& e) {
        throw ModelError(source + ":" + std::to_string(e.mark.line + 1), "YAML syntax error: " + e.msg);
    }
}

YAML::Node loadYamlFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw ModelError(path, "cannot open file");
    std::stringstream text;
    text << in.rdbuf();
    return parseYamlText(text.str(), path);
}

}  // namespace sinew

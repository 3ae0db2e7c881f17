#pragma once
// Reading fields of a YAML document, every problem a ModelError at "file:line" naming the field and what was
// expected: the base of sinew's YAML readers (model files, whole-body rules).
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <set>
#include <string>
#include <vector>

namespace sinew {

// Every number read is bounded in magnitude: SI quantities of a body (masses, lengths, stiffnesses, forces,
// times) stay far below it, and beyond it squared terms and step sizes leave what a double carries through
// the dynamics (a stiffness of 1e308 overflows the first force; a point 1e20 m away collapses every step).
constexpr double kMaxFieldMagnitude = 1e9;

class YamlFields {
public:
    explicit YamlFields(std::string source) : source_(std::move(source)) {}

    const std::string& getSource() const { return source_; }
    std::string where(const YAML::Node& node) const { return source_ + ":" + std::to_string(node.Mark().line + 1); }
    [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const;

    void requireKeys(const YAML::Node& map, const std::string& what, const std::set<std::string>& allowed) const;
    // The mappings listed under `key` (none when absent).
    std::vector<YAML::Node> sequence(const YAML::Node& root, const std::string& key) const;
    YAML::Node field(const YAML::Node& map, const std::string& key, const std::string& owner) const;
    std::string readString(const YAML::Node& node, const std::string& key) const;
    std::vector<std::string> readStrings(const YAML::Node& node, const std::string& key) const;
    double readNumber(const YAML::Node& node, const std::string& key) const;
    int readInt(const YAML::Node& node, const std::string& key) const;
    std::vector<double> readNumbers(const YAML::Node& node, const std::string& key) const;
    Eigen::Vector3d readVector3(const YAML::Node& node, const std::string& key) const;

private:
    std::string source_;
};

// Parses YAML text, turning a syntax error into a ModelError at "source:line".
YAML::Node parseYamlText(const std::string& text, const std::string& source);
// The same from a file, an unreadable one a ModelError naming it.
YAML::Node loadYamlFile(const std::string& path);

}  // namespace sinew

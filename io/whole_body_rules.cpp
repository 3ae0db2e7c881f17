#include "sinew/io/whole_body_rules.hpp"

#include <Eigen/Geometry>
#include <fstream>
#include <sstream>

#include "sinew/core/error.hpp"
#include "yaml_fields.hpp"

namespace sinew {
namespace {

constexpr int kRulesFormatVersion = 1;

class RulesReader : public YamlFields {
public:
    using YamlFields::YamlFields;

    WholeBodyRules read(const YAML::Node& root) const {
        if (!root.IsMap()) fail(root, "a rules file is a mapping with keys whole_body_rules, name, root, links, ...");
        requireKeys(root, "rules", {"whole_body_rules", "name", "root", "stiffness", "strength", "missing_mass", "links",
                                    "loops", "forks", "unwrapped", "ligaments", "cartilage", "joint_ligaments", "discs"});
        if (readInt(field(root, "whole_body_rules", "rules"), "whole_body_rules") != kRulesFormatVersion)
            fail(root["whole_body_rules"], "unsupported rules version (this sinew reads version 1)");
        WholeBodyRules rules;
        rules.file = getSource();
        if (root["name"]) rules.name = readString(root["name"], "name");
        rules.root = readString(field(root, "root", "rules"), "root");
        if (root["stiffness"]) rules.stiffness = readStiffness(root["stiffness"]);
        if (root["strength"]) rules.strength = readStrength(root["strength"]);
        if (root["missing_mass"]) rules.missingMass = readMassRule(root["missing_mass"]);
        for (const YAML::Node& node : sequence(root, "links")) rules.links.push_back(readLink(node));
        for (const YAML::Node& node : sequence(root, "loops")) rules.loops.push_back(readLoop(node));
        for (const YAML::Node& node : sequence(root, "forks")) rules.forks.push_back(readFork(node));
        if (root["unwrapped"]) rules.unwrapped = readStrings(root["unwrapped"], "unwrapped");
        for (const YAML::Node& node : sequence(root, "ligaments")) rules.passive.push_back(readPassive(node, WireKind::Ligament));
        for (const YAML::Node& node : sequence(root, "cartilage")) rules.passive.push_back(readPassive(node, WireKind::Cartilage));
        for (const YAML::Node& node : sequence(root, "joint_ligaments"))
            rules.jointWires.push_back(readJointWires(node, WireKind::Ligament));
        for (const YAML::Node& node : sequence(root, "discs")) rules.jointWires.push_back(readJointWires(node, WireKind::Cartilage));
        return rules;
    }

private:
    // Each present key's number into its field, >= 0 (or > 0 when `positive`).
    template <std::size_t N>
    void readOptionalNumbers(const YAML::Node& node, const std::pair<const char*, double*> (&entries)[N],
                             const std::string& owner, bool positive) const {
        for (const auto& [key, value] : entries) {
            if (!node[key]) continue;
            *value = readNumber(node[key], key);
            if (positive ? !(*value > 0) : *value < 0)
                fail(node[key], owner + ": '" + key + "' must be " + (positive ? "> 0" : ">= 0"));
        }
    }

    WholeBodyStiffness readStiffness(const YAML::Node& node) const {
        requireKeys(node, "stiffness", {"muscle_strain_stiffness", "tendon", "ligament", "cartilage",
                                        "cartilage_precompression", "limit_fraction", "damping_ratio", "prestretch"});
        WholeBodyStiffness s;
        const std::pair<const char*, double*> entries[] = {
            {"muscle_strain_stiffness", &s.muscleStrainStiffness}, {"tendon", &s.tendonStiffness},
            {"ligament", &s.ligamentStiffness}, {"cartilage", &s.cartilageStiffness},
            {"cartilage_precompression", &s.cartilagePrecompression}, {"limit_fraction", &s.limitFraction},
            {"damping_ratio", &s.dampingRatio}, {"prestretch", &s.prestretch}};
        readOptionalNumbers(node, entries, "stiffness", false);
        return s;
    }

    WholeBodyStrength readStrength(const YAML::Node& node) const {
        requireKeys(node, "strength", {"specific_tension", "tendon_stress", "ligament_cross_section", "ligament_stress",
                                       "cartilage_cross_section", "cartilage_stress"});
        WholeBodyStrength s;
        const std::pair<const char*, double*> entries[] = {
            {"specific_tension", &s.specificTension}, {"tendon_stress", &s.tendonStress},
            {"ligament_cross_section", &s.ligamentCrossSection}, {"ligament_stress", &s.ligamentStress},
            {"cartilage_cross_section", &s.cartilageCrossSection}, {"cartilage_stress", &s.cartilageStress}};
        readOptionalNumbers(node, entries, "strength", true);
        return s;
    }

    WholeBodyMassRule readMassRule(const YAML::Node& node) const {
        requireKeys(node, "missing_mass", {"segment", "gender", "segment_bodies", "missing_bodies"});
        WholeBodyMassRule rule;
        rule.where = where(node);
        rule.segment = readString(field(node, "segment", "missing_mass"), "segment");
        if (node["gender"]) rule.gender = readString(node["gender"], "gender");
        rule.segmentBodies = readStrings(field(node, "segment_bodies", "missing_mass"), "segment_bodies");
        rule.missingBodies = readStrings(field(node, "missing_bodies", "missing_mass"), "missing_bodies");
        return rule;
    }

    WholeBodyLinkRule readLink(const YAML::Node& node) const {
        requireKeys(node, "link", {"name", "bodies"});
        WholeBodyLinkRule rule;
        rule.where = where(node);
        rule.name = readString(field(node, "name", "link"), "name");
        rule.bodies = readStrings(field(node, "bodies", "link '" + rule.name + "'"), "bodies");
        return rule;
    }

    SourcePoint readPoint(const YAML::Node& node, const std::string& owner) const {
        if (!node.IsMap()) fail(node, owner + ": a point is a mapping {body: NAME, point: [x, y, z]} or {body: NAME, ground: [x, y, z]}");
        requireKeys(node, "point", {"body", "point", "ground"});
        const bool inGround = static_cast<bool>(node["ground"]);
        if (inGround == static_cast<bool>(node["point"])) fail(node, owner + ": give a point's 'point' (body frame) or 'ground' (neutral pose), one of them");
        const char* key = inGround ? "ground" : "point";
        return {readString(field(node, "body", owner), "body"), readVector3(node[key], key), inGround, where(node)};
    }

    WholeBodyJointWiresRule readJointWires(const YAML::Node& node, WireKind kind) const {
        requireKeys(node, "joint wires", {"name", "joint", "flexion_axis", "bone_axis", "radius", "half_span", "flexion",
                                          "abduction", "names"});
        WholeBodyJointWiresRule rule;
        rule.kind = kind;
        rule.where = where(node);
        rule.name = readString(field(node, "name", "joint wires"), "name");
        const std::string owner = "'" + rule.name + "'";
        rule.joint = readString(field(node, "joint", owner), "joint");
        if (node["flexion_axis"]) rule.flexionAxis = readVector3(node["flexion_axis"], "flexion_axis");
        if (node["bone_axis"]) rule.boneAxis = readVector3(node["bone_axis"], "bone_axis");
        if (!(rule.flexionAxis.cross(rule.boneAxis).norm() > 1e-6))
            fail(node, owner + ": 'flexion_axis' and 'bone_axis' must be non-zero and not parallel");
        const std::pair<const char*, double*> numbers[] = {{"radius", &rule.radius}, {"half_span", &rule.halfSpan},
                                                           {"flexion", &rule.flexion}, {"abduction", &rule.abduction}};
        readOptionalNumbers(node, numbers, owner, true);
        rule.names = kind == WireKind::Ligament ? std::vector<std::string>{"anterior", "posterior", "medial", "lateral"}
                                                : std::vector<std::string>{"front", "back", "side_a", "side_b"};
        if (node["names"]) rule.names = readStrings(node["names"], "names");
        if (rule.names.size() != 4) fail(node["names"], owner + ": 'names' lists the four wires' names");
        return rule;
    }

    WholeBodyLoopRule readLoop(const YAML::Node& node) const {
        requireKeys(node, "loop", {"name", "links", "at"});
        WholeBodyLoopRule rule;
        rule.where = where(node);
        rule.name = readString(field(node, "name", "loop"), "name");
        const std::string owner = "loop '" + rule.name + "'";
        const std::vector<std::string> links = readStrings(field(node, "links", owner), "links");
        if (links.size() != 2) fail(node["links"], owner + ": 'links' names the two links the loop closes");
        rule.linkA = links[0];
        rule.linkB = links[1];
        rule.at = readPoint(field(node, "at", owner), owner);
        return rule;
    }

    WholeBodyForkRule readFork(const YAML::Node& node) const {
        requireKeys(node, "fork", {"name", "heads", "fraction", "tendon"});
        WholeBodyForkRule rule;
        rule.where = where(node);
        rule.name = readString(field(node, "name", "fork"), "name");
        const std::string owner = "fork '" + rule.name + "'";
        rule.heads = readStrings(field(node, "heads", owner), "heads");
        if (node["fraction"]) rule.fraction = readNumber(node["fraction"], "fraction");
        if (!(rule.fraction > 0 && rule.fraction < 1)) fail(node, owner + ": 'fraction' must lie in (0, 1)");
        rule.tendon = readString(field(node, "tendon", owner), "tendon");
        return rule;
    }

    WholeBodyPassiveRule readPassive(const YAML::Node& node, WireKind kind) const {
        const bool ligament = kind == WireKind::Ligament;
        if (ligament) requireKeys(node, "ligament", {"name", "points", "joint", "limit_axis", "limit_angle"});
        else requireKeys(node, "cartilage", {"name", "points"});
        WholeBodyPassiveRule rule;
        rule.kind = kind;
        rule.where = where(node);
        rule.name = readString(field(node, "name", toString(kind)), "name");
        const std::string owner = std::string(toString(kind)) + " '" + rule.name + "'";
        const YAML::Node points = field(node, "points", owner);
        if (!points.IsSequence()) fail(points, owner + ": 'points' must be a list");
        for (const YAML::Node& point : points) rule.points.push_back(readPoint(point, owner));
        if (!ligament) return rule;
        rule.joint = readString(field(node, "joint", owner), "joint");
        rule.limitAxis = readVector3(field(node, "limit_axis", owner), "limit_axis");
        if (!(rule.limitAxis.norm() > 0)) fail(node["limit_axis"], owner + ": 'limit_axis' must not be zero");
        rule.limitAngle = readNumber(field(node, "limit_angle", owner), "limit_angle");
        return rule;
    }
};

// Dumas' CSV numbers may end in "j" (a negative product of inertia); only the mass ratio is read here.
double parseRatio(const std::string& text, const std::string& where) {
    std::size_t used = 0;
    double value = 0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || !(value > 0 && value < 1))
        throw Error(where + ": RelMass must be a number in (0, 1), got '" + text + "'");
    return value;
}

std::vector<std::string> splitCsvLine(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) {
        if (!cell.empty() && cell.back() == '\r') cell.pop_back();
        cells.push_back(cell);
    }
    return cells;
}

}  // namespace

WholeBodyRules readWholeBodyRules(const std::string& path) { return RulesReader(path).read(loadYamlFile(path)); }

SegmentRatios readSegmentRatios(const std::string& csvPath, const std::string& segment, const std::string& gender) {
    std::ifstream in(csvPath);
    if (!in) throw Error(csvPath + ": cannot open the anthropometric table");
    std::string line;
    std::getline(in, line);
    if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    const std::vector<std::string> header = splitCsvLine(line);
    auto column = [&](const std::string& name) {
        for (std::size_t i = 0; i < header.size(); ++i)
            if (header[i] == name) return i;
        throw Error(csvPath + ":1: no column '" + name + "' (expected Dumas 2007's Segment, Gender, RelMass, ...)");
    };
    const std::size_t segmentColumn = column("Segment"), genderColumn = column("Gender"), massColumn = column("RelMass");
    for (int lineNumber = 2; std::getline(in, line); ++lineNumber) {
        const std::vector<std::string> cells = splitCsvLine(line);
        if (cells.size() != header.size())
            throw Error(csvPath + ":" + std::to_string(lineNumber) + ": expected " + std::to_string(header.size()) +
                        " cells, got " + std::to_string(cells.size()));
        if (cells[segmentColumn] == segment && cells[genderColumn] == gender)
            return {parseRatio(cells[massColumn], csvPath + ":" + std::to_string(lineNumber))};
    }
    throw Error(csvPath + ": no row for segment '" + segment + "', gender '" + gender + "'");
}

}  // namespace sinew

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "sinew/core/error.hpp"
#include "sinew/core/model_builder.hpp"
#include "sinew/io/model_file.hpp"

namespace sinew {
namespace {

// Reads one model document, turning every problem into a ModelError at "file:line".
class Reader {
public:
    explicit Reader(std::string source) : source_(std::move(source)) {}

    Model read(const YAML::Node& root) {
        if (!root.IsMap()) fail(root, "a model file is a mapping with keys sinew_model, name, links, joints, ...");
        requireKeys(root, "model", {"sinew_model", "name", "gravity", "links", "joints", "virtual_links", "loops", "wires"});
        const YAML::Node version = root["sinew_model"];
        if (!version) fail(root, "missing 'sinew_model: " + std::to_string(kModelFormatVersion) + "' (format version)");
        if (readInt(version, "sinew_model") != kModelFormatVersion)
            fail(version, "unsupported format version " + version.Scalar() + " (this sinew reads version " +
                              std::to_string(kModelFormatVersion) + ")");
        ModelBuilder builder(root["name"] ? readString(root["name"], "name") : std::string("model"));
        if (root["gravity"]) builder.setGravity(readVector3(root["gravity"], "gravity"), where(root["gravity"]));
        for (const YAML::Node& node : sequence(root, "links")) builder.addLink(readLink(node));
        for (const YAML::Node& node : sequence(root, "joints")) builder.addJoint(readJoint(node));
        for (const YAML::Node& node : sequence(root, "virtual_links")) builder.addVirtualLink(readVirtualLink(node));
        for (const YAML::Node& node : sequence(root, "loops")) builder.addLoop(readLoop(node));
        for (const YAML::Node& node : sequence(root, "wires")) builder.addWire(readWire(node));
        return builder.build();
    }

private:
    std::string source_;

    std::string where(const YAML::Node& node) const { return source_ + ":" + std::to_string(node.Mark().line + 1); }

    [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
        throw ModelError(where(node), message);
    }

    void requireKeys(const YAML::Node& map, const std::string& what, std::set<std::string> allowed) const {
        for (const auto& entry : map) {
            const std::string key = entry.first.Scalar();
            if (!allowed.count(key)) {
                std::string list;
                for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
                fail(entry.first, "unknown field '" + key + "' in " + what + " (expected one of: " + list + ")");
            }
        }
    }

    std::vector<YAML::Node> sequence(const YAML::Node& root, const std::string& key) const {
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

    YAML::Node field(const YAML::Node& map, const std::string& key, const std::string& owner) const {
        const YAML::Node node = map[key];
        if (!node || node.IsNull()) fail(map, owner + ": missing field '" + key + "'");
        return node;
    }

    std::string readString(const YAML::Node& node, const std::string& key) const {
        if (!node.IsScalar()) fail(node, "field '" + key + "' must be a single word or string");
        return node.Scalar();
    }

    double readNumber(const YAML::Node& node, const std::string& key) const {
        if (!node.IsScalar()) fail(node, "field '" + key + "' must be a number");
        double value = 0;
        try {
            value = node.as<double>();
        } catch (const YAML::Exception&) {
            fail(node, "field '" + key + "' must be a number, got '" + node.Scalar() + "'");
        }
        if (!std::isfinite(value)) fail(node, "field '" + key + "' must be finite, got '" + node.Scalar() + "'");
        return value;
    }

    int readInt(const YAML::Node& node, const std::string& key) const {
        const double value = readNumber(node, key);
        if (value != std::floor(value) || std::abs(value) > 1e9) fail(node, "field '" + key + "' must be a whole number");
        return static_cast<int>(value);
    }

    std::vector<double> readNumbers(const YAML::Node& node, const std::string& key) const {
        if (node.IsScalar()) return {readNumber(node, key)};
        if (!node.IsSequence()) fail(node, "field '" + key + "' must be a number or a list of numbers");
        std::vector<double> values;
        for (const YAML::Node& item : node) values.push_back(readNumber(item, key));
        return values;
    }

    Eigen::Vector3d readVector3(const YAML::Node& node, const std::string& key) const {
        const std::vector<double> v = readNumbers(node, key);
        if (v.size() != 3 || !node.IsSequence()) fail(node, "field '" + key + "' must be a list of 3 numbers");
        return Eigen::Vector3d(v[0], v[1], v[2]);
    }

    LinkSpec readLink(const YAML::Node& node) const {
        requireKeys(node, "link", {"name", "mass", "com", "inertia"});
        LinkSpec link;
        link.where = where(node);
        link.name = readString(field(node, "name", "link"), "name");
        const std::string owner = "link '" + link.name + "'";
        link.mass = readNumber(field(node, "mass", owner), "mass");
        if (node["com"]) link.com_B = readVector3(node["com"], "com");
        const YAML::Node inertia = field(node, "inertia", owner);
        const std::vector<double> I = readNumbers(inertia, "inertia");
        if (I.size() != 6) fail(inertia, owner + ": field 'inertia' must be 6 numbers [Ixx, Iyy, Izz, Ixy, Ixz, Iyz]");
        link.inertia_Bcom << I[0], I[3], I[4], I[3], I[1], I[5], I[4], I[5], I[2];
        return link;
    }

    JointSpec readJoint(const YAML::Node& node) const {
        requireKeys(node, "joint", {"name", "type", "parent", "child", "parent_point", "child_point", "axis",
                                    "initial_rotation", "initial_angle", "initial_position"});
        JointSpec joint;
        joint.where = where(node);
        joint.name = readString(field(node, "name", "joint"), "name");
        const std::string owner = "joint '" + joint.name + "'";
        const YAML::Node type = field(node, "type", owner);
        const std::string typeName = readString(type, "type");
        if (typeName == "free") joint.type = JointType::Free;
        else if (typeName == "ball") joint.type = JointType::Ball;
        else if (typeName == "pin") joint.type = JointType::Pin;
        else if (typeName == "weld") joint.type = JointType::Weld;
        else fail(type, owner + ": unknown joint type '" + typeName + "' (expected free, ball, pin or weld)");
        joint.parent = readString(field(node, "parent", owner), "parent");
        joint.child = readString(field(node, "child", owner), "child");
        if (node["parent_point"]) joint.p_PF = readVector3(node["parent_point"], "parent_point");
        if (node["child_point"]) joint.p_BM = readVector3(node["child_point"], "child_point");
        if (node["axis"]) joint.axis = readVector3(node["axis"], "axis");
        if (node["initial_rotation"]) joint.initialRotation = readVector3(node["initial_rotation"], "initial_rotation");
        if (node["initial_angle"]) joint.initialAngle = readNumber(node["initial_angle"], "initial_angle");
        if (node["initial_position"]) joint.initialPosition = readVector3(node["initial_position"], "initial_position");
        return joint;
    }

    VirtualLinkSpec readVirtualLink(const YAML::Node& node) const {
        requireKeys(node, "virtual link", {"name", "initial_position"});
        VirtualLinkSpec link;
        link.where = where(node);
        link.name = readString(field(node, "name", "virtual link"), "name");
        link.initialPosition = readVector3(field(node, "initial_position", "virtual link '" + link.name + "'"),
                                           "initial_position");
        return link;
    }

    LoopSpec readLoop(const YAML::Node& node) const {
        requireKeys(node, "loop", {"name", "link_a", "point_a", "link_b", "point_b"});
        LoopSpec loop;
        loop.where = where(node);
        loop.name = readString(field(node, "name", "loop"), "name");
        const std::string owner = "loop '" + loop.name + "'";
        loop.linkA = readString(field(node, "link_a", owner), "link_a");
        loop.p_A = readVector3(field(node, "point_a", owner), "point_a");
        loop.linkB = readString(field(node, "link_b", owner), "link_b");
        loop.p_B = readVector3(field(node, "point_b", owner), "point_b");
        return loop;
    }

    WireSpec readWire(const YAML::Node& node) const {
        requireKeys(node, "wire", {"name", "kind", "points", "force_law"});
        WireSpec wire;
        wire.where = where(node);
        wire.name = readString(field(node, "name", "wire"), "name");
        const std::string owner = "wire '" + wire.name + "'";
        const YAML::Node kind = field(node, "kind", owner);
        const std::string kindName = readString(kind, "kind");
        if (kindName == "muscle") wire.kind = WireKind::Muscle;
        else if (kindName == "tendon") wire.kind = WireKind::Tendon;
        else if (kindName == "ligament") wire.kind = WireKind::Ligament;
        else if (kindName == "cartilage") wire.kind = WireKind::Cartilage;
        else fail(kind, owner + ": unknown kind '" + kindName + "' (expected muscle, tendon, ligament or cartilage)");
        const YAML::Node points = field(node, "points", owner);
        if (!points.IsSequence()) fail(points, owner + ": field 'points' must be a list");
        for (const YAML::Node& point : points) {
            if (!point.IsMap()) fail(point, owner + ": each point is a mapping {link: NAME, at: [x, y, z]}");
            requireKeys(point, "wire point", {"link", "at"});
            wire.points.push_back({readString(field(point, "link", owner + " point"), "link"),
                                   readVector3(field(point, "at", owner + " point"), "at"), where(point)});
        }
        const YAML::Node law = field(node, "force_law", owner);
        if (!law.IsMap()) fail(law, owner + ": field 'force_law' must be a mapping with a 'type'");
        for (const auto& entry : law) {
            const std::string key = entry.first.Scalar();
            if (key == "type") wire.law.type = readString(entry.second, "type");
            else wire.law.parameters.set(key, readNumbers(entry.second, key));
        }
        if (wire.law.type.empty()) fail(law, owner + ": force_law needs a 'type'");
        wire.lawWhere = where(law);
        return wire;
    }
};

Model readDocument(const std::string& text, const std::string& source) {
    YAML::Node root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::ParserException& e) {
        throw ModelError(source + ":" + std::to_string(e.mark.line + 1), "YAML syntax error: " + e.msg);
    }
    return Reader(source).read(root);
}

}  // namespace

Model readModelFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw ModelError(path, "cannot open model file");
    std::stringstream text;
    text << in.rdbuf();
    return readDocument(text.str(), path);
}

Model readModelText(const std::string& text, const std::string& sourceName) { return readDocument(text, sourceName); }

}  // namespace sinew

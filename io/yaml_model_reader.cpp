#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "sinew/core/error.hpp"
#include "sinew/core/model_builder.hpp"
#include "sinew/io/model_file.hpp"
#include "yaml_fields.hpp"
#include "yaml_force_elements.hpp"

namespace sinew {
namespace {

// Reads one model document, turning every problem into a ModelError at "file:line".
class Reader : public YamlFields {
public:
    using YamlFields::YamlFields;

    Model read(const YAML::Node& root) {
        if (!root.IsMap()) fail(root, "a model file is a mapping with keys sinew_model, name, links, joints, ...");
        requireKeys(root, "model", {"sinew_model", "name", "gravity", "links", "joints", "virtual_links", "loops", "couplers",
                                    "wrap_objects", "wires", "contacts", "contact_geometry", "force_elements"});
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
        for (const YAML::Node& node : sequence(root, "couplers")) builder.addCoupler(readCoupler(node));
        for (const YAML::Node& node : sequence(root, "wrap_objects")) builder.addWrapObject(readWrapObject(node));
        for (const YAML::Node& node : sequence(root, "wires")) builder.addWire(readWire(node));
        for (const YAML::Node& node : sequence(root, "contacts")) builder.addContact(readContact(node));
        readForceElements(*this, root, builder);
        return builder.build();
    }

private:
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
                                    "initial_rotation", "initial_angle", "initial_position", "parent_orientation",
                                    "child_orientation", "coordinates", "transform"});
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
        else if (typeName == "custom") joint.type = JointType::Custom;
        else fail(type, owner + ": unknown joint type '" + typeName + "' (expected free, ball, pin, weld or custom)");
        joint.parent = readString(field(node, "parent", owner), "parent");
        joint.child = readString(field(node, "child", owner), "child");
        if (node["parent_point"]) joint.p_PF = readVector3(node["parent_point"], "parent_point");
        if (node["child_point"]) joint.p_BM = readVector3(node["child_point"], "child_point");
        if (node["axis"]) joint.axis = readVector3(node["axis"], "axis");
        if (node["initial_rotation"]) joint.initialRotation = readVector3(node["initial_rotation"], "initial_rotation");
        if (node["initial_angle"]) joint.initialAngle = readNumber(node["initial_angle"], "initial_angle");
        if (node["initial_position"]) joint.initialPosition = readVector3(node["initial_position"], "initial_position");
        if (node["parent_orientation"]) joint.R_PF = readOrientation(node["parent_orientation"], "parent_orientation");
        if (node["child_orientation"]) joint.R_BM = readOrientation(node["child_orientation"], "child_orientation");
        for (const YAML::Node& item : sequence(node, "coordinates")) joint.coordinates.push_back(readCoordinate(item, owner));
        if (joint.type == JointType::Custom) readTransform(node, owner, joint);
        else if (node["transform"]) fail(node["transform"], owner + ": only custom joints take a transform");
        return joint;
    }

    // Body-fixed x-y-z angles in rad (OpenSim's frame orientation), or a rotation matrix as 9 numbers row by row.
    Eigen::Matrix3d readOrientation(const YAML::Node& node, const std::string& key) const {
        const std::vector<double> v = readNumbers(node, key);
        if (v.size() == 3)
            return (Eigen::AngleAxisd(v[0], Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(v[1], Eigen::Vector3d::UnitY()) *
                    Eigen::AngleAxisd(v[2], Eigen::Vector3d::UnitZ())).toRotationMatrix();
        if (v.size() != 9 || !node.IsSequence())
            fail(node, "field '" + key + "' must be 3 body-fixed x-y-z angles (rad) or a rotation matrix as 9 numbers, "
                       "row by row");
        return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(v.data());
    }

    bool readBool(const YAML::Node& node, const std::string& key) const {
        bool value = false;
        if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value))
            fail(node, "field '" + key + "' must be true or false");
        return value;
    }

    CoordinateSpec readCoordinate(const YAML::Node& node, const std::string& owner) const {
        requireKeys(node, "coordinate", {"name", "default", "range", "clamped", "locked"});
        CoordinateSpec coordinate;
        coordinate.where = where(node);
        coordinate.name = readString(field(node, "name", owner + " coordinate"), "name");
        if (node["default"]) coordinate.defaultValue = readNumber(node["default"], "default");
        if (node["range"]) {
            const std::vector<double> range = readNumbers(node["range"], "range");
            if (range.size() != 2 || !node["range"].IsSequence()) fail(node["range"], "field 'range' must be [min, max]");
            coordinate.rangeMin = range[0];
            coordinate.rangeMax = range[1];
        }
        if (node["clamped"]) coordinate.clamped = readBool(node["clamped"], "clamped");
        if (node["locked"]) coordinate.locked = readBool(node["locked"], "locked");
        return coordinate;
    }

    // The six transform axes; an axis left out is OpenSim's default (x, y, z in turn; no coordinate; zero).
    void readTransform(const YAML::Node& joint, const std::string& owner, JointSpec& spec) const {
        static const char* const names[] = {"rotation1", "rotation2", "rotation3", "translation1", "translation2",
                                            "translation3"};
        const YAML::Node transform = field(joint, "transform", owner);
        if (!transform.IsMap()) fail(transform, owner + ": field 'transform' must be a mapping of rotation1..translation3");
        requireKeys(transform, owner + " transform", {names[0], names[1], names[2], names[3], names[4], names[5]});
        for (int k = 0; k < 6; ++k) {
            TransformAxisSpec axis;
            axis.axis = Eigen::Vector3d::Unit(k % 3);
            const YAML::Node node = transform[names[k]];
            if (node) {
                const std::string label = owner + " " + names[k];
                if (!node.IsMap()) fail(node, label + " must be a mapping {axis, coordinate, function}");
                requireKeys(node, label, {"axis", "coordinate", "function"});
                axis.axis = readVector3(field(node, "axis", label), "axis");
                if (node["coordinate"]) axis.coordinate = readString(node["coordinate"], "coordinate");
                if (node["function"]) axis.function = readFunction(node["function"], label);
            }
            spec.transformAxes.push_back(axis);
        }
    }

    Function readFunction(const YAML::Node& node, const std::string& owner) const {
        if (!node.IsMap()) fail(node, owner + ": a function is a mapping with a 'type'");
        const std::string type = readString(field(node, "type", owner + " function"), "type");
        auto numbers = [&](const char* key) { return readNumbers(field(node, key, owner + " function"), key); };
        try {
            std::optional<Function> f;
            if (type == "constant") {
                requireKeys(node, owner + " constant function", {"type", "value", "scale"});
                f = Function::constant(readNumber(field(node, "value", owner + " function"), "value"));
            } else if (type == "linear" || type == "polynomial") {
                requireKeys(node, owner + " " + type + " function", {"type", "coefficients", "scale"});
                const std::vector<double> c = numbers("coefficients");
                if (type == "linear" && c.size() != 2)
                    fail(node["coefficients"], owner + ": a linear function's coefficients are [slope, intercept]");
                f = type == "linear" ? Function::linear(c[0], c[1]) : Function::polynomial(c);
            } else if (type == "simm_spline" || type == "natural_cubic_spline") {
                requireKeys(node, owner + " " + type, {"type", "x", "y", "scale"});
                f = type == "simm_spline" ? Function::simmSpline(numbers("x"), numbers("y"))
                                          : Function::naturalCubicSpline(numbers("x"), numbers("y"));
            } else {
                fail(node["type"], owner + ": unknown function type '" + type + "' (expected constant, linear, polynomial, "
                                   "simm_spline or natural_cubic_spline)");
            }
            if (node["scale"]) f = f->multipliedBy(readNumber(node["scale"], "scale"));
            return *f;
        } catch (const ModelError&) {
            throw;
        } catch (const Error& e) {
            fail(node, owner + ": " + e.what());
        }
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

    // A foot: the link, its sole polygon (vertices in the link frame) and the friction coefficient.
    ContactSpec readContact(const YAML::Node& node) const {
        requireKeys(node, "contact", {"name", "link", "sole", "friction"});
        ContactSpec contact;
        contact.where = where(node);
        contact.name = readString(field(node, "name", "contact"), "name");
        const std::string owner = "contact '" + contact.name + "'";
        contact.link = readString(field(node, "link", owner), "link");
        const YAML::Node sole = field(node, "sole", owner);
        if (!sole.IsSequence() || sole.size() == 0)
            fail(sole, owner + ": field 'sole' must be a list of vertices [x, y, z] (m, in the link frame)");
        for (const YAML::Node& vertex : sole) contact.sole_B.push_back(readVector3(vertex, "sole"));
        if (node["friction"]) contact.friction = readNumber(node["friction"], "friction");
        return contact;
    }

    // OpenSim's CoordinateCouplerConstraint: dependent = scale_factor * function(independent).
    CoordinateCouplerSpec readCoupler(const YAML::Node& node) const {
        requireKeys(node, "coupler", {"name", "dependent", "independent", "function", "scale_factor"});
        CoordinateCouplerSpec coupler;
        coupler.where = where(node);
        coupler.name = readString(field(node, "name", "coupler"), "name");
        const std::string owner = "coupler '" + coupler.name + "'";
        coupler.dependentCoordinate = readString(field(node, "dependent", owner), "dependent");
        coupler.independentCoordinate = readString(field(node, "independent", owner), "independent");
        coupler.function = readFunction(field(node, "function", owner), owner);
        if (node["scale_factor"]) coupler.scaleFactor = readNumber(node["scale_factor"], "scale_factor");
        return coupler;
    }

    // {link, at} plus, for OpenSim's path points, active_when: {coordinate, range} and moving: {x|y|z:
    // {coordinate, function}} (the moving components' entries of `at` are not read).
    WirePointSpec readWirePoint(const YAML::Node& node, const std::string& owner) const {
        if (!node.IsMap()) fail(node, owner + ": each point is a mapping {link: NAME, at: [x, y, z]}");
        requireKeys(node, "wire point", {"link", "at", "active_when", "moving"});
        const std::string label = owner + " point";
        WirePointSpec point{readString(field(node, "link", label), "link"), readVector3(field(node, "at", label), "at"),
                            where(node)};
        if (const YAML::Node when = node["active_when"]) {
            if (!when.IsMap()) fail(when, label + ": active_when is a mapping {coordinate, range}");
            requireKeys(when, "active_when", {"coordinate", "range"});
            const YAML::Node range = field(when, "range", label + " active_when");
            const std::vector<double> r = readNumbers(range, "range");
            if (r.size() != 2 || !range.IsSequence()) fail(range, label + ": active_when range must be [min, max]");
            point.condition = WirePointConditionSpec{readString(field(when, "coordinate", label + " active_when"), "coordinate"),
                                                     r[0], r[1]};
        }
        if (const YAML::Node moving = node["moving"]) {
            if (!moving.IsMap()) fail(moving, label + ": moving is a mapping of x, y, z to {coordinate, function}");
            requireKeys(moving, "moving", {"x", "y", "z"});
            for (int axis = 0; axis < 3; ++axis) {
                const std::string key(1, static_cast<char>('x' + axis));
                const YAML::Node component = moving[key];
                if (!component) continue;
                const std::string componentLabel = label + " moving " + key;
                if (!component.IsMap()) fail(component, componentLabel + " must be a mapping {coordinate, function}");
                requireKeys(component, "moving " + key, {"coordinate", "function"});
                point.motions.push_back({axis, readString(field(component, "coordinate", componentLabel), "coordinate"),
                                         readFunction(field(component, "function", componentLabel), componentLabel)});
            }
        }
        return point;
    }

    WireWrapSpec readWireWrap(const YAML::Node& node, const std::string& owner) const {
        requireKeys(node, "wrap", {"object", "range", "method", "side_site", "side_site_link"});
        WireWrapSpec wrap;
        wrap.where = where(node);
        wrap.object = readString(field(node, "object", owner + " wrap"), "object");
        if (const YAML::Node range = node["range"]) {
            const std::vector<double> r = readNumbers(range, "range");
            if (r.size() != 2 || !range.IsSequence()) fail(range, owner + ": wrap range must be [first, last] point");
            wrap.firstPoint = readInt(range[0], "range");
            wrap.lastPoint = readInt(range[1], "range");
        }
        if (const YAML::Node method = node["method"]) {
            const std::string name = readString(method, "method");
            if (name == "hybrid") wrap.method = WrapMethod::Hybrid;
            else if (name == "midpoint") wrap.method = WrapMethod::Midpoint;
            else if (name == "axial") wrap.method = WrapMethod::Axial;
            else if (name == "mujoco") wrap.method = WrapMethod::MuJoCo;
            else fail(method, owner + ": unknown wrap method '" + name + "' (expected hybrid, midpoint, axial or mujoco)");
        }
        if (const YAML::Node side = node["side_site"]) wrap.sideSite = readVector3(side, "side_site");
        if (const YAML::Node link = node["side_site_link"]) wrap.sideSiteLink = readString(link, "side_site_link");
        return wrap;
    }

    WrapObjectSpec readWrapObject(const YAML::Node& node) const {
        requireKeys(node, "wrap object", {"name", "type", "link", "rotation", "translation", "radius", "length", "radii",
                                          "quadrant"});
        WrapObjectSpec object;
        object.where = where(node);
        object.name = readString(field(node, "name", "wrap object"), "name");
        const std::string owner = "wrap object '" + object.name + "'";
        const YAML::Node type = field(node, "type", owner);
        const std::string typeName = readString(type, "type");
        auto only = [&](const char* key, bool allowed) {
            if (node[key] && !allowed) fail(node[key], owner + ": a " + typeName + " takes no '" + key + "'");
        };
        if (typeName == "sphere") object.shape = WrapShape::Sphere;
        else if (typeName == "cylinder") object.shape = WrapShape::Cylinder;
        else if (typeName == "ellipsoid") object.shape = WrapShape::Ellipsoid;
        else fail(type, owner + ": unknown wrap object type '" + typeName + "' (expected sphere, cylinder or ellipsoid)");
        object.link = readString(field(node, "link", owner), "link");
        if (node["rotation"]) object.xyzBodyRotation = readVector3(node["rotation"], "rotation");
        if (node["translation"]) object.translation = readVector3(node["translation"], "translation");
        only("radius", object.shape != WrapShape::Ellipsoid);
        only("length", object.shape == WrapShape::Cylinder);
        only("radii", object.shape == WrapShape::Ellipsoid);
        if (object.shape == WrapShape::Ellipsoid) object.radii = readVector3(field(node, "radii", owner), "radii");
        else object.radius = readNumber(field(node, "radius", owner), "radius");
        if (object.shape == WrapShape::Cylinder) object.length = readNumber(field(node, "length", owner), "length");
        if (node["quadrant"]) object.quadrant = readString(node["quadrant"], "quadrant");
        return object;
    }

    WireSpec readWire(const YAML::Node& node) const {
        requireKeys(node, "wire", {"name", "kind", "points", "wraps", "force_law", "strength", "cross_section"});
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
        for (const YAML::Node& point : points) wire.points.push_back(readWirePoint(point, owner));
        for (const YAML::Node& wrap : sequence(node, "wraps")) wire.wraps.push_back(readWireWrap(wrap, owner));
        const YAML::Node law = field(node, "force_law", owner);
        if (!law.IsMap()) fail(law, owner + ": field 'force_law' must be a mapping with a 'type'");
        for (const auto& entry : law) {
            const std::string key = entry.first.Scalar();
            if (key == "type") wire.law.type = readString(entry.second, "type");
            else wire.law.parameters.set(key, readNumbers(entry.second, key));
        }
        if (wire.law.type.empty()) fail(law, owner + ": force_law needs a 'type'");
        wire.lawWhere = where(law);
        // Their signs are checked where every wire's are, in ModelBuilder, at the wire's line.
        if (node["strength"]) wire.strength = readNumber(node["strength"], "strength");
        if (node["cross_section"]) wire.crossSection = readNumber(node["cross_section"], "cross_section");
        return wire;
    }
};

Model readDocument(const std::string& text, const std::string& source) {
    return Reader(source).read(parseYamlText(text, source));
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

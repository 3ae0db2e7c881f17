#include "yaml_force_elements.hpp"

#include <functional>
#include <map>

#include "yaml_emit.hpp"

namespace sinew {
namespace {

LinkFrameSpec readFrame(const YamlFields& f, const YAML::Node& node, const std::string& owner, const std::string& suffix) {
    LinkFrameSpec frame;
    frame.link = f.readString(f.field(node, "link" + suffix, owner), "link" + suffix);
    if (node["translation" + suffix]) frame.translation = f.readVector3(node["translation" + suffix], "translation" + suffix);
    if (node["rotation" + suffix]) frame.xyzBodyRotation = f.readVector3(node["rotation" + suffix], "rotation" + suffix);
    return frame;
}

void readCoordinateLimit(const YamlFields& f, const YAML::Node& node, const std::string& owner, ModelBuilder& builder) {
    f.requireKeys(node, owner, {"type", "name", "coordinate", "upper_stiffness", "upper_limit", "lower_stiffness",
                                "lower_limit", "damping", "transition"});
    CoordinateLimitForceSpec spec;
    spec.where = f.where(node);
    spec.name = f.readString(node["name"], "name");
    spec.coordinate = f.readString(f.field(node, "coordinate", owner), "coordinate");
    spec.upperStiffness = f.readNumber(f.field(node, "upper_stiffness", owner), "upper_stiffness");
    spec.upperLimit = f.readNumber(f.field(node, "upper_limit", owner), "upper_limit");
    spec.lowerStiffness = f.readNumber(f.field(node, "lower_stiffness", owner), "lower_stiffness");
    spec.lowerLimit = f.readNumber(f.field(node, "lower_limit", owner), "lower_limit");
    if (node["damping"]) spec.damping = f.readNumber(node["damping"], "damping");
    spec.transition = f.readNumber(f.field(node, "transition", owner), "transition");
    builder.addCoordinateLimitForce(std::move(spec));
}

void readSpring(const YamlFields& f, const YAML::Node& node, const std::string& owner, ModelBuilder& builder) {
    f.requireKeys(node, owner, {"type", "name", "link_a", "point_a", "link_b", "point_b", "stiffness", "rest_length"});
    PointToPointSpringSpec spec;
    spec.where = f.where(node);
    spec.name = f.readString(node["name"], "name");
    spec.linkA = f.readString(f.field(node, "link_a", owner), "link_a");
    spec.linkB = f.readString(f.field(node, "link_b", owner), "link_b");
    if (node["point_a"]) spec.pointA = f.readVector3(node["point_a"], "point_a");
    if (node["point_b"]) spec.pointB = f.readVector3(node["point_b"], "point_b");
    spec.stiffness = f.readNumber(f.field(node, "stiffness", owner), "stiffness");
    spec.restLength = f.readNumber(f.field(node, "rest_length", owner), "rest_length");
    builder.addPointToPointSpring(std::move(spec));
}

void readBushing(const YamlFields& f, const YAML::Node& node, const std::string& owner, ModelBuilder& builder) {
    f.requireKeys(node, owner, {"type", "name", "link_a", "translation_a", "rotation_a", "link_b", "translation_b",
                                "rotation_b", "rotational_stiffness", "translational_stiffness", "rotational_damping",
                                "translational_damping"});
    BushingForceSpec spec;
    spec.where = f.where(node);
    spec.name = f.readString(node["name"], "name");
    spec.frameA = readFrame(f, node, owner, "_a");
    spec.frameB = readFrame(f, node, owner, "_b");
    const auto read = [&](const char* key, Eigen::Vector3d& value) {
        if (node[key]) value = f.readVector3(node[key], key);
    };
    read("rotational_stiffness", spec.rotationalStiffness);
    read("translational_stiffness", spec.translationalStiffness);
    read("rotational_damping", spec.rotationalDamping);
    read("translational_damping", spec.translationalDamping);
    builder.addBushingForce(std::move(spec));
}

void readHuntCrossley(const YamlFields& f, const YAML::Node& node, const std::string& owner, ModelBuilder& builder) {
    f.requireKeys(node, owner, {"type", "name", "transition_velocity", "surfaces"});
    HuntCrossleyForceSpec spec;
    spec.where = f.where(node);
    spec.name = f.readString(node["name"], "name");
    if (node["transition_velocity"]) spec.transitionVelocity = f.readNumber(node["transition_velocity"], "transition_velocity");
    for (const YAML::Node& s : f.sequence(node, "surfaces")) {
        f.requireKeys(s, owner + " surface", {"geometry", "stiffness", "dissipation", "static_friction",
                                              "dynamic_friction", "viscous_friction"});
        HuntCrossleySurfaceSpec surface;
        surface.geometry = f.readString(f.field(s, "geometry", owner + " surface"), "geometry");
        surface.stiffness = f.readNumber(f.field(s, "stiffness", owner + " surface"), "stiffness");
        const auto read = [&](const char* key, double& value) {
            if (s[key]) value = f.readNumber(s[key], key);
        };
        read("dissipation", surface.dissipation);
        read("static_friction", surface.staticFriction);
        read("dynamic_friction", surface.dynamicFriction);
        read("viscous_friction", surface.viscousFriction);
        spec.surfaces.push_back(std::move(surface));
    }
    builder.addHuntCrossleyForce(std::move(spec));
}

void readContactGeometry(const YamlFields& f, const YAML::Node& node, ModelBuilder& builder) {
    f.requireKeys(node, "contact geometry", {"name", "shape", "link", "translation", "rotation", "radius"});
    ContactGeometrySpec spec;
    spec.where = f.where(node);
    spec.name = f.readString(f.field(node, "name", "contact geometry"), "name");
    const std::string owner = "contact geometry '" + spec.name + "'";
    const YAML::Node shape = f.field(node, "shape", owner);
    const std::string shapeName = f.readString(shape, "shape");
    if (shapeName == "sphere") spec.shape = ContactGeometry::Shape::Sphere;
    else if (shapeName == "half_space") spec.shape = ContactGeometry::Shape::HalfSpace;
    else f.fail(shape, owner + ": unknown shape '" + shapeName + "' (expected sphere or half_space)");
    spec.frame = readFrame(f, node, owner, "");
    if (spec.shape == ContactGeometry::Shape::Sphere) spec.radius = f.readNumber(f.field(node, "radius", owner), "radius");
    else if (node["radius"]) f.fail(node["radius"], owner + ": a half_space takes no 'radius'");
    builder.addContactGeometry(std::move(spec));
}

void emitKeyedVector(YAML::Emitter& out, const char* key, const Eigen::Vector3d& v) {
    out << YAML::Key << key << YAML::Value;
    emitVector(out, v);
}

void emitFrame(YAML::Emitter& out, const Model& model, const LinkFrame& frame, const std::string& suffix) {
    out << YAML::Key << "link" + suffix << YAML::Value << linkName(model, frame.link);
    emitKeyedVector(out, ("translation" + suffix).c_str(), frame.p_BF);
    emitKeyedVector(out, ("rotation" + suffix).c_str(), frame.xyzBodyRotation);
}

}  // namespace

void readForceElements(const YamlFields& f, const YAML::Node& root, ModelBuilder& builder) {
    for (const YAML::Node& node : f.sequence(root, "contact_geometry")) readContactGeometry(f, node, builder);
    using Reader = std::function<void(const YamlFields&, const YAML::Node&, const std::string&, ModelBuilder&)>;
    static const std::map<std::string, Reader> readers{{"coordinate_limit", readCoordinateLimit},
                                                       {"point_to_point_spring", readSpring},
                                                       {"bushing", readBushing},
                                                       {"hunt_crossley", readHuntCrossley}};
    for (const YAML::Node& node : f.sequence(root, "force_elements")) {
        const YAML::Node type = f.field(node, "type", "force element");
        const std::string typeName = f.readString(type, "type");
        const auto reader = readers.find(typeName);
        if (reader == readers.end())
            f.fail(type, "unknown force element type '" + typeName +
                             "' (expected coordinate_limit, point_to_point_spring, bushing or hunt_crossley)");
        const std::string name = f.readString(f.field(node, "name", typeName), "name");
        reader->second(f, node, typeName + " '" + name + "'", builder);
    }
}

void emitForceElements(YAML::Emitter& out, const Model& model) {
    const ForceElements& elements = model.getForceElements();
    if (!elements.contactGeometry.empty()) {
        out << YAML::Key << "contact_geometry" << YAML::Value << YAML::BeginSeq;
        for (const ContactGeometry& g : elements.contactGeometry) {
            const bool sphere = g.shape == ContactGeometry::Shape::Sphere;
            out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << g.name << YAML::Key << "shape" << YAML::Value
                << (sphere ? "sphere" : "half_space");
            emitFrame(out, model, g.frame, "");
            if (sphere) out << YAML::Key << "radius" << YAML::Value << g.radius;
            out << YAML::EndMap;
        }
        out << YAML::EndSeq;
    }
    if (elements.empty()) return;
    out << YAML::Key << "force_elements" << YAML::Value << YAML::BeginSeq;
    const auto begin = [&](const char* type, const std::string& name) {
        out << YAML::BeginMap << YAML::Key << "type" << YAML::Value << type << YAML::Key << "name" << YAML::Value << name;
    };
    const auto number = [&](const char* key, double value) { out << YAML::Key << key << YAML::Value << value; };
    for (const CoordinateLimitForce& l : elements.coordinateLimits) {
        begin("coordinate_limit", l.name);
        out << YAML::Key << "coordinate" << YAML::Value << model.getCoordinates()[static_cast<std::size_t>(l.q)].name;
        number("upper_stiffness", l.upperStiffness);
        number("upper_limit", l.upperLimit);
        number("lower_stiffness", l.lowerStiffness);
        number("lower_limit", l.lowerLimit);
        number("damping", l.damping);
        number("transition", l.transition);
        out << YAML::EndMap;
    }
    for (const PointToPointSpring& s : elements.springs) {
        begin("point_to_point_spring", s.name);
        out << YAML::Key << "link_a" << YAML::Value << linkName(model, s.linkA);
        emitKeyedVector(out, "point_a", s.pointA);
        out << YAML::Key << "link_b" << YAML::Value << linkName(model, s.linkB);
        emitKeyedVector(out, "point_b", s.pointB);
        number("stiffness", s.stiffness);
        number("rest_length", s.restLength);
        out << YAML::EndMap;
    }
    for (const BushingForce& b : elements.bushings) {
        begin("bushing", b.name);
        emitFrame(out, model, b.frameA, "_a");
        emitFrame(out, model, b.frameB, "_b");
        emitKeyedVector(out, "rotational_stiffness", b.rotationalStiffness);
        emitKeyedVector(out, "translational_stiffness", b.translationalStiffness);
        emitKeyedVector(out, "rotational_damping", b.rotationalDamping);
        emitKeyedVector(out, "translational_damping", b.translationalDamping);
        out << YAML::EndMap;
    }
    for (const HuntCrossleyForce& h : elements.huntCrossley) {
        begin("hunt_crossley", h.name);
        number("transition_velocity", h.transitionVelocity);
        out << YAML::Key << "surfaces" << YAML::Value << YAML::BeginSeq;
        for (const HuntCrossleySurface& s : h.surfaces) {
            out << YAML::BeginMap << YAML::Key << "geometry" << YAML::Value
                << elements.contactGeometry[static_cast<std::size_t>(s.geometry)].name;
            number("stiffness", s.stiffness);
            number("dissipation", s.dissipation);
            number("static_friction", s.staticFriction);
            number("dynamic_friction", s.dynamicFriction);
            number("viscous_friction", s.viscousFriction);
            out << YAML::EndMap;
        }
        out << YAML::EndSeq << YAML::EndMap;
    }
    out << YAML::EndSeq;
}

}  // namespace sinew

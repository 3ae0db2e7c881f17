#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <limits>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/model_file.hpp"
#include "yaml_emit.hpp"
#include "yaml_force_elements.hpp"

namespace sinew {
namespace {

void emitRotation(YAML::Emitter& out, const Eigen::Matrix3d& R) {
    out << YAML::Flow << YAML::BeginSeq;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out << R(r, c);
    out << YAML::EndSeq;
}

void emitFunction(YAML::Emitter& out, const Function& f) {
    static const char* const typeNames[] = {"constant", "linear", "simm_spline", "natural_cubic_spline", "polynomial"};
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "type" << YAML::Value << typeNames[static_cast<int>(f.getType())];
    auto emitList = [&](const char* key, const std::vector<double>& values) {
        out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
        for (double v : values) out << v;
        out << YAML::EndSeq;
    };
    switch (f.getType()) {
        case Function::Type::Constant: out << YAML::Key << "value" << YAML::Value << f.getCoefficients()[0]; break;
        case Function::Type::Linear:
        case Function::Type::Polynomial: emitList("coefficients", f.getCoefficients()); break;
        case Function::Type::SimmSpline:
        case Function::Type::NaturalCubicSpline:
            emitList("x", f.getX());
            emitList("y", f.getY());
            break;
    }
    if (f.getScale() != 1) out << YAML::Key << "scale" << YAML::Value << f.getScale();
    out << YAML::EndMap;
}

void emitWrapObject(YAML::Emitter& out, const Model& model, const WrapObject& object) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << object.name << YAML::Key << "type"
        << YAML::Value << toString(object.shape) << YAML::Key << "link" << YAML::Value << linkName(model, object.link)
        << YAML::Key << "rotation" << YAML::Value;
    emitVector(out, object.xyzBodyRotation);
    out << YAML::Key << "translation" << YAML::Value;
    emitVector(out, object.p_BW);
    if (object.shape == WrapShape::Ellipsoid) {
        out << YAML::Key << "radii" << YAML::Value;
        emitVector(out, object.radii);
    } else {
        out << YAML::Key << "radius" << YAML::Value << object.radius;
    }
    if (object.shape == WrapShape::Cylinder) out << YAML::Key << "length" << YAML::Value << object.length;
    const std::string quadrant = object.quadrantSign == 0 ? "all"
                                                          : std::string(object.quadrantSign > 0 ? "+" : "-") +
                                                                static_cast<char>('x' + object.quadrantAxis);
    out << YAML::Key << "quadrant" << YAML::Value << quadrant << YAML::EndMap;
}

// A wire point with, for OpenSim's path points, its active range and its moving components.
void emitWirePoint(YAML::Emitter& out, const Model& model, const Wire& wire, int k) {
    const WirePoint& point = model.getWirePoints()[static_cast<std::size_t>(wire.firstPoint + k)];
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "link" << YAML::Value << linkName(model, point.link) << YAML::Key
        << "at" << YAML::Value;
    emitVector(out, point.p_B);
    const std::vector<std::string> coordinates = getCoordinateNames(model);
    for (const WirePointCondition& c : wire.conditions) {
        if (c.point != k) continue;
        out << YAML::Key << "active_when" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "coordinate"
            << YAML::Value << coordinates[static_cast<std::size_t>(c.q)] << YAML::Key << "range" << YAML::Value
            << YAML::Flow << YAML::BeginSeq << c.min << c.max << YAML::EndSeq << YAML::EndMap;
    }
    bool moving = false;
    for (const WirePointMotion& m : wire.motions) {
        if (m.point != k) continue;
        if (!moving) out << YAML::Key << "moving" << YAML::Value << YAML::Flow << YAML::BeginMap;
        moving = true;
        out << YAML::Key << std::string(1, static_cast<char>('x' + m.axis)) << YAML::Value << YAML::Flow << YAML::BeginMap
            << YAML::Key << "coordinate" << YAML::Value << coordinates[static_cast<std::size_t>(m.q)] << YAML::Key
            << "function" << YAML::Value;
        emitFunction(out, m.function);
        out << YAML::EndMap;
    }
    if (moving) out << YAML::EndMap;
    out << YAML::EndMap;
}

// A custom joint's coordinates and its six transform axes.
void emitCustomJoint(YAML::Emitter& out, const Model& model, const Joint& joint) {
    static const char* const axisNames[] = {"rotation1", "rotation2", "rotation3", "translation1", "translation2",
                                            "translation3"};
    const auto& coordinates = model.getCoordinates();
    auto coordinate = [&](int k) -> const Coordinate& { return coordinates[static_cast<std::size_t>(joint.qStart + k)]; };
    out << YAML::Key << "coordinates" << YAML::Value << YAML::BeginSeq;
    for (int k = 0; k < joint.nq; ++k) {
        const Coordinate& c = coordinate(k);
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << c.name << YAML::Key << "default"
            << YAML::Value << c.defaultValue;
        if (c.rangeMin != -std::numeric_limits<double>::infinity() || c.rangeMax != std::numeric_limits<double>::infinity())
            out << YAML::Key << "range" << YAML::Value << YAML::Flow << YAML::BeginSeq << c.rangeMin << c.rangeMax
                << YAML::EndSeq;
        if (c.clamped) out << YAML::Key << "clamped" << YAML::Value << true;
        if (c.locked) out << YAML::Key << "locked" << YAML::Value << true;
        out << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::Key << "transform" << YAML::Value << YAML::BeginMap;
    for (int k = 0; k < 6; ++k) {
        const TransformAxis& axis = joint.transformAxes[static_cast<std::size_t>(k)];
        out << YAML::Key << axisNames[k] << YAML::Value << YAML::BeginMap << YAML::Key << "axis" << YAML::Value;
        emitVector(out, axis.axis);
        if (axis.coordinate != kNoCoordinate) out << YAML::Key << "coordinate" << YAML::Value << coordinate(axis.coordinate).name;
        out << YAML::Key << "function" << YAML::Value;
        emitFunction(out, axis.function);
        out << YAML::EndMap;
    }
    out << YAML::EndMap;
}

Eigen::Vector3d rotationVector(const Eigen::VectorXd& q, int start) {
    const Eigen::AngleAxisd aa(Eigen::Quaterniond(q[start], q[start + 1], q[start + 2], q[start + 3]).normalized());
    return aa.angle() * aa.axis();
}

void emitLinks(YAML::Emitter& out, const Model& model) {
    out << YAML::Key << "links" << YAML::Value << YAML::BeginSeq;
    for (const Link& link : model.getLinks()) {
        if (link.isVirtual) continue;
        const Eigen::Matrix3d& I = link.inertia_Bcom;
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << link.name << YAML::Key << "mass"
            << YAML::Value << link.mass << YAML::Key << "com" << YAML::Value;
        emitVector(out, link.com_B);
        out << YAML::Key << "inertia" << YAML::Value << YAML::Flow << YAML::BeginSeq << I(0, 0) << I(1, 1) << I(2, 2)
            << I(0, 1) << I(0, 2) << I(1, 2) << YAML::EndSeq << YAML::EndMap;
    }
    out << YAML::EndSeq;
}

// The joint of link i: its frames, its initial pose from the default q, and a custom joint's axes.
void emitJoint(YAML::Emitter& out, const Model& model, int i) {
    const Eigen::VectorXd& q0 = model.getDefaultQ();
    const Joint& joint = model.getJoint(i);
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << joint.name << YAML::Key << "type" << YAML::Value
        << toString(joint.type) << YAML::Key << "parent" << YAML::Value << linkName(model, joint.parent)
        << YAML::Key << "child" << YAML::Value << model.getLink(i).name << YAML::Key << "parent_point" << YAML::Value;
    emitVector(out, joint.p_PF);
    out << YAML::Key << "child_point" << YAML::Value;
    emitVector(out, joint.p_BM);
    switch (joint.type) {
        case JointType::Pin:
            out << YAML::Key << "axis" << YAML::Value;
            emitVector(out, joint.R_PF.col(2));
            out << YAML::Key << "initial_angle" << YAML::Value << q0[joint.qStart];
            break;
        case JointType::Free:
            out << YAML::Key << "initial_position" << YAML::Value;
            emitVector(out, q0.segment<3>(joint.qStart + 4));
            [[fallthrough]];
        case JointType::Ball:
            out << YAML::Key << "initial_rotation" << YAML::Value;
            emitVector(out, rotationVector(q0, joint.qStart));
            break;
        case JointType::Weld:
        case JointType::Custom: break;
    }
    if (joint.type == JointType::Weld || joint.type == JointType::Custom) {
        if (!joint.R_PF.isIdentity(0)) {
            out << YAML::Key << "parent_orientation" << YAML::Value;
            emitRotation(out, joint.R_PF);
        }
        if (!joint.R_BM.isIdentity(0)) {
            out << YAML::Key << "child_orientation" << YAML::Value;
            emitRotation(out, joint.R_BM);
        }
    }
    if (joint.type == JointType::Custom) emitCustomJoint(out, model, joint);
    out << YAML::EndMap;
}

// Joints, virtual links (a free joint each, implied) and loops.
void emitTopology(YAML::Emitter& out, const Model& model) {
    out << YAML::Key << "joints" << YAML::Value << YAML::BeginSeq;
    for (int i = 0; i < model.getNumLinks(); ++i)
        if (!model.getLink(i).isVirtual) emitJoint(out, model, i);
    out << YAML::EndSeq;

    out << YAML::Key << "virtual_links" << YAML::Value << YAML::BeginSeq;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        if (!model.getLink(i).isVirtual) continue;
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << model.getLink(i).name << YAML::Key
            << "initial_position" << YAML::Value;
        emitVector(out, model.getDefaultQ().segment<3>(model.getJoint(i).qStart + 4));
        out << YAML::EndMap;
    }
    out << YAML::EndSeq;

    out << YAML::Key << "loops" << YAML::Value << YAML::BeginSeq;
    for (const Loop& loop : model.getLoops()) {
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << loop.name << YAML::Key << "link_a"
            << YAML::Value << linkName(model, loop.linkA) << YAML::Key << "point_a" << YAML::Value;
        emitVector(out, loop.p_A);
        out << YAML::Key << "link_b" << YAML::Value << linkName(model, loop.linkB) << YAML::Key << "point_b" << YAML::Value;
        emitVector(out, loop.p_B);
        out << YAML::EndMap;
    }
    out << YAML::EndSeq;
}

void emitCouplers(YAML::Emitter& out, const Model& model) {
    if (model.getNumCouplers() == 0) return;
    const std::vector<std::string> coordinates = getCoordinateNames(model);
    out << YAML::Key << "couplers" << YAML::Value << YAML::BeginSeq;
    for (const CoordinateCoupler& c : model.getCouplers()) {
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << c.name << YAML::Key
            << "dependent" << YAML::Value << coordinates[static_cast<std::size_t>(c.dependentQ)] << YAML::Key
            << "independent" << YAML::Value << coordinates[static_cast<std::size_t>(c.independentQ)] << YAML::Key
            << "function" << YAML::Value;
        emitFunction(out, c.function);
        if (c.scaleFactor != 1) out << YAML::Key << "scale_factor" << YAML::Value << c.scaleFactor;
        out << YAML::EndMap;
    }
    out << YAML::EndSeq;
}

void emitWireWrap(YAML::Emitter& out, const Model& model, const WireWrap& wrap) {
    const WrapObject& object = model.getWrapObjects()[static_cast<std::size_t>(wrap.object)];
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "object" << YAML::Value << object.name << YAML::Key << "range"
        << YAML::Value << YAML::Flow << YAML::BeginSeq << wrap.firstPoint << wrap.lastPoint << YAML::EndSeq
        << YAML::Key << "method" << YAML::Value << toString(wrap.method);
    if (wrap.hasSideSite) {
        out << YAML::Key << "side_site" << YAML::Value;
        emitVector(out, wrap.sideSite_B);
        if (wrap.sideSiteLink != object.link)
            out << YAML::Key << "side_site_link" << YAML::Value << linkName(model, wrap.sideSiteLink);
    }
    out << YAML::EndMap;
}

void emitWire(YAML::Emitter& out, const Model& model, const Wire& wire) {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << wire.name << YAML::Key << "kind" << YAML::Value
        << toString(wire.kind) << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
    for (int k = 0; k < wire.numPoints; ++k) emitWirePoint(out, model, wire, k);
    out << YAML::EndSeq;
    if (!wire.wraps.empty()) {
        out << YAML::Key << "wraps" << YAML::Value << YAML::BeginSeq;
        for (const WireWrap& wrap : wire.wraps) emitWireWrap(out, model, wrap);
        out << YAML::EndSeq;
    }
    out << YAML::Key << "force_law" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "type" << YAML::Value
        << wire.lawSpec.type;
    for (const auto& [name, values] : wire.lawSpec.parameters.getAll()) {
        out << YAML::Key << name << YAML::Value;
        if (values.size() == 1) {
            out << values[0];
        } else {
            out << YAML::Flow << YAML::BeginSeq;
            for (double v : values) out << v;
            out << YAML::EndSeq;
        }
    }
    out << YAML::EndMap;
    if (wire.strength) out << YAML::Key << "strength" << YAML::Value << *wire.strength;
    if (wire.crossSection) out << YAML::Key << "cross_section" << YAML::Value << *wire.crossSection;
    out << YAML::EndMap;
}

// Written only when the model names feet, so models without them keep their files byte for byte.
void emitContacts(YAML::Emitter& out, const Model& model) {
    if (model.getContacts().empty()) return;
    out << YAML::Key << "contacts" << YAML::Value << YAML::BeginSeq;
    for (const Contact& contact : model.getContacts()) {
        out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << contact.name << YAML::Key << "link" << YAML::Value
            << linkName(model, contact.link) << YAML::Key << "friction" << YAML::Value << contact.friction << YAML::Key
            << "sole" << YAML::Value << YAML::BeginSeq;
        for (const Eigen::Vector3d& vertex : contact.sole_B) emitVector(out, vertex);
        out << YAML::EndSeq << YAML::EndMap;
    }
    out << YAML::EndSeq;
}

}  // namespace

std::string writeModelText(const Model& model) {
    YAML::Emitter out;
    out.SetDoublePrecision(17);
    out << YAML::BeginMap << YAML::Key << "sinew_model" << YAML::Value << kModelFormatVersion;
    out << YAML::Key << "name" << YAML::Value << model.getName();
    out << YAML::Key << "gravity" << YAML::Value;
    emitVector(out, model.getGravity());
    emitLinks(out, model);
    emitTopology(out, model);
    emitCouplers(out, model);
    out << YAML::Key << "wrap_objects" << YAML::Value << YAML::BeginSeq;
    for (const WrapObject& object : model.getWrapObjects()) emitWrapObject(out, model, object);
    out << YAML::EndSeq;
    out << YAML::Key << "wires" << YAML::Value << YAML::BeginSeq;
    for (const Wire& wire : model.getWires()) emitWire(out, model, wire);
    out << YAML::EndSeq;
    emitContacts(out, model);
    emitForceElements(out, model);
    out << YAML::EndMap;
    return std::string(out.c_str()) + "\n";
}

void writeModelFile(const Model& model, const std::string& path) { writeFileAtomically(path, writeModelText(model)); }

}  // namespace sinew

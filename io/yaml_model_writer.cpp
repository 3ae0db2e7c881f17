#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <fstream>

#include "sinew/core/error.hpp"
#include "sinew/io/model_file.hpp"

namespace sinew {
namespace {

void emitVector(YAML::Emitter& out, const Eigen::Vector3d& v) {
    out << YAML::Flow << YAML::BeginSeq << v[0] << v[1] << v[2] << YAML::EndSeq;
}

std::string linkName(const Model& model, int link) { return link == kGround ? "ground" : model.getLink(link).name; }

Eigen::Vector3d rotationVector(const Eigen::VectorXd& q, int start) {
    const Eigen::AngleAxisd aa(Eigen::Quaterniond(q[start], q[start + 1], q[start + 2], q[start + 3]).normalized());
    return aa.angle() * aa.axis();
}

}  // namespace

std::string writeModelText(const Model& model) {
    const Eigen::VectorXd& q0 = model.getDefaultQ();
    YAML::Emitter out;
    out.SetDoublePrecision(17);
    out << YAML::BeginMap << YAML::Key << "sinew_model" << YAML::Value << kModelFormatVersion;
    out << YAML::Key << "name" << YAML::Value << model.getName();
    out << YAML::Key << "gravity" << YAML::Value;
    emitVector(out, model.getGravity());

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

    out << YAML::Key << "joints" << YAML::Value << YAML::BeginSeq;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        if (model.getLink(i).isVirtual) continue;
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
            case JointType::Weld: break;
        }
        out << YAML::EndMap;
    }
    out << YAML::EndSeq;

    out << YAML::Key << "virtual_links" << YAML::Value << YAML::BeginSeq;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        if (!model.getLink(i).isVirtual) continue;
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << model.getLink(i).name << YAML::Key
            << "initial_position" << YAML::Value;
        emitVector(out, q0.segment<3>(model.getJoint(i).qStart + 4));
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

    out << YAML::Key << "wires" << YAML::Value << YAML::BeginSeq;
    for (const Wire& wire : model.getWires()) {
        out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << wire.name << YAML::Key << "kind" << YAML::Value
            << toString(wire.kind) << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const WirePoint& point = model.getWirePoints()[static_cast<std::size_t>(k)];
            out << YAML::Flow << YAML::BeginMap << YAML::Key << "link" << YAML::Value << linkName(model, point.link)
                << YAML::Key << "at" << YAML::Value;
            emitVector(out, point.p_B);
            out << YAML::EndMap;
        }
        out << YAML::EndSeq << YAML::Key << "force_law" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key
            << "type" << YAML::Value << wire.lawSpec.type;
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
        out << YAML::EndMap << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::EndMap;
    return std::string(out.c_str()) + "\n";
}

void writeModelFile(const Model& model, const std::string& path) {
    std::ofstream file(path);
    if (!file) throw Error(path + ": cannot open for writing");
    file << writeModelText(model);
    if (!file) throw Error(path + ": write failed");
}

}  // namespace sinew

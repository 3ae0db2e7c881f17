#include "sinew/core/model.hpp"

namespace sinew {

const char* toString(JointType type) {
    switch (type) {
        case JointType::Free: return "free";
        case JointType::Ball: return "ball";
        case JointType::Pin: return "pin";
        case JointType::Weld: return "weld";
    }
    return "?";
}

const char* toString(WireKind kind) {
    switch (kind) {
        case WireKind::Muscle: return "muscle";
        case WireKind::Tendon: return "tendon";
        case WireKind::Ligament: return "ligament";
        case WireKind::Cartilage: return "cartilage";
    }
    return "?";
}

int getNumQ(JointType type) {
    switch (type) {
        case JointType::Free: return 7;
        case JointType::Ball: return 4;
        case JointType::Pin: return 1;
        case JointType::Weld: return 0;
    }
    return 0;
}

int getNumU(JointType type) {
    switch (type) {
        case JointType::Free: return 6;
        case JointType::Ball: return 3;
        case JointType::Pin: return 1;
        case JointType::Weld: return 0;
    }
    return 0;
}

int Model::findLinkIndex(const std::string& name) const {
    if (name == "ground") return kGround;
    for (std::size_t i = 0; i < links_.size(); ++i)
        if (links_[i].name == name) return static_cast<int>(i);
    return kNotFound;
}

int Model::findWireIndex(const std::string& name) const {
    for (std::size_t i = 0; i < wires_.size(); ++i)
        if (wires_[i].name == name) return static_cast<int>(i);
    return kNotFound;
}

namespace {

std::vector<std::string> suffixedNames(const Model& model, bool speeds) {
    static const std::vector<std::string> quaternion{"_qw", "_qx", "_qy", "_qz"}, position{"_x", "_y", "_z"},
        angular{"_wx", "_wy", "_wz"}, linear{"_vx", "_vy", "_vz"};
    std::vector<std::string> names;
    for (const Joint& joint : model.getJoints()) {
        std::vector<std::string> suffixes;
        if (joint.type == JointType::Free || joint.type == JointType::Ball)
            suffixes = speeds ? angular : quaternion;
        if (joint.type == JointType::Free)
            suffixes.insert(suffixes.end(), (speeds ? linear : position).begin(), (speeds ? linear : position).end());
        if (joint.type == JointType::Pin) suffixes = {""};
        for (const std::string& suffix : suffixes) names.push_back(joint.name + suffix);
    }
    return names;
}

}  // namespace

std::vector<std::string> getCoordinateNames(const Model& model) { return suffixedNames(model, false); }
std::vector<std::string> getSpeedNames(const Model& model) { return suffixedNames(model, true); }

}  // namespace sinew

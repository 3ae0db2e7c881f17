#include "sinew/core/model.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

const char* toString(JointType type) {
    switch (type) {
        case JointType::Free: return "free";
        case JointType::Ball: return "ball";
        case JointType::Pin: return "pin";
        case JointType::Weld: return "weld";
        case JointType::Custom: return "custom";
    }
    return "?";
}

const char* toString(MotionType type) {
    switch (type) {
        case MotionType::Rotational: return "rotational";
        case MotionType::Translational: return "translational";
        case MotionType::Coupled: return "coupled";
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

const char* toString(WrapShape shape) {
    switch (shape) {
        case WrapShape::Sphere: return "sphere";
        case WrapShape::Cylinder: return "cylinder";
        case WrapShape::Ellipsoid: return "ellipsoid";
    }
    return "?";
}

const char* toString(WrapMethod method) {
    switch (method) {
        case WrapMethod::Hybrid: return "hybrid";
        case WrapMethod::Midpoint: return "midpoint";
        case WrapMethod::Axial: return "axial";
        case WrapMethod::MuJoCo: return "mujoco";
    }
    return "?";
}

std::optional<double> getWireStrength(const Wire& wire) {
    if (wire.strength) return wire.strength;
    return wire.law->getMaxIsometricForce();
}

int getNumQ(JointType type) {
    switch (type) {
        case JointType::Free: return 7;
        case JointType::Ball: return 4;
        case JointType::Pin: return 1;
        case JointType::Weld: return 0;
        case JointType::Custom: break;
    }
    throw Error("getNumQ: a custom joint has as many coordinates as it declares (see Joint::nq)");
}

int getNumU(JointType type) {
    switch (type) {
        case JointType::Free: return 6;
        case JointType::Ball: return 3;
        case JointType::Pin: return 1;
        case JointType::Weld: return 0;
        case JointType::Custom: break;
    }
    throw Error("getNumU: a custom joint has as many speeds as coordinates (see Joint::nu)");
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

std::vector<int> Model::getSupportLinks(const Wire& wire) const {
    const auto first = supportLinks_.begin() + wire.firstSupportLink;
    return {first, first + wire.numSupportLinks};
}

int Model::findCoordinateIndex(const std::string& name) const {
    for (std::size_t i = 0; i < coordinates_.size(); ++i)
        if (coordinates_[i].name == name) return static_cast<int>(i);
    return kNotFound;
}

std::vector<std::string> getCoordinateNames(const Model& model) {
    std::vector<std::string> names;
    for (const Coordinate& coordinate : model.getCoordinates()) names.push_back(coordinate.name);
    return names;
}

// Quaternion joints have fewer speeds than coordinates and name them for the axes; the others have one
// speed per coordinate, named as it.
std::vector<std::string> getSpeedNames(const Model& model) {
    static const char* const angular[] = {"_wx", "_wy", "_wz"};
    static const char* const linear[] = {"_vx", "_vy", "_vz"};
    std::vector<std::string> names;
    for (const Joint& joint : model.getJoints()) {
        if (joint.type == JointType::Free || joint.type == JointType::Ball) {
            for (const char* suffix : angular) names.push_back(joint.name + suffix);
            if (joint.type == JointType::Free)
                for (const char* suffix : linear) names.push_back(joint.name + suffix);
        } else {
            for (int k = 0; k < joint.nq; ++k)
                names.push_back(model.getCoordinates()[static_cast<std::size_t>(joint.qStart + k)].name);
        }
    }
    return names;
}

}  // namespace sinew

#include "sinew/tools/model_scaling.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"

namespace sinew {
namespace {

// The model is scaled in its own description (io/yaml_model_writer.cpp, docs/model-format.md), which holds
// every element with the lengths in its link's frame, and built again by the reader that validates it:
// no second copy of ModelBuilder's element list to keep in step with the model format.
class ScaledDescription {
public:
    ScaledDescription(const Model& model, const std::vector<double>& factors) : model_(model) {
        // A virtual link's points are in its own frame, which follows the wires, not a segment.
        for (int i = 0; i < model.getNumLinks(); ++i)
            factorOf_[model.getLink(i).name] = model.getLink(i).isVirtual ? 1 : factors[static_cast<std::size_t>(i)];
        factorOf_["ground"] = 1;
    }

    // The model with its lengths scaled; virtual links at `virtualPositions` (m, ground; by link name) where
    // given, force-law lengths times `wireRatio` (per wire) where given.
    Model build(const std::map<std::string, Eigen::Vector3d>& virtualPositions, const Eigen::VectorXd& wireRatio) const {
        YAML::Node root = YAML::Load(writeModelText(model_));
        scaleLinks(root["links"]);
        scaleJoints(root["joints"]);
        for (YAML::Node link : root["virtual_links"])
            if (const auto found = virtualPositions.find(link["name"].Scalar()); found != virtualPositions.end())
                for (std::size_t k = 0; k < 3; ++k) link["initial_position"][k] = found->second[static_cast<Eigen::Index>(k)];
        for (YAML::Node loop : root["loops"]) {
            scale(loop["point_a"], factor(loop["link_a"]));
            scale(loop["point_b"], factor(loop["link_b"]));
        }
        std::map<std::string, std::string> objectLink;
        for (YAML::Node object : root["wrap_objects"]) {
            const double s = factor(object["link"]);
            objectLink[object["name"].Scalar()] = object["link"].Scalar();
            for (const char* key : {"translation", "radius", "length", "radii"})
                if (object[key]) scale(object[key], s);
        }
        scaleWires(root["wires"], objectLink, wireRatio);
        if (root["contacts"])
            for (YAML::Node contact : root["contacts"])
                for (YAML::Node vertex : contact["sole"]) scale(vertex, factor(contact["link"]));
        YAML::Emitter out;
        out.SetDoublePrecision(17);
        out << root;
        return readModelText(out.c_str(), model_.getName() + " (scaled)");
    }

private:
    double factor(const YAML::Node& linkName) const { return factorOf_.at(linkName.Scalar()); }

    // A number or a vector of them, times s.
    static void scale(YAML::Node node, double s) {
        if (node.IsScalar()) {
            node = s * node.as<double>();
            return;
        }
        for (std::size_t k = 0; k < node.size(); ++k) node[k] = s * node[k].as<double>();
    }

    void scaleLinks(YAML::Node links) const {
        for (YAML::Node link : links) {
            const double s = factor(link["name"]);
            scale(link["com"], s);
            scale(link["inertia"], s * s);  // mass kept: a uniformly stretched body's inertia grows as s^2
        }
    }

    void scaleJoints(YAML::Node joints) const {
        for (YAML::Node joint : joints) {
            const double child = factor(joint["child"]);
            scale(joint["parent_point"], factor(joint["parent"]));
            scale(joint["child_point"], child);
            if (joint["initial_position"]) scale(joint["initial_position"], child);
            if (!joint["transform"]) continue;
            for (const char* axis : {"translation1", "translation2", "translation3"}) {
                const YAML::Node function = joint["transform"][axis]["function"];
                const bool none = !joint["transform"][axis]["coordinate"] && function["type"].Scalar() == "constant" &&
                                  function["value"].as<double>() == 0;
                if (!none)
                    throw Error("model '" + model_.getName() + "', joint '" + joint["name"].Scalar() +
                                "': a custom joint's translation is a function of its coordinates; scaling it is not supported");
            }
        }
    }

    void scaleWires(YAML::Node wires, const std::map<std::string, std::string>& objectLink,
                    const Eigen::VectorXd& wireRatio) const {
        Eigen::Index w = 0;
        for (YAML::Node wire : wires) {
            for (YAML::Node point : wire["points"]) {
                if (point["moving"])
                    throw Error("model '" + model_.getName() + "', wire '" + wire["name"].Scalar() +
                                "': a moving point's position is a function of a coordinate; scaling it is not supported");
                scale(point["at"], factor(point["link"]));
            }
            for (YAML::Node wrap : wire["wraps"]) {
                if (!wrap["side_site"]) continue;
                const std::string link = wrap["side_site_link"] ? wrap["side_site_link"].Scalar()
                                                                : objectLink.at(wrap["object"].Scalar());
                scale(wrap["side_site"], factorOf_.at(link));
            }
            if (wireRatio.size() > 0)
                for (auto parameter : wire["force_law"]) {
                    const std::string name = parameter.first.Scalar();
                    if (name.size() > 7 && name.compare(name.size() - 7, 7, "_length") == 0)
                        scale(parameter.second, wireRatio[w]);
                }
            ++w;
        }
    }

    const Model& model_;
    std::map<std::string, double> factorOf_;
};

// Each virtual link's default position carried over from `model` to `scaled`: fixed in the frame of the
// link of the nearest wire point next to it on any wire, that frame's offset scaled by the link's factor.
std::map<std::string, Eigen::Vector3d> placeVirtualLinks(const Model& model, const Model& scaled,
                                                         const std::vector<double>& factors) {
    Data data(model), scaledData(scaled);
    calcPositionKinematics(model, data, model.getDefaultQ());
    calcPositionKinematics(scaled, scaledData, scaled.getDefaultQ());
    const std::vector<WirePoint>& points = model.getWirePoints();
    auto location = [&](const WirePoint& p) {
        const std::size_t b = static_cast<std::size_t>(p.link);
        return Eigen::Vector3d(data.p_GB[b] + data.R_GB[b] * p.p_B);
    };
    std::map<std::string, Eigen::Vector3d> placed;
    for (int v = 0; v < model.getNumLinks(); ++v) {
        if (!model.getLink(v).isVirtual) continue;
        const Eigen::Vector3d p_GV = data.p_GB[static_cast<std::size_t>(v)];
        double nearest = std::numeric_limits<double>::infinity();
        int anchor = -1;
        for (const Wire& wire : model.getWires())
            for (int k = 0; k < wire.numPoints; ++k) {
                if (points[static_cast<std::size_t>(wire.firstPoint + k)].link != v) continue;
                for (int n : {k - 1, k + 1}) {
                    if (n < 0 || n >= wire.numPoints) continue;
                    const WirePoint& next = points[static_cast<std::size_t>(wire.firstPoint + n)];
                    if (next.link == kGround || model.getLink(next.link).isVirtual) continue;
                    if ((location(next) - p_GV).norm() < nearest) {
                        nearest = (location(next) - p_GV).norm();
                        anchor = next.link;
                    }
                }
            }
        if (anchor < 0) continue;  // on no wire beside a link: left where it was
        const std::size_t a = static_cast<std::size_t>(anchor);
        const Eigen::Vector3d p_A = data.R_GB[a].transpose() * (p_GV - data.p_GB[a]);
        placed[model.getLink(v).name] = scaledData.p_GB[a] + scaledData.R_GB[a] * (factors[a] * p_A);
    }
    return placed;
}

Eigen::VectorXd calcDefaultWireLengths(const Model& model) {
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    calcWirePaths(model, data);
    return data.wireLength;
}

}  // namespace

Model scaleModel(const Model& model, const std::vector<double>& factors) {
    if (factors.size() != static_cast<std::size_t>(model.getNumLinks()))
        throw Error("scaling model '" + model.getName() + "': " + std::to_string(factors.size()) + " factors for " +
                    std::to_string(model.getNumLinks()) + " links");
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const double s = factors[static_cast<std::size_t>(i)];
        if (!model.getLink(i).isVirtual && !(std::isfinite(s) && s > 0))
            throw Error("scaling model '" + model.getName() + "': link '" + model.getLink(i).name +
                        "' has factor " + std::to_string(s) + "; factors must be finite and > 0");
    }
    const ScaledDescription description(model, factors);
    // Three builds: the geometry, to place the virtual links on; with them, to measure the wires; the last
    // with the force laws' lengths following the wires'.
    const Model geometry = description.build({}, Eigen::VectorXd());
    const std::map<std::string, Eigen::Vector3d> virtualPositions = placeVirtualLinks(model, geometry, factors);
    const Model placed = virtualPositions.empty() ? geometry : description.build(virtualPositions, Eigen::VectorXd());
    if (model.getWires().empty()) return placed;
    const Eigen::VectorXd ratio = calcDefaultWireLengths(placed).cwiseQuotient(calcDefaultWireLengths(model));
    return description.build(virtualPositions, ratio);
}

}  // namespace sinew

#pragma once
// Builds a validated, immutable Model from element descriptions that refer to each other by name. Every
// element carries `where` (e.g. "arm.yaml:14"), which prefixes the ModelError it causes.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

struct LinkSpec {
    std::string name;
    double mass = 0;                                         // kg
    Eigen::Vector3d com_B = Eigen::Vector3d::Zero();         // m
    Eigen::Matrix3d inertia_Bcom = Eigen::Matrix3d::Zero();  // kg m^2 about the centre of mass
    std::string where;
};

struct JointSpec {
    std::string name;
    JointType type = JointType::Ball;
    std::string parent;  // link name or "ground"
    std::string child;
    Eigen::Vector3d p_PF = Eigen::Vector3d::Zero();  // m, joint centre in the parent frame
    Eigen::Vector3d p_BM = Eigen::Vector3d::Zero();  // m, joint centre in the child frame
    std::optional<Eigen::Vector3d> axis;             // pin only: rotation axis, in the parent (and child) frame
    // Initial pose: rotation vector (rad, in F; ball and free), angle (rad; pin), position of M in F (m; free).
    std::optional<Eigen::Vector3d> initialRotation;
    std::optional<double> initialAngle;
    std::optional<Eigen::Vector3d> initialPosition;
    std::string where;
};

struct VirtualLinkSpec {
    std::string name;
    Eigen::Vector3d initialPosition = Eigen::Vector3d::Zero();  // m, in ground
    std::string where;
};

struct LoopSpec {
    std::string name;
    std::string linkA;
    Eigen::Vector3d p_A = Eigen::Vector3d::Zero();
    std::string linkB;
    Eigen::Vector3d p_B = Eigen::Vector3d::Zero();
    std::string where;
};

struct WirePointSpec {
    std::string link;
    Eigen::Vector3d p_B = Eigen::Vector3d::Zero();
    std::string where;
};

struct WireSpec {
    std::string name;
    WireKind kind = WireKind::Muscle;
    std::vector<WirePointSpec> points;
    ForceLawSpec law;
    std::string where;
    std::string lawWhere;  // where the force law is written, for its errors; `where` when empty
};

class ModelBuilder {
public:
    explicit ModelBuilder(std::string modelName) : name_(std::move(modelName)) {}

    void setGravity(const Eigen::Vector3d& gravity, std::string where = {});
    void addLink(LinkSpec link) { links_.push_back(std::move(link)); }
    void addJoint(JointSpec joint) { joints_.push_back(std::move(joint)); }
    void addVirtualLink(VirtualLinkSpec link) { virtualLinks_.push_back(std::move(link)); }
    void addLoop(LoopSpec loop) { loops_.push_back(std::move(loop)); }
    void addWire(WireSpec wire) { wires_.push_back(std::move(wire)); }

    // Validates everything and builds the model; throws ModelError naming the offending element's `where`.
    Model build() const;

private:
    std::string name_;
    Eigen::Vector3d gravity_ = Eigen::Vector3d(0, -9.80665, 0);
    std::string gravityWhere_;
    std::vector<LinkSpec> links_;
    std::vector<JointSpec> joints_;
    std::vector<VirtualLinkSpec> virtualLinks_;
    std::vector<LoopSpec> loops_;
    std::vector<WireSpec> wires_;
};

}  // namespace sinew

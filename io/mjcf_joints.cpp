#include "mjcf_joints.hpp"

#include <algorithm>
#include <sstream>

#include "sinew/core/error.hpp"

namespace sinew::mjcf {
namespace {

constexpr double kCollinear = 1e-5;  // |a x b| of unit axes below which sinew's custom joint refuses them

bool areCollinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.cross(b).norm() < kCollinear; }

// Whether joint `joint` is the dependent joint (joint1) of an active joint equality with a second joint: a
// coupler in sinew.
bool isCoupledJoint(const MjcfModel& model, const std::string& joint) {
    for (const MjcfEquality& e : model.equalities)
        if (e.tag == "joint" && e.active && e.name1 == joint && !e.name2.empty()) return true;
    return false;
}

// A slide along the axis of an earlier slide of the same body that no equality couples to another joint:
// collinear slides add up, but two free ones would make the joint's inertia singular, so sinew keeps only
// the first of them as a coordinate. Coupled ones (MS-Human-700's knee translations) stay coordinates.
bool isHeldSlide(const MjcfModel& model, const MjcfBody& body, std::size_t j) {
    if (body.joints[j].type != JointKind::Slide || isCoupledJoint(model, body.joints[j].name)) return false;
    for (std::size_t k = 0; k < j; ++k)
        if (body.joints[k].type == JointKind::Slide && areCollinear(body.joints[k].axis, body.joints[j].axis))
            return true;
    return false;
}

[[noreturn]] void failBody(const MjcfBody& body, const std::string& message) {
    throw ModelError(body.where, "body '" + body.name + "': " + message);
}

Eigen::Vector3d toRotationVector(const Eigen::Quaterniond& q) {
    const Eigen::AngleAxisd angleAxis(q.normalized());
    return angleAxis.angle() * angleAxis.axis();
}

// Axes completing `used` (unit; rotations pairwise independent, translations possibly collinear) to three,
// for the custom joint's slots without a coordinate: each new axis is independent of all before it.
std::vector<Eigen::Vector3d> completeAxes(std::vector<Eigen::Vector3d> used) {
    std::vector<Eigen::Vector3d> independent;
    for (const Eigen::Vector3d& a : used)
        if (std::none_of(independent.begin(), independent.end(), [&](const Eigen::Vector3d& b) { return areCollinear(a, b); }))
            independent.push_back(a);
    while (used.size() < 3) {
        Eigen::Vector3d next;
        if (independent.empty()) {
            next = Eigen::Vector3d::Unit(static_cast<Eigen::Index>(used.size()));
        } else if (independent.size() == 1) {
            Eigen::Index least = 0;
            independent[0].cwiseAbs().minCoeff(&least);
            next = independent[0].cross(Eigen::Vector3d::Unit(least)).normalized();
        } else {
            next = independent[0].cross(independent[1]).normalized();
        }
        used.push_back(next);
        independent.push_back(next);
    }
    return used;
}

// Slides first, then hinges about one anchor, at most three of each (docs/mjcf-import.md).
void checkCustomLayout(const MjcfModel& model, const MjcfBody& body) {
    int hinges = 0, slides = 0;
    const MjcfJoint* firstHinge = nullptr;
    for (std::size_t j = 0; j < body.joints.size(); ++j) {
        const MjcfJoint& joint = body.joints[j];
        if (joint.type == JointKind::Ball || joint.type == JointKind::Free)
            failBody(body, "joint '" + joint.name + "' (" + joint.where + "): a ball or free joint must be the body's "
                           "only joint in sinew");
        if (joint.type == JointKind::Slide && firstHinge)
            failBody(body, "slide '" + joint.name + "' (" + joint.where + ") follows hinge '" + firstHinge->name +
                           "'; sinew's custom joint translates, then rotates: put the body's slides before its hinges");
        if (joint.type == JointKind::Hinge) {
            if (firstHinge && (joint.pos - firstHinge->pos).norm() > 1e-12)
                failBody(body, "hinges '" + firstHinge->name + "' and '" + joint.name + "' (" + joint.where +
                               ") turn about different anchors (pos); sinew's custom joint has one centre");
            for (std::size_t k = 0; k < j; ++k)
                if (body.joints[k].type == JointKind::Hinge && areCollinear(body.joints[k].axis, joint.axis))
                    failBody(body, "hinges '" + body.joints[k].name + "' and '" + joint.name + "' (" + joint.where +
                                   ") turn about collinear axes; sinew's custom joint needs independent rotation axes");
            if (!firstHinge) firstHinge = &joint;
            ++hinges;
        } else if (!isHeldSlide(model, body, j)) {
            ++slides;
        }
    }
    if (hinges > 3 || slides > 3)
        failBody(body, std::to_string(hinges) + " hinges and " + std::to_string(slides) +
                       " slides (beyond those held at their ref); sinew's custom joint takes at most three of each");
}

// The transform axes of one kind (rotations: hinges; translations: slides) in joint order, completed by
// constant axes. A coordinate equals MuJoCo's qpos: the displacement is qpos - ref.
void addTransformAxes(const MjcfModel& model, const MjcfBody& body, JointKind kind, JointSpec& spec) {
    std::vector<Eigen::Vector3d> axes;
    std::vector<const MjcfJoint*> joints;
    for (std::size_t j = 0; j < body.joints.size(); ++j)
        if (body.joints[j].type == kind && !isHeldSlide(model, body, j)) {
            axes.push_back(body.joints[j].axis);
            joints.push_back(&body.joints[j]);
        }
    axes = completeAxes(axes);
    for (std::size_t k = 0; k < 3; ++k) {
        TransformAxisSpec axis;
        axis.axis = axes[k];
        if (k < joints.size()) {
            axis.coordinate = joints[k]->name;
            axis.function = Function::linear(1, -joints[k]->ref);
        } else {
            axis.function = Function::constant(0);
        }
        spec.transformAxes.push_back(axis);
    }
}

CoordinateSpec convertCoordinate(const MjcfJoint& joint) {
    CoordinateSpec c;
    c.name = joint.name;
    c.defaultValue = joint.ref;
    if (joint.limited) {
        c.rangeMin = joint.rangeMin;
        c.rangeMax = joint.rangeMax;
    }
    c.where = joint.where;
    return c;
}

void convertCustomJoint(const MjcfModel& model, const MjcfBody& body, JointSpec& spec) {
    checkCustomLayout(model, body);
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
    for (const MjcfJoint& joint : body.joints)
        if (joint.type == JointKind::Hinge) {
            anchor = joint.pos;
            break;
        }
    spec.type = JointType::Custom;
    spec.p_PF = body.pos + body.quat * anchor;
    spec.R_PF = body.quat.toRotationMatrix();
    spec.p_BM = anchor;
    spec.R_BM = Eigen::Matrix3d::Identity();
    addTransformAxes(model, body, JointKind::Hinge, spec);
    addTransformAxes(model, body, JointKind::Slide, spec);
    for (std::size_t j = 0; j < body.joints.size(); ++j)
        if (!isHeldSlide(model, body, j)) spec.coordinates.push_back(convertCoordinate(body.joints[j]));
}

void notePassiveProperties(const MjcfJoint& joint, std::vector<std::string>& notImported) {
    std::ostringstream dropped;
    const std::pair<const char*, double> properties[] = {{"stiffness", joint.stiffness}, {"damping", joint.damping},
                                                         {"armature", joint.armature}, {"frictionloss", joint.frictionloss}};
    for (const auto& [name, value] : properties)
        if (value != 0) dropped << (dropped.tellp() > 0 ? ", " : "") << name << " " << value;
    if (dropped.tellp() > 0)
        notImported.push_back(describeAt("joint", joint.name, joint.where) + ": " + dropped.str() +
                              ": sinew's joints carry no passive forces");
}

}  // namespace

std::string getLinkName(const MjcfModel& model, int body) {
    return body == 0 ? std::string(kWorldLink) : model.bodies[static_cast<std::size_t>(body)].name;
}

JointSpec convertBodyJoints(const MjcfModel& model, int body, std::vector<std::string>& notImported) {
    const MjcfBody& b = model.bodies[static_cast<std::size_t>(body)];
    JointSpec spec;
    spec.name = b.name;
    spec.parent = b.parent == 0 ? std::string("ground") : getLinkName(model, b.parent);
    spec.child = b.name;
    spec.where = b.where;
    const bool single = b.joints.size() == 1;
    if (b.joints.empty()) {
        spec.type = JointType::Weld;
        spec.p_PF = b.pos;
        spec.R_PF = b.quat.toRotationMatrix();
        if (b.mocap) notImported.push_back(describeAt("body", b.name, b.where) + ": mocap: welded at its pose");
    } else if (single && b.joints[0].type == JointKind::Free) {
        if (b.parent != 0) failBody(b, "a free joint must be on a child of the world body");
        spec.type = JointType::Free;
        spec.name = b.joints[0].name;
        spec.initialRotation = toRotationVector(b.quat);
        spec.initialPosition = b.pos;
    } else if (single && b.joints[0].type == JointKind::Ball) {
        // sinew's ball turns M from F, both aligned with their links: its quaternion is the body's quat
        // times MuJoCo's qpos, so qpos0 (identity) is the body's quat.
        spec.type = JointType::Ball;
        spec.name = b.joints[0].name;
        spec.p_PF = b.pos + b.quat * b.joints[0].pos;
        spec.p_BM = b.joints[0].pos;
        spec.initialRotation = toRotationVector(b.quat);
        if (b.joints[0].limited)
            notImported.push_back(describeAt("joint", b.joints[0].name, b.joints[0].where) +
                                  ": the ball's cone limit: sinew's ball joints have no range");
    } else {
        convertCustomJoint(model, b, spec);
    }
    for (std::size_t j = 0; j < b.joints.size(); ++j) {
        if (isHeldSlide(model, b, j))
            notImported.push_back(describeAt("joint", b.joints[j].name, b.joints[j].where) +
                                  ": a slide along the axis of an earlier slide of body '" + b.name +
                                  "' that no joint equality couples; sinew keeps one free coordinate per "
                                  "translation axis, so it stays at its ref (" + formatNumber(b.joints[j].ref) + " m)");
        notePassiveProperties(b.joints[j], notImported);
    }
    return spec;
}

std::vector<Eigen::Isometry3d> calcRestPoses(const MjcfModel& model) {
    std::vector<Eigen::Isometry3d> poses(model.bodies.size(), Eigen::Isometry3d::Identity());
    for (std::size_t b = 1; b < model.bodies.size(); ++b) {
        const MjcfBody& body = model.bodies[b];
        Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
        local.translate(body.pos);
        local.rotate(body.quat);
        poses[b] = poses[static_cast<std::size_t>(body.parent)] * local;
    }
    return poses;
}

bool isImportedJoint(const MjcfModel& model, int body, int joint) {
    return !isHeldSlide(model, model.bodies[static_cast<std::size_t>(body)], static_cast<std::size_t>(joint));
}

}  // namespace sinew::mjcf

#include "sinew/io/mjcf_model_writer.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <sstream>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/io/atomic_file.hpp"

namespace sinew {
namespace {

// The joint's R_FM and p_FM at q, as sinew's kinematics computes them (custom joints are refused before).
struct JointTransform {
    Eigen::Matrix3d R_FM;
    Eigen::Vector3d p_FM;
};

JointTransform calcTransform(const Joint& joint, const Eigen::VectorXd& q) {
    JointTransform X;
    JointMotion unusedH_FM;
    calcJointTransform(joint, q, X.R_FM, X.p_FM, unusedH_FM);
    return X;
}

// A point or direction of link B's frame in its MuJoCo body's frame, which is B's joint frame M.
Eigen::Vector3d toBodyFrame(const Joint& joint, const Eigen::Vector3d& p_B) { return joint.R_BM.transpose() * (p_B - joint.p_BM); }

}  // namespace

void requireMjcfWritable(const Model& model) {
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Joint& joint = model.getJoint(i);
        const std::string where = "cannot write MJCF: link '" + model.getLink(i).name + "'";
        if (joint.type == JointType::Custom)
            throw Error(where + " has a custom joint; MJCF's joints are free, ball, hinge and slide, one body each");
        if (joint.type == JointType::Free && joint.parent != kGround)
            throw Error(where + " has a free joint below the root; MuJoCo allows free joints only on the world's children");
        if (joint.type != JointType::Weld && !(model.getLink(i).mass > 0))
            throw Error(where + (model.getLink(i).isVirtual ? " is a virtual link" : " has no mass") +
                        "; MuJoCo needs mass on every body a joint moves");
    }
    if (!model.getCouplers().empty())
        throw Error("cannot write MJCF: coupler '" + model.getCouplers().front().name + "' (coordinate couplers are not written)");
    for (const Wire& wire : model.getWires())
        if (!wire.isPolyline())
            throw Error("cannot write MJCF: wire '" + wire.name +
                        "' wraps or has conditional or moving points; only polyline wires are written");
}

namespace {

std::string formatNumber(double x) {
    std::ostringstream out;
    out.precision(17);
    out << x;
    return out.str();
}

std::string formatVector(const Eigen::Vector3d& v) {
    return formatNumber(v.x()) + " " + formatNumber(v.y()) + " " + formatNumber(v.z());
}

std::string formatQuaternion(const Eigen::Matrix3d& R) {
    const Eigen::Quaterniond quaternion(R);
    return formatNumber(quaternion.w()) + " " + formatNumber(quaternion.x()) + " " + formatNumber(quaternion.y()) + " " +
           formatNumber(quaternion.z());
}

std::string escapeXml(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

// Each link's children, ground's first (index parent + 1), in link order: the order bodies are written in.
std::vector<std::vector<int>> findChildren(const Model& model) {
    std::vector<std::vector<int>> children(static_cast<std::size_t>(model.getNumLinks() + 1));
    for (int i = 0; i < model.getNumLinks(); ++i) children[static_cast<std::size_t>(model.getJoint(i).parent + 1)].push_back(i);
    return children;
}

// The links in MuJoCo's body order: the document's, depth first. MuJoCo lays out qpos and qvel in it.
std::vector<int> findBodyOrder(const Model& model) {
    const std::vector<std::vector<int>> children = findChildren(model);
    std::vector<int> order, stack(children[0].rbegin(), children[0].rend());
    while (!stack.empty()) {
        const int link = stack.back();
        stack.pop_back();
        order.push_back(link);
        const std::vector<int>& next = children[static_cast<std::size_t>(link + 1)];
        stack.insert(stack.end(), next.rbegin(), next.rend());
    }
    return order;
}

std::string siteName(const Wire& wire, int point) { return escapeXml(wire.name) + "_p" + std::to_string(point); }

class BodyWriter {
public:
    BodyWriter(const Model& model, std::ostringstream& out) : model_(model), out_(out), children_(findChildren(model)) {
        sites_.resize(static_cast<std::size_t>(model.getNumLinks()));
        for (const Wire& wire : model.getWires())
            for (int k = 0; k < wire.numPoints; ++k)
                sites_[static_cast<std::size_t>(model.getWirePoints()[static_cast<std::size_t>(wire.firstPoint + k)].link)]
                    .push_back({&wire, k});
    }

    void writeChildrenOf(int parent, int depth) {
        for (const int link : children_[static_cast<std::size_t>(parent + 1)]) writeBody(link, depth);
    }

private:
    void writeBody(int link, int depth) {
        const Joint& joint = model_.getJoint(link);
        const Link& body = model_.getLink(link);
        const std::string indent(static_cast<std::size_t>(2 * depth), ' ');
        // F in the parent body's frame (its M), then M at the default pose.
        Eigen::Matrix3d R_PF = joint.R_PF;
        Eigen::Vector3d p_PF = joint.p_PF;
        if (joint.parent != kGround) {
            const Joint& parentJoint = model_.getJoint(joint.parent);
            R_PF = parentJoint.R_BM.transpose() * joint.R_PF;
            p_PF = toBodyFrame(parentJoint, joint.p_PF);
        }
        const Eigen::VectorXd& q0 = model_.getDefaultQ();
        const JointTransform X_FM = calcTransform(joint, q0);
        const Eigen::Matrix3d R_PM = R_PF * X_FM.R_FM;
        const Eigen::Vector3d p_PM = p_PF + R_PF * X_FM.p_FM;
        out_ << indent << "<body name=\"" << escapeXml(body.name) << "\" pos=\"" << formatVector(p_PM) << "\" quat=\""
             << formatQuaternion(R_PM) << "\">\n";
        // Principal axes computed here: MuJoCo's own diagonalisation of a fullinertia costs its accelerations
        // about 1e-8 of their size.
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(joint.R_BM.transpose() * body.inertia_Bcom * joint.R_BM);
        Eigen::Matrix3d axes = principal.eigenvectors();
        if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
        out_ << indent << "  <inertial pos=\"" << formatVector(toBodyFrame(joint, body.com_B)) << "\" quat=\""
             << formatQuaternion(axes) << "\" mass=\"" << formatNumber(body.mass) << "\" diaginertia=\""
             << formatVector(principal.eigenvalues()) << "\"/>\n";
        const std::string jointName = escapeXml(joint.name.empty() ? body.name + "_joint" : joint.name);
        switch (joint.type) {
            case JointType::Free: out_ << indent << "  <joint name=\"" << jointName << "\" type=\"free\"/>\n"; break;
            case JointType::Ball: out_ << indent << "  <joint name=\"" << jointName << "\" type=\"ball\"/>\n"; break;
            case JointType::Pin:
                out_ << indent << "  <joint name=\"" << jointName << "\" type=\"hinge\" axis=\"0 0 1\" ref=\""
                     << formatNumber(q0[joint.qStart]) << "\"/>\n";
                break;
            default: break;
        }
        for (const auto& [wire, point] : sites_[static_cast<std::size_t>(link)]) {
            const WirePoint& p = model_.getWirePoints()[static_cast<std::size_t>(wire->firstPoint + point)];
            out_ << indent << "  <site name=\"" << siteName(*wire, point) << "\" pos=\""
                 << formatVector(toBodyFrame(joint, p.p_B)) << "\"/>\n";
        }
        writeChildrenOf(link, depth + 1);
        out_ << indent << "</body>\n";
    }

    const Model& model_;
    std::ostringstream& out_;
    std::vector<std::vector<int>> children_;  // by parent + 1 (ground first)
    std::vector<std::vector<std::pair<const Wire*, int>>> sites_;  // the wire points fixed on each link
};

void writeLoops(const Model& model, std::ostringstream& out) {
    if (model.getLoops().empty()) return;
    out << "  <equality>\n";
    for (const Loop& loop : model.getLoops()) {
        // MuJoCo takes body2's anchor from qpos0, sinew's default pose, where the loop is closed.
        out << "    <connect name=\"" << escapeXml(loop.name) << "\" body1=\"" << escapeXml(model.getLink(loop.linkA).name)
            << "\" body2=\"" << escapeXml(model.getLink(loop.linkB).name) << "\" anchor=\""
            << formatVector(toBodyFrame(model.getJoint(loop.linkA), loop.p_A)) << "\"/>\n";
    }
    out << "  </equality>\n";
}

// Writes the tendons; returns how many wires each force law other than spring_damper has.
std::map<std::string, int> writeTendons(const Model& model, std::ostringstream& out) {
    std::map<std::string, int> unwrittenLaws;
    if (model.getWires().empty()) return unwrittenLaws;
    out << "  <tendon>\n";
    for (const Wire& wire : model.getWires()) {
        out << "    <spatial name=\"" << escapeXml(wire.name) << "\"";
        if (wire.lawSpec.type == "spring_damper") {
            const ForceLawParameters& parameters = wire.lawSpec.parameters;
            out << " stiffness=\"" << formatNumber(parameters.getScalar("stiffness")) << "\" damping=\""
                << formatNumber(parameters.getScalarOr("damping", 0.0)) << "\" springlength=\""
                << formatNumber(parameters.getScalar("rest_length")) << "\"";
        } else {
            ++unwrittenLaws[wire.lawSpec.type];
        }
        out << ">\n";
        for (int k = 0; k < wire.numPoints; ++k) out << "      <site site=\"" << siteName(wire, k) << "\"/>\n";
        out << "    </spatial>\n";
    }
    out << "  </tendon>\n";
    return unwrittenLaws;
}

std::vector<std::string> describeDifferences(const Model& model, const std::map<std::string, int>& unwrittenLaws) {
    std::vector<std::string> notes;
    int springDampers = 0;
    for (const Wire& wire : model.getWires()) springDampers += wire.lawSpec.type == "spring_damper";
    if (springDampers > 0)
        notes.push_back(std::to_string(springDampers) +
                        " spring_damper wires: MuJoCo's tendon spring and damper act at every length (sinew's wire "
                        "goes slack below its rest length)");
    for (const auto& [law, count] : unwrittenLaws)
        notes.push_back(std::to_string(count) + " wires with force law '" + law +
                        "': written as spatial tendons without force (MuJoCo has no such tendon law)");
    if (model.getNumLoops() > 0)
        notes.push_back(std::to_string(model.getNumLoops()) +
                        " loops: MuJoCo's connect equalities are soft constraints (its default solref and solimp); "
                        "sinew closes loops exactly");
    bool ranges = false;
    for (const Coordinate& coordinate : model.getCoordinates())
        ranges = ranges || std::isfinite(coordinate.rangeMin) || std::isfinite(coordinate.rangeMax);
    if (ranges) notes.push_back("coordinate ranges: not written (sinew's forward dynamics does not enforce them either)");
    if (!model.getForceElements().empty()) notes.push_back("force elements (springs, bushings, limits, contact): not written");
    if (!model.getContacts().empty())
        notes.push_back(std::to_string(model.getContacts().size()) + " contact links (feet): not written");
    return notes;
}

// A speed-space vector at q in MuJoCo's qvel coordinates (toMujoco) or back: one rotation per ball or free joint.
Eigen::VectorXd mapVelocity(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v, bool toMujoco) {
    if (q.size() != model.getNumQ() || v.size() != model.getNumU())
        throw Error("MuJoCo velocity map: expected q of " + std::to_string(model.getNumQ()) + " and a vector of " +
                    std::to_string(model.getNumU()) + " entries, got " + std::to_string(q.size()) + " and " +
                    std::to_string(v.size()));
    Eigen::VectorXd result(v.size());
    Eigen::Index dof = 0;  // the joint's first entry of MuJoCo's qvel
    for (const int link : findBodyOrder(model)) {
        const Joint& joint = model.getJoint(link);
        const Eigen::Index s = toMujoco ? joint.uStart : dof, r = toMujoco ? dof : joint.uStart;
        dof += joint.nu;
        const Eigen::Matrix3d R_FM = calcTransform(joint, q).R_FM;
        if (joint.type == JointType::Ball) {
            result.segment<3>(r) = (toMujoco ? Eigen::Matrix3d(R_FM.transpose()) : R_FM) * v.segment<3>(s);
        } else if (joint.type == JointType::Free && toMujoco) {
            // MuJoCo's free joint: the linear velocity in the world first, then the angular one in the body.
            result.segment<3>(r) = joint.R_PF * v.segment<3>(s + 3);
            result.segment<3>(r + 3) = R_FM.transpose() * v.segment<3>(s);
        } else if (joint.type == JointType::Free) {
            result.segment<3>(r) = R_FM * v.segment<3>(s + 3);
            result.segment<3>(r + 3) = joint.R_PF.transpose() * v.segment<3>(s);
        } else {
            result.segment(r, joint.nu) = v.segment(s, joint.nu);
        }
    }
    return result;
}

}  // namespace

MjcfExport writeMjcfText(const Model& model) {
    requireMjcfWritable(model);
    std::ostringstream out;
    out << "<!-- Written by sinew from model '" << escapeXml(model.getName())
        << "'; bodies at the model's default pose (MuJoCo's qpos0), each in its link's joint frame. -->\n";
    out << "<mujoco model=\"" << escapeXml(model.getName()) << "\">\n";
    out << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
    out << "  <option gravity=\"" << formatVector(model.getGravity()) << "\"/>\n";
    out << "  <worldbody>\n";
    BodyWriter(model, out).writeChildrenOf(kGround, 2);
    out << "  </worldbody>\n";
    writeLoops(model, out);
    const std::map<std::string, int> unwrittenLaws = writeTendons(model, out);
    out << "</mujoco>\n";
    return {out.str(), describeDifferences(model, unwrittenLaws)};
}

std::vector<std::string> writeMjcfModel(const Model& model, const std::string& path) {
    MjcfExport document = writeMjcfText(model);
    writeFileAtomically(path, document.text);
    return std::move(document.notes);
}

Eigen::VectorXd toMujocoQpos(const Model& model, const Eigen::VectorXd& q) {
    if (q.size() != model.getNumQ())
        throw Error("MuJoCo qpos: expected q of " + std::to_string(model.getNumQ()) + " entries, got " + std::to_string(q.size()));
    requireMjcfWritable(model);
    Eigen::VectorXd qpos(model.getNumQ());
    const Eigen::VectorXd& q0 = model.getDefaultQ();
    Eigen::Index s = 0;  // the joint's first entry of MuJoCo's qpos
    for (const int link : findBodyOrder(model)) {
        const Joint& joint = model.getJoint(link);
        switch (joint.type) {
            case JointType::Free: {
                // The world pose of the body frame M.
                const JointTransform X_FM = calcTransform(joint, q);
                qpos.segment<3>(s) = joint.p_PF + joint.R_PF * X_FM.p_FM;
                const Eigen::Quaterniond R(joint.R_PF * X_FM.R_FM);
                qpos.segment<4>(s + 3) << R.w(), R.x(), R.y(), R.z();
                break;
            }
            case JointType::Ball: {
                // Relative to the body's placement at the default pose.
                const Eigen::Quaterniond R(calcTransform(joint, q0).R_FM.transpose() * calcTransform(joint, q).R_FM);
                qpos.segment<4>(s) << R.w(), R.x(), R.y(), R.z();
                break;
            }
            case JointType::Pin: qpos[s] = q[joint.qStart]; break;
            default: break;
        }
        s += joint.nq;
    }
    return qpos;
}

Eigen::VectorXd toMujocoVelocity(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
    return mapVelocity(model, q, u, true);
}

Eigen::VectorXd fromMujocoVelocity(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qvel) {
    return mapVelocity(model, q, qvel, false);
}

}  // namespace sinew

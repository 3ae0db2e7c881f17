#include "sinew/core/model_builder.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "sinew/core/error.hpp"
#include "sinew/core/force_law_registry.hpp"

namespace sinew {
namespace {

bool isFinite(const Eigen::MatrixXd& m) { return m.allFinite(); }

void requireFinite(const std::string& where, const std::string& what, const Eigen::MatrixXd& m) {
    if (!isFinite(m)) throw ModelError(where, what + " must be finite (got NaN or inf)");
}

// Records `name` of a `kind` as defined at `where`; throws for an empty or already-used name.
void claimName(std::map<std::string, std::string>& defined, const std::string& kind, const std::string& name,
               const std::string& where) {
    if (name.empty()) throw ModelError(where, kind + " needs a non-empty name");
    auto [it, fresh] = defined.emplace(name, where);
    if (!fresh) throw ModelError(where, "duplicate " + kind + " name '" + name + "' (first defined at " + it->second + ")");
}

// Rotation taking F's z axis onto `axis` (pin joints rotate about F's z, as Simbody's Pin does). Its z column
// is the unit axis bit for bit, and an axis that is already unit is not renormalised: the model writer stores
// that column as the axis, and any drift in its last bits would change the model on every write and read.
Eigen::Matrix3d rotationWithZAlong(const Eigen::Vector3d& axis) {
    const bool isUnit = std::abs(axis.squaredNorm() - 1) <= 8 * std::numeric_limits<double>::epsilon();
    const Eigen::Vector3d z = isUnit ? axis : axis.normalized();
    Eigen::Matrix3d R = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), z).toRotationMatrix();
    R.col(2) = z;
    return R;
}

Eigen::Vector4d quaternionFromRotationVector(const Eigen::Vector3d& rotation) {
    const double angle = rotation.norm();
    const Eigen::Quaterniond q = angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, rotation / angle))
                                           : Eigen::Quaterniond::Identity();
    // q and -q are the same rotation; w >= 0 is the one a written model (rotation angle <= pi) reads back as.
    return (q.w() < 0 ? -1.0 : 1.0) * Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
}

void checkMassProperties(const LinkSpec& link, bool welded) {
    if (!std::isfinite(link.mass)) throw ModelError(link.where, "link '" + link.name + "': mass must be finite");
    requireFinite(link.where, "link '" + link.name + "': com", link.com_B);
    requireFinite(link.where, "link '" + link.name + "': inertia", link.inertia_Bcom);
    if (link.mass < 0) throw ModelError(link.where, "link '" + link.name + "': mass must be >= 0");
    const Eigen::Matrix3d& I = link.inertia_Bcom;
    if (link.mass == 0) {
        if (!welded)
            throw ModelError(link.where, "link '" + link.name +
                                             "': a massless link must be welded to its parent (use a virtual link "
                                             "for a massless 6-DOF link)");
        if (!I.isZero(0))
            throw ModelError(link.where, "link '" + link.name + "': a massless link must have zero inertia");
        return;
    }
    // The eigensolver reads one triangle only, so a non-symmetric inertia would otherwise pass unchecked.
    if (!I.isApprox(I.transpose(), 1e-12))
        throw ModelError(link.where, "link '" + link.name + "': inertia is not symmetric");
    const Eigen::Vector3d eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I, Eigen::EigenvaluesOnly).eigenvalues();
    if (!(eig.minCoeff() > 0))
        throw ModelError(link.where, "link '" + link.name + "': inertia is not positive definite (smallest principal "
                                     "moment " + std::to_string(eig.minCoeff()) + " kg m^2)");
    // A rigid body's principal moments obey the triangle inequality; Simbody rejects inertias that do not.
    const double slack = 1e-12 * eig.sum();
    if (eig[0] + eig[1] < eig[2] - slack)
        throw ModelError(link.where, "link '" + link.name + "': inertia violates the triangle inequality of principal "
                                     "moments (" + std::to_string(eig[0]) + " + " + std::to_string(eig[1]) + " < " +
                                     std::to_string(eig[2]) + "), so no rigid body has it");
}

}  // namespace

void ModelBuilder::setGravity(const Eigen::Vector3d& gravity, std::string where) {
    gravity_ = gravity;
    gravityWhere_ = std::move(where);
}

Model ModelBuilder::build() const {
    Model model;
    model.name_ = name_;
    requireFinite(gravityWhere_, "gravity", gravity_);
    model.gravity_ = gravity_;

    // Names: links and virtual links share one namespace; "ground" is reserved.
    std::map<std::string, std::string> linkWhere;  // name -> where
    auto claimLinkName = [&](const std::string& name, const std::string& where, const char* kind) {
        if (name == "ground") throw ModelError(where, std::string(kind) + " cannot be called 'ground' (reserved)");
        claimName(linkWhere, "link", name, where);
    };
    std::map<std::string, std::size_t> linkSpecIndex;
    for (std::size_t i = 0; i < links_.size(); ++i) {
        claimLinkName(links_[i].name, links_[i].where, "link");
        linkSpecIndex[links_[i].name] = i;
    }
    for (const VirtualLinkSpec& v : virtualLinks_) {
        claimLinkName(v.name, v.where, "virtual link");
        requireFinite(v.where, "virtual link '" + v.name + "': initial position", v.initialPosition);
    }

    // Joints: each real link is the child of exactly one joint.
    std::map<std::string, std::size_t> jointOfChild;
    std::map<std::string, std::string> jointWhere;
    for (std::size_t j = 0; j < joints_.size(); ++j) {
        const JointSpec& js = joints_[j];
        claimName(jointWhere, "joint", js.name, js.where);
        const std::string label = "joint '" + js.name + "'";
        if (!linkSpecIndex.count(js.child))
            throw ModelError(js.where, label + ": unknown child link '" + js.child + "'" +
                                           (linkWhere.count(js.child) ? " (virtual links have no joint)" : ""));
        if (js.parent != "ground" && !linkSpecIndex.count(js.parent))
            throw ModelError(js.where, label + ": unknown parent link '" + js.parent + "'" +
                                           (linkWhere.count(js.parent) ? " (a virtual link cannot be a parent)" : ""));
        if (js.parent == js.child) throw ModelError(js.where, label + ": a link cannot be its own parent");
        auto [prev, first] = jointOfChild.emplace(js.child, j);
        if (!first)
            throw ModelError(js.where, label + ": link '" + js.child + "' already has joint '" +
                                           joints_[prev->second].name + "' to its parent; close loops with a "
                                           "'loops' entry instead");
        requireFinite(js.where, label + ": parent_point", js.p_PF);
        requireFinite(js.where, label + ": child_point", js.p_BM);
        if (js.type == JointType::Pin) {
            if (!js.axis || !js.axis->allFinite() || js.axis->norm() < 1e-12)
                throw ModelError(js.where, label + ": a pin joint needs a finite, non-zero axis");
        } else if (js.axis) {
            throw ModelError(js.where, label + ": only pin joints take an axis");
        }
        if (js.initialRotation && js.type != JointType::Ball && js.type != JointType::Free)
            throw ModelError(js.where, label + ": initial_rotation applies to ball and free joints only");
        if (js.initialAngle && js.type != JointType::Pin)
            throw ModelError(js.where, label + ": initial_angle applies to pin joints only");
        if (js.initialPosition && js.type != JointType::Free)
            throw ModelError(js.where, label + ": initial_position applies to free joints only");
        if (js.initialRotation) requireFinite(js.where, label + ": initial_rotation", *js.initialRotation);
        if (js.initialPosition) requireFinite(js.where, label + ": initial_position", *js.initialPosition);
        if (js.initialAngle && !std::isfinite(*js.initialAngle))
            throw ModelError(js.where, label + ": initial_angle must be finite");
    }
    // A virtual link's 6-DOF joint takes the virtual link's name.
    for (const VirtualLinkSpec& v : virtualLinks_)
        if (jointWhere.count(v.name))
            throw ModelError(v.where, "virtual link '" + v.name + "' has the name of joint '" + v.name + "' (" +
                                          jointWhere.at(v.name) + "); its own joint takes that name");
    for (const LinkSpec& ls : links_) {
        auto it = jointOfChild.find(ls.name);
        if (it == jointOfChild.end())
            throw ModelError(ls.where, "link '" + ls.name + "' has no joint (every link needs one joint to its "
                                       "parent or to ground)");
        checkMassProperties(ls, joints_[it->second].type == JointType::Weld);
    }

    // Parents-first order: depth-first from ground, siblings in file order, so subtrees stay contiguous.
    std::map<std::string, std::vector<std::size_t>> childJoints;  // parent name -> joints
    for (std::size_t j = 0; j < joints_.size(); ++j) childJoints[joints_[j].parent].push_back(j);
    std::vector<std::size_t> order;  // joint spec indices
    std::vector<std::size_t> stack;
    auto pushChildren = [&](const std::string& parent) {
        const auto& kids = childJoints[parent];
        stack.insert(stack.end(), kids.rbegin(), kids.rend());
    };
    pushChildren("ground");
    while (!stack.empty()) {
        const std::size_t j = stack.back();
        stack.pop_back();
        order.push_back(j);
        pushChildren(joints_[j].child);
    }
    if (order.size() != joints_.size()) {
        for (const JointSpec& js : joints_)
            if (std::find_if(order.begin(), order.end(), [&](std::size_t o) { return joints_[o].name == js.name; }) ==
                order.end())
                throw ModelError(js.where, "joint '" + js.name + "' is part of a cycle of joints that never reaches "
                                           "ground; close loops with a 'loops' entry instead");
    }

    std::map<std::string, int> linkIndex;
    int nq = 0, nu = 0;
    std::vector<double> defaultQ;
    auto appendJoint = [&](Joint joint, Link link) {
        joint.nq = getNumQ(joint.type);
        joint.nu = getNumU(joint.type);
        joint.qStart = nq;
        joint.uStart = nu;
        nq += joint.nq;
        nu += joint.nu;
        linkIndex[link.name] = static_cast<int>(model.links_.size());
        model.links_.push_back(std::move(link));
        model.joints_.push_back(std::move(joint));
    };
    for (std::size_t j : order) {
        const JointSpec& js = joints_[j];
        const LinkSpec& ls = links_[linkSpecIndex.at(js.child)];
        Joint joint;
        joint.name = js.name;
        joint.type = js.type;
        joint.parent = js.parent == "ground" ? kGround : linkIndex.at(js.parent);
        joint.p_PF = js.p_PF;
        joint.p_BM = js.p_BM;
        if (js.type == JointType::Pin) joint.R_PF = joint.R_BM = rotationWithZAlong(*js.axis);
        const Eigen::Vector4d quat = quaternionFromRotationVector(js.initialRotation.value_or(Eigen::Vector3d::Zero()));
        switch (js.type) {
            case JointType::Free: {
                const Eigen::Vector3d p = js.initialPosition.value_or(Eigen::Vector3d::Zero());
                defaultQ.insert(defaultQ.end(), {quat[0], quat[1], quat[2], quat[3], p[0], p[1], p[2]});
                break;
            }
            case JointType::Ball: defaultQ.insert(defaultQ.end(), {quat[0], quat[1], quat[2], quat[3]}); break;
            case JointType::Pin: defaultQ.push_back(js.initialAngle.value_or(0.0)); break;
            case JointType::Weld: break;
        }
        // Exactly symmetric (an inertia computed as R D R^T is not), as the model file stores one triangle.
        const Eigen::Matrix3d inertia_Bcom = 0.5 * (ls.inertia_Bcom + ls.inertia_Bcom.transpose());
        appendJoint(joint, Link{ls.name, ls.mass, ls.com_B, inertia_Bcom, false});
    }
    for (const VirtualLinkSpec& v : virtualLinks_) {
        Joint joint;
        joint.name = v.name;
        joint.type = JointType::Free;
        defaultQ.insert(defaultQ.end(), {1, 0, 0, 0, v.initialPosition[0], v.initialPosition[1], v.initialPosition[2]});
        Link link;
        link.name = v.name;
        link.isVirtual = true;
        appendJoint(joint, link);
    }
    model.nq_ = nq;
    model.nu_ = nu;
    model.defaultQ_ = Eigen::Map<const Eigen::VectorXd>(defaultQ.data(), static_cast<Eigen::Index>(defaultQ.size()));

    auto resolveLink = [&](const std::string& where, const std::string& owner, const std::string& name) {
        if (name == "ground")
            throw ModelError(where, owner + ": 'ground' is not a link; attach to a link (fix a link to ground with a "
                                            "weld joint, or simulate with --hang-by)");
        auto it = linkIndex.find(name);
        if (it == linkIndex.end()) throw ModelError(where, owner + ": unknown link '" + name + "'");
        return it->second;
    };

    // Loops.
    std::map<std::string, std::string> loopWhere;
    for (const LoopSpec& ls : loops_) {
        claimName(loopWhere, "loop", ls.name, ls.where);
        const std::string label = "loop '" + ls.name + "'";
        Loop loop{ls.name, resolveLink(ls.where, label, ls.linkA), ls.p_A, resolveLink(ls.where, label, ls.linkB), ls.p_B};
        requireFinite(ls.where, label + ": point_a", ls.p_A);
        requireFinite(ls.where, label + ": point_b", ls.p_B);
        if (loop.linkA == loop.linkB) throw ModelError(ls.where, label + ": both ends are on link '" + ls.linkA + "'");
        for (const Loop& other : model.loops_) {
            const bool same = (other.linkA == loop.linkA && other.linkB == loop.linkB && other.p_A.isApprox(loop.p_A) &&
                               other.p_B.isApprox(loop.p_B)) ||
                              (other.linkA == loop.linkB && other.linkB == loop.linkA && other.p_A.isApprox(loop.p_B) &&
                               other.p_B.isApprox(loop.p_A));
            if (same)
                throw ModelError(ls.where, label + " closes the same joint as loop '" + other.name + "' (" +
                                               loopWhere.at(other.name) + ")");
        }
        for (int end = 0; end < 2; ++end) {
            const int child = end == 0 ? loop.linkA : loop.linkB;
            const int parent = end == 0 ? loop.linkB : loop.linkA;
            const Joint& joint = model.joints_[static_cast<std::size_t>(child)];
            const Eigen::Vector3d& p_child = end == 0 ? loop.p_A : loop.p_B;
            const Eigen::Vector3d& p_parent = end == 0 ? loop.p_B : loop.p_A;
            if (joint.parent == parent && joint.type != JointType::Free && (p_child - joint.p_BM).norm() < 1e-12 &&
                (p_parent - joint.p_PF).norm() < 1e-12)
                throw ModelError(ls.where, label + " closes over tree joint '" + joint.name +
                                               "', which already joins these two points");
        }
        model.loops_.push_back(loop);
    }

    // Wires.
    std::map<std::string, std::string> wireWhere;
    for (const WireSpec& ws : wires_) {
        claimName(wireWhere, "wire", ws.name, ws.where);
        const std::string label = "wire '" + ws.name + "'";
        if (ws.points.size() < 2)
            throw ModelError(ws.where, label + " has " + std::to_string(ws.points.size()) +
                                           " point(s); a wire needs at least 2 (origin and insertion)");
        Wire wire;
        wire.name = ws.name;
        wire.kind = ws.kind;
        wire.firstPoint = static_cast<int>(model.wirePoints_.size());
        wire.numPoints = static_cast<int>(ws.points.size());
        for (std::size_t k = 0; k < ws.points.size(); ++k) {
            const WirePointSpec& ps = ws.points[k];
            const std::string& where = ps.where.empty() ? ws.where : ps.where;
            WirePoint point{resolveLink(where, label, ps.link), ps.p_B};
            requireFinite(where, label + ": point " + std::to_string(k), ps.p_B);
            if (k > 0) {
                const WirePoint& prev = model.wirePoints_.back();
                if (prev.link == point.link && (prev.p_B - point.p_B).norm() < 1e-12)
                    throw ModelError(where, label + ": points " + std::to_string(k - 1) + " and " + std::to_string(k) +
                                                " coincide on link '" + ps.link + "' (zero-length segment)");
            }
            model.wirePoints_.push_back(point);
        }
        wire.lawSpec = ws.law;
        try {
            wire.law = ForceLawRegistry::global().create(ws.law.type, ws.law.parameters);
        } catch (const ModelError&) {
            throw;
        } catch (const Error& e) {
            throw ModelError(ws.lawWhere.empty() ? ws.where : ws.lawWhere, label + ": " + e.what());
        }
        std::set<int, std::greater<int>> support;
        for (int k = 0; k < wire.numPoints; ++k)
            for (int l = model.wirePoints_[static_cast<std::size_t>(wire.firstPoint + k)].link; l != kGround;
                 l = model.joints_[static_cast<std::size_t>(l)].parent)
                if (!support.insert(l).second) break;
        wire.supportLinks.assign(support.begin(), support.end());
        model.wires_.push_back(std::move(wire));
    }
    return model;
}

}  // namespace sinew

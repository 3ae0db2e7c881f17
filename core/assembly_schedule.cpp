#include "sinew/core/assembly_schedule.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <numeric>
#include <set>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

int positionOf(const std::vector<int>& handles, int handle) {
    return static_cast<int>(std::find(handles.begin(), handles.end(), handle) - handles.begin());
}

std::vector<int> without(const std::vector<int>& handles, int a, int b = -1) {
    std::vector<int> rest;
    for (int h : handles)
        if (h != a && h != b) rest.push_back(h);
    return rest;
}

AssemblyJoint::Motion motionOf(JointType type) {
    switch (type) {
        case JointType::Free: return AssemblyJoint::Motion::Free;
        case JointType::Ball: return AssemblyJoint::Motion::Ball;
        case JointType::Pin: return AssemblyJoint::Motion::Pin;
        case JointType::Weld: return AssemblyJoint::Motion::Weld;
        case JointType::Custom: return AssemblyJoint::Motion::Custom;
    }
    return AssemblyJoint::Motion::Weld;
}

}  // namespace

AssemblySchedule::AssemblySchedule(const Model& model, Kind kind, int hangLink) : kind_(kind) {
    if (kind == Kind::Automatic) {
        AssemblySchedule serial(model, Kind::Serial, hangLink);
        if (serial.findPointMassBody() >= 0) {
            *this = std::move(serial);
            return;
        }
        AssemblySchedule balanced(model, Kind::Balanced, hangLink);
        *this = balanced.getCost() < serial.getCost() ? std::move(balanced) : std::move(serial);
        return;
    }
    buildBodies(model);
    // The balanced schedule starts from every body's own inverse inertia, which a point mass has not.
    if (const int body = findPointMassBody(); kind == Kind::Balanced && body >= 0)
        throw Error("model '" + model.getName() + "': link '" + model.getLink(bodies_[static_cast<std::size_t>(body)].links.front()).name +
                    "' is a point mass or massless (no rotational inertia): the balanced schedule inverts every "
                    "body's inertia; use the serial schedule");
    const int numTreeJoints = static_cast<int>(joints_.size());
    addLoopJoints(model);
    addHangJoint(model, hangLink);
    chooseTreeOperations(model, hangLink);
    buildLeaves(numTreeJoints);
    if (kind == Kind::Serial) scheduleSerial(numTreeJoints);
    else scheduleBalanced(numTreeJoints);
}

// An assembly joint per loop, between the bodies of its two links.
void AssemblySchedule::addLoopJoints(const Model& model) {
    for (int k = 0; k < model.getNumLoops(); ++k) {
        const Loop& loop = model.getLoop(k);
        const int a = linkBody_[static_cast<std::size_t>(loop.linkA)];
        const int b = linkBody_[static_cast<std::size_t>(loop.linkB)];
        if (a == kNoBody || b == kNoBody)
            throw Error("model '" + model.getName() + "': loop '" + loop.name + "' has an end on virtual link '" +
                        model.getLink(a == kNoBody ? loop.linkA : loop.linkB).name +
                        "'; loops join links with mass only");
        if (a == b)
            throw Error("model '" + model.getName() + "': loop '" + loop.name + "' joins links '" +
                        model.getLink(loop.linkA).name + "' and '" + model.getLink(loop.linkB).name +
                        "', which are welded together");
        joints_.push_back({AssemblyJoint::Kind::Loop, AssemblyJoint::Motion::Ball, k, a, b});
    }
}

// The hang's weld to ground, unless the link is welded to ground already (or hangLink is -1).
void AssemblySchedule::addHangJoint(const Model& model, int hangLink) {
    if (hangLink < 0) return;
    const int body = linkBody_[static_cast<std::size_t>(hangLink)];
    if (body == kNoBody)
        throw Error("model '" + model.getName() + "': cannot hang by virtual link '" + model.getLink(hangLink).name +
                    "' (it is massless); hang by a link with mass");
    if (body != kGroundBody)
        joints_.push_back({AssemblyJoint::Kind::Hang, AssemblyJoint::Motion::Weld, hangLink, kGroundBody, body});
}

// Leaves: each body with the handles of the joints that touch it, but for what is folded: both handles
// of an Absorb, the alpha handle of an AbsorbSubassembly. Then ground.
void AssemblySchedule::buildLeaves(int numTreeJoints) {
    handles_.assign(static_cast<std::size_t>(getNumBodies() + 1), {});
    for (int j = 0; j < static_cast<int>(joints_.size()); ++j) {
        const AssemblyOperation::Kind how = j < numTreeJoints ? treeOperation_[static_cast<std::size_t>(j)]
                                                              : AssemblyOperation::Kind::Join;
        const AssemblyJoint& joint = joints_[static_cast<std::size_t>(j)];
        if (how == AssemblyOperation::Kind::Join) handles_[static_cast<std::size_t>(leafOf(joint.alphaBody))].push_back(2 * j);
        if (how != AssemblyOperation::Kind::Absorb) handles_[static_cast<std::size_t>(leafOf(joint.betaBody))].push_back(2 * j + 1);
    }
    mergedInto_.resize(handles_.size());
    std::iota(mergedInto_.begin(), mergedInto_.end(), 0);
    closed_.assign(joints_.size(), false);
}

// Bodies are numbered parents first, so the reverse order visits tips first: fold the children that no loop
// crosses into the body, then, if its subtree holds loop ends, make its leaf and join the children that
// loops cross. Ground (kGroundBody = -1) comes last; its leaf needs no operation (it does not move: Phi = 0,
// b = 0). One operation per level: each depends on the one before.
void AssemblySchedule::scheduleSerial(int numTreeJoints) {
    const int numBodies = getNumBodies();
    std::vector<std::vector<int>> children(static_cast<std::size_t>(numBodies + 1));
    for (int j = 0; j < numTreeJoints; ++j)
        children[static_cast<std::size_t>(leafOf(joints_[static_cast<std::size_t>(j)].alphaBody))].push_back(j);
    for (int body = numBodies - 1; body >= kGroundBody; --body) {
        const std::vector<int>& mine = children[static_cast<std::size_t>(leafOf(body))];
        for (int j : mine) {
            const AssemblyOperation::Kind how = treeOperation_[static_cast<std::size_t>(j)];
            if (how == AssemblyOperation::Kind::Absorb) emitAbsorb(j);
            if (how == AssemblyOperation::Kind::AbsorbSubassembly) emitAbsorbSubassembly(j);
        }
        if (body != kGroundBody) {
            if (handles_[static_cast<std::size_t>(body)].empty()) continue;  // folded whole into its parent
            emitLeaf(body);
        }
        for (int j : mine) {
            if (treeOperation_[static_cast<std::size_t>(j)] != AssemblyOperation::Kind::Join) continue;
            emitJoin(j);
            closeReadyLoops(false);
        }
    }
    levelStarts_.resize(operations_.size() + 1);
    std::iota(levelStarts_.begin(), levelStarts_.end(), 0);
}

// Every body's leaf on the first level; then level by level, the pairs whose result has the fewest handles
// joined first, each subassembly once per level, and the loops that became closable closed.
void AssemblySchedule::scheduleBalanced(int numTreeJoints) {
    levelStarts_.push_back(0);
    for (int body = 0; body < getNumBodies(); ++body) emitLeaf(body);
    levelStarts_.push_back(static_cast<int>(operations_.size()));
    std::vector<int> pending(static_cast<std::size_t>(numTreeJoints));
    std::iota(pending.begin(), pending.end(), 0);
    while (!pending.empty()) {
        auto cost = [&](int j) {
            const AssemblyJoint& joint = joints_[static_cast<std::size_t>(j)];
            return handles_[static_cast<std::size_t>(currentOf(joint.alphaBody))].size() +
                   handles_[static_cast<std::size_t>(currentOf(joint.betaBody))].size();
        };
        std::stable_sort(pending.begin(), pending.end(), [&](int x, int y) { return cost(x) < cost(y); });
        std::set<int> busy;
        std::vector<int> later;
        for (int j : pending) {
            const AssemblyJoint& joint = joints_[static_cast<std::size_t>(j)];
            const int a = currentOf(joint.alphaBody);
            const int b = currentOf(joint.betaBody);
            if (busy.count(a) || busy.count(b)) {
                later.push_back(j);
                continue;
            }
            emitJoin(j);
            busy.insert({a, b, operations_.back().result});
        }
        levelStarts_.push_back(static_cast<int>(operations_.size()));
        pending = later;
        closeReadyLoops(true);
    }
}

// Bodies and their inboard tree joints (assembly joint b for body b); welded links merged into their
// parent's body, with the body's mass properties in its first link's frame.
void AssemblySchedule::buildBodies(const Model& model) {
    linkBody_.assign(static_cast<std::size_t>(model.getNumLinks()), kGroundBody);
    // Pose of each link's frame in its body's first link's frame (welds only).
    std::vector<Eigen::Matrix3d> R_1L(linkBody_.size(), Eigen::Matrix3d::Identity());
    std::vector<Eigen::Vector3d> p_1L(linkBody_.size(), Eigen::Vector3d::Zero());
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Link& link = model.getLink(i);
        const Joint& joint = model.getJoint(i);
        const std::size_t l = static_cast<std::size_t>(i);
        if (link.isVirtual) {
            linkBody_[l] = kNoBody;
            virtualLinks_.push_back(i);
            continue;
        }
        const int parentBody = joint.parent == kGround ? kGroundBody : linkBody_[static_cast<std::size_t>(joint.parent)];
        if (parentBody == kNoBody)
            throw Error("model '" + model.getName() + "': link '" + link.name + "' hangs from virtual link '" +
                        model.getLink(joint.parent).name + "'; virtual links carry no links");
        if (joint.type == JointType::Weld) {
            linkBody_[l] = parentBody;
            if (parentBody == kGroundBody) continue;
            const std::size_t parent = static_cast<std::size_t>(joint.parent);
            const Eigen::Matrix3d R_PB = joint.R_PF * joint.R_BM.transpose();
            R_1L[l] = R_1L[parent] * R_PB;
            p_1L[l] = p_1L[parent] + R_1L[parent] * (joint.p_PF - R_PB * joint.p_BM);
            bodies_[static_cast<std::size_t>(parentBody)].links.push_back(i);
            continue;
        }
        linkBody_[l] = static_cast<int>(bodies_.size());
        bodies_.push_back({{i}, 0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()});
        joints_.push_back({AssemblyJoint::Kind::Tree, motionOf(joint.type), i, parentBody, linkBody_[l]});
    }
    for (AssemblyBody& body : bodies_) {
        for (int link : body.links) {
            const Link& info = model.getLink(link);
            body.mass += info.mass;
            body.com += info.mass * (p_1L[static_cast<std::size_t>(link)] + R_1L[static_cast<std::size_t>(link)] * info.com_B);
        }
        if (body.mass > 0) body.com /= body.mass;  // a massless body's centre is its origin
        for (int link : body.links) {
            const Link& info = model.getLink(link);
            const Eigen::Matrix3d& R = R_1L[static_cast<std::size_t>(link)];
            const Eigen::Vector3d d = p_1L[static_cast<std::size_t>(link)] + R * info.com_B - body.com;
            body.inertia += R * info.inertia_Bcom * R.transpose() +
                            info.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
        }
    }
}

int AssemblySchedule::findPointMassBody() const {
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
        const Eigen::Vector3d moments =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(bodies_[b].inertia, Eigen::EigenvaluesOnly).eigenvalues();
        if (!(moments[0] > 1e-12 * moments[2])) return static_cast<int>(b);
    }
    return -1;
}

// Serial schedules fold every subtree that no loop crosses into its parent: with Absorb when it holds no
// loop end (nor the hung body), else with AbsorbSubassembly once its loops are closed; the subtrees that
// loops (or the hang) cross are joined. The balanced schedule joins everything, to keep its O(log N) levels.
void AssemblySchedule::chooseTreeOperations(const Model& model, int hangLink) {
    const std::size_t numBodies = bodies_.size();
    treeOperation_.assign(numBodies, AssemblyOperation::Kind::Join);
    if (kind_ != Kind::Serial) return;
    // Per body, over the loops (and the hang): how many ends its subtree holds, and whether one loop has
    // exactly one end in it (crosses it).
    std::vector<int> ends(numBodies, 0);
    std::vector<bool> crossed(numBodies, false);
    std::vector<int> endsOfThis(numBodies, 0);
    auto addClosure = [&](int a, int b) {
        std::fill(endsOfThis.begin(), endsOfThis.end(), 0);
        for (int end : {a, b})
            for (int body = end; body >= 0; body = joints_[static_cast<std::size_t>(body)].alphaBody)
                ++endsOfThis[static_cast<std::size_t>(body)];
        for (std::size_t body = 0; body < numBodies; ++body) {
            ends[body] += endsOfThis[body];
            if (endsOfThis[body] == 1) crossed[body] = true;
        }
    };
    for (const Loop& loop : model.getLoops())
        addClosure(linkBody_[static_cast<std::size_t>(loop.linkA)], linkBody_[static_cast<std::size_t>(loop.linkB)]);
    if (hangLink >= 0) addClosure(linkBody_[static_cast<std::size_t>(hangLink)], kGroundBody);
    for (std::size_t body = 0; body < numBodies; ++body) {
        if (crossed[body]) continue;
        treeOperation_[body] = ends[body] == 0 ? AssemblyOperation::Kind::Absorb : AssemblyOperation::Kind::AbsorbSubassembly;
    }
}

int AssemblySchedule::leafOf(int body) const { return body == kGroundBody ? getGroundLeaf() : body; }

int AssemblySchedule::currentOf(int body) const { return findCurrent(leafOf(body)); }

int AssemblySchedule::findCurrent(int subassembly) const {
    int root = subassembly;
    while (mergedInto_[static_cast<std::size_t>(root)] != root) root = mergedInto_[static_cast<std::size_t>(root)];
    for (int s = subassembly; s != root;) {
        const int next = mergedInto_[static_cast<std::size_t>(s)];
        mergedInto_[static_cast<std::size_t>(s)] = root;
        s = next;
    }
    return root;
}

void AssemblySchedule::emitAbsorb(int j) {
    AssemblyOperation absorb;
    absorb.kind = AssemblyOperation::Kind::Absorb;
    absorb.joint = j;
    operations_.push_back(absorb);
}

void AssemblySchedule::emitAbsorbSubassembly(int j) {
    AssemblyOperation absorb;
    absorb.kind = AssemblyOperation::Kind::AbsorbSubassembly;
    absorb.joint = j;
    absorb.first = currentOf(joints_[static_cast<std::size_t>(j)].betaBody);
    // Its loops are all closed: the joint's handle is the only one left.
    assert(handles_[static_cast<std::size_t>(absorb.first)].size() == 1);
    absorb.betaPosition = 0;
    operations_.push_back(absorb);
}

void AssemblySchedule::emitLeaf(int body) {
    AssemblyOperation leaf;
    leaf.kind = AssemblyOperation::Kind::Leaf;
    leaf.first = body;
    leaf.result = leafOf(body);
    operations_.push_back(leaf);
}

void AssemblySchedule::emitJoin(int j) {
    const AssemblyJoint& joint = joints_[static_cast<std::size_t>(j)];
    AssemblyOperation join;
    join.kind = AssemblyOperation::Kind::Join;
    join.joint = j;
    join.first = currentOf(joint.alphaBody);
    join.second = currentOf(joint.betaBody);
    join.result = static_cast<int>(handles_.size());
    join.alphaPosition = positionOf(handles_[static_cast<std::size_t>(join.first)], 2 * j);
    join.betaPosition = positionOf(handles_[static_cast<std::size_t>(join.second)], 2 * j + 1);
    std::vector<int> merged = without(handles_[static_cast<std::size_t>(join.first)], 2 * j);
    const std::vector<int> fromSecond = without(handles_[static_cast<std::size_t>(join.second)], 2 * j + 1);
    merged.insert(merged.end(), fromSecond.begin(), fromSecond.end());
    handles_.push_back(merged);
    mergedInto_.push_back(join.result);
    mergedInto_[static_cast<std::size_t>(join.first)] = join.result;
    mergedInto_[static_cast<std::size_t>(join.second)] = join.result;
    operations_.push_back(join);
}

void AssemblySchedule::emitClose(int j) {
    const AssemblyJoint& joint = joints_[static_cast<std::size_t>(j)];
    AssemblyOperation close;
    close.kind = AssemblyOperation::Kind::Close;
    close.joint = j;
    close.first = currentOf(joint.alphaBody);
    close.result = static_cast<int>(handles_.size());
    const std::vector<int> before = handles_[static_cast<std::size_t>(close.first)];
    close.alphaPosition = positionOf(before, 2 * j);
    close.betaPosition = positionOf(before, 2 * j + 1);
    handles_.push_back(without(before, 2 * j, 2 * j + 1));
    mergedInto_.push_back(close.result);
    mergedInto_[static_cast<std::size_t>(close.first)] = close.result;
    closed_[static_cast<std::size_t>(j)] = true;
    operations_.push_back(close);
}

// Closes every loop (and the hang) whose ends now share a subassembly: the smallest one that contains both.
// Serially one after another; balanced, one close per subassembly per level.
void AssemblySchedule::closeReadyLoops(bool oneCloseLevelPerSubassembly) {
    bool closedAny = true;
    while (closedAny) {
        closedAny = false;
        std::set<int> busy;
        for (std::size_t j = 0; j < joints_.size(); ++j) {
            const AssemblyJoint& joint = joints_[j];
            if (joint.kind == AssemblyJoint::Kind::Tree || closed_[j]) continue;
            const int s = currentOf(joint.alphaBody);
            if (s != currentOf(joint.betaBody) || busy.count(s)) continue;
            emitClose(static_cast<int>(j));
            closedAny = true;
            if (oneCloseLevelPerSubassembly) busy.insert(operations_.back().result);
        }
        if (oneCloseLevelPerSubassembly && closedAny) levelStarts_.push_back(static_cast<int>(operations_.size()));
    }
}

double AssemblySchedule::getCost() const {
    double cost = 0;
    for (const AssemblyOperation& op : operations_) {
        double inputs = 1;
        switch (op.kind) {
            case AssemblyOperation::Kind::Absorb:
            case AssemblyOperation::Kind::AbsorbSubassembly: break;
            case AssemblyOperation::Kind::Leaf:
                inputs = static_cast<double>(handles_[static_cast<std::size_t>(op.result)].size());
                break;
            case AssemblyOperation::Kind::Join:
                inputs = static_cast<double>(handles_[static_cast<std::size_t>(op.first)].size() +
                                             handles_[static_cast<std::size_t>(op.second)].size());
                break;
            case AssemblyOperation::Kind::Close:
                inputs = static_cast<double>(handles_[static_cast<std::size_t>(op.first)].size());
                break;
        }
        cost += inputs * inputs;
    }
    return cost;
}

int AssemblySchedule::getMaxHandles() const {
    std::size_t most = 0;
    for (const std::vector<int>& h : handles_) most = std::max(most, h.size());
    return static_cast<int>(most);
}

}  // namespace sinew

#include "sinew/core/assembly_schedule.hpp"

#include <algorithm>
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

}  // namespace

AssemblySchedule::AssemblySchedule(const Model& model, Kind kind, int hangLink) : kind_(kind) {
    if (kind == Kind::Automatic) {
        AssemblySchedule serial(model, Kind::Serial, hangLink);
        AssemblySchedule balanced(model, Kind::Balanced, hangLink);
        // The estimate already overstates the balanced schedule (1.6-1.9x the serial one on bare trees, where it
        // measures 1.1-1.3x), so the plain comparison leans serial wherever the two are close.
        *this = balanced.getCost() < serial.getCost() ? std::move(balanced) : std::move(serial);
        return;
    }
    linkBody_.assign(static_cast<std::size_t>(model.getNumLinks()), kGroundBody);
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Link& link = model.getLink(i);
        if (link.isVirtual)
            throw Error("model '" + model.getName() + "': virtual link '" + link.name +
                        "' is massless; the assembly-disassembly solver does not treat virtual links yet");
        const Joint& joint = model.getJoint(i);
        const std::size_t l = static_cast<std::size_t>(i);
        if (joint.type == JointType::Weld) {
            linkBody_[l] = joint.parent == kGround ? kGroundBody : linkBody_[static_cast<std::size_t>(joint.parent)];
            if (linkBody_[l] != kGroundBody) bodyLinks_[static_cast<std::size_t>(linkBody_[l])].push_back(i);
            continue;
        }
        linkBody_[l] = static_cast<int>(bodyLinks_.size());
        bodyLinks_.push_back({i});
        const int parentBody = joint.parent == kGround ? kGroundBody : linkBody_[static_cast<std::size_t>(joint.parent)];
        joints_.push_back({AssemblyJoint::Kind::Tree, i, parentBody, linkBody_[l]});
    }
    const int numTreeJoints = static_cast<int>(joints_.size());
    for (int k = 0; k < model.getNumLoops(); ++k) {
        const Loop& loop = model.getLoop(k);
        const int a = linkBody_[static_cast<std::size_t>(loop.linkA)];
        const int b = linkBody_[static_cast<std::size_t>(loop.linkB)];
        if (a == b)
            throw Error("model '" + model.getName() + "': loop '" + loop.name + "' joins links '" +
                        model.getLink(loop.linkA).name + "' and '" + model.getLink(loop.linkB).name +
                        "', which are welded together");
        joints_.push_back({AssemblyJoint::Kind::Loop, k, a, b});
    }
    if (hangLink >= 0 && linkBody_[static_cast<std::size_t>(hangLink)] != kGroundBody)
        joints_.push_back({AssemblyJoint::Kind::Hang, hangLink, kGroundBody, linkBody_[static_cast<std::size_t>(hangLink)]});

    // Leaves: each body with the handles of the joints that touch it; then ground.
    const int numBodies = getNumBodies();
    handles_.assign(static_cast<std::size_t>(numBodies + 1), {});
    for (int j = 0; j < static_cast<int>(joints_.size()); ++j) {
        handles_[static_cast<std::size_t>(leafOf(joints_[static_cast<std::size_t>(j)].alphaBody))].push_back(2 * j);
        handles_[static_cast<std::size_t>(leafOf(joints_[static_cast<std::size_t>(j)].betaBody))].push_back(2 * j + 1);
    }
    mergedInto_.resize(handles_.size());
    for (std::size_t s = 0; s < mergedInto_.size(); ++s) mergedInto_[s] = static_cast<int>(s);
    closed_.assign(joints_.size(), false);
    levelStarts_.push_back(0);

    if (kind == Kind::Serial) {
        // Bodies are numbered parents first, so the reverse order visits tips first.
        for (int j = numTreeJoints - 1; j >= 0; --j) {
            emitJoin(j);
            levelStarts_.push_back(static_cast<int>(operations_.size()));
            closeReadyLoops(false);
        }
    } else {
        std::vector<int> pending(static_cast<std::size_t>(numTreeJoints));
        for (int j = 0; j < numTreeJoints; ++j) pending[static_cast<std::size_t>(j)] = j;
        while (!pending.empty()) {
            // Join the pairs whose result has the fewest handles first; each subassembly once per level.
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

void AssemblySchedule::emitJoin(int j) {
    const AssemblyJoint& joint = joints_[static_cast<std::size_t>(j)];
    AssemblyOperation join;
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
    close.isClose = true;
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
            else levelStarts_.push_back(static_cast<int>(operations_.size()));
        }
        if (oneCloseLevelPerSubassembly && closedAny) levelStarts_.push_back(static_cast<int>(operations_.size()));
    }
}

double AssemblySchedule::getCost() const {
    double cost = 0;
    for (const AssemblyOperation& op : operations_) {
        const double inputs = static_cast<double>(handles_[static_cast<std::size_t>(op.first)].size() +
                                                  (op.isClose ? 0 : handles_[static_cast<std::size_t>(op.second)].size()));
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

#include "sinew/core/assembly_schedule.hpp"

#include <algorithm>

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

AssemblySchedule::AssemblySchedule(const Model& model, Kind /*kind*/) {
    linkBody_.assign(static_cast<std::size_t>(model.getNumLinks()), kGroundBody);
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Link& link = model.getLink(i);
        if (link.isVirtual)
            throw Error("model '" + model.getName() + "': virtual link '" + link.name +
                        "' is massless; the assembly-disassembly solver does not treat virtual links yet");
        const Joint& joint = model.getJoint(i);
        if (joint.type == JointType::Weld) {
            linkBody_[static_cast<std::size_t>(i)] =
                joint.parent == kGround ? kGroundBody : linkBody_[static_cast<std::size_t>(joint.parent)];
            if (linkBody_[static_cast<std::size_t>(i)] != kGroundBody)
                bodyLinks_[static_cast<std::size_t>(linkBody_[static_cast<std::size_t>(i)])].push_back(i);
            continue;
        }
        linkBody_[static_cast<std::size_t>(i)] = static_cast<int>(bodyLinks_.size());
        bodyLinks_.push_back({i});
        const int parentBody = joint.parent == kGround ? kGroundBody : linkBody_[static_cast<std::size_t>(joint.parent)];
        joints_.push_back({false, i, parentBody, linkBody_[static_cast<std::size_t>(i)]});
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
        joints_.push_back({true, k, a, b});
    }

    // Leaves: each body with the handles of the joints that touch it; then ground.
    const int numBodies = getNumBodies();
    handles_.assign(static_cast<std::size_t>(numBodies + 1), {});
    auto leafOf = [&](int body) { return body == kGroundBody ? numBodies : body; };
    for (int j = 0; j < static_cast<int>(joints_.size()); ++j) {
        handles_[static_cast<std::size_t>(leafOf(joints_[static_cast<std::size_t>(j)].alphaBody))].push_back(2 * j);
        handles_[static_cast<std::size_t>(leafOf(joints_[static_cast<std::size_t>(j)].betaBody))].push_back(2 * j + 1);
    }

    // Serial schedule: tree joints from the tips to the root (bodies are numbered parents first), each loop
    // closed in the first subassembly that holds both of its ends.
    std::vector<int> subOfBody(static_cast<std::size_t>(numBodies + 1));
    for (int b = 0; b <= numBodies; ++b) subOfBody[static_cast<std::size_t>(b)] = b;
    auto currentSub = [&](int body) { return subOfBody[static_cast<std::size_t>(leafOf(body))]; };
    std::vector<bool> closed(joints_.size(), false);
    for (int j = numTreeJoints - 1; j >= 0; --j) {
        const AssemblyJoint& joint = joints_[static_cast<std::size_t>(j)];
        AssemblyOperation join;
        join.joint = j;
        join.first = currentSub(joint.alphaBody);
        join.second = currentSub(joint.betaBody);
        join.result = static_cast<int>(handles_.size());
        join.alphaPosition = positionOf(handles_[static_cast<std::size_t>(join.first)], 2 * j);
        join.betaPosition = positionOf(handles_[static_cast<std::size_t>(join.second)], 2 * j + 1);
        std::vector<int> merged = without(handles_[static_cast<std::size_t>(join.first)], 2 * j);
        const std::vector<int> fromSecond = without(handles_[static_cast<std::size_t>(join.second)], 2 * j + 1);
        merged.insert(merged.end(), fromSecond.begin(), fromSecond.end());
        handles_.push_back(merged);
        operations_.push_back(join);
        for (int& sub : subOfBody)
            if (sub == join.first || sub == join.second) sub = join.result;

        for (int l = numTreeJoints; l < static_cast<int>(joints_.size()); ++l) {
            const AssemblyJoint& loop = joints_[static_cast<std::size_t>(l)];
            if (closed[static_cast<std::size_t>(l)] || currentSub(loop.alphaBody) != currentSub(loop.betaBody)) continue;
            closed[static_cast<std::size_t>(l)] = true;
            AssemblyOperation close;
            close.isClose = true;
            close.joint = l;
            close.first = currentSub(loop.alphaBody);
            close.result = static_cast<int>(handles_.size());
            const std::vector<int>& before = handles_[static_cast<std::size_t>(close.first)];
            close.alphaPosition = positionOf(before, 2 * l);
            close.betaPosition = positionOf(before, 2 * l + 1);
            handles_.push_back(without(before, 2 * l, 2 * l + 1));
            operations_.push_back(close);
            for (int& sub : subOfBody)
                if (sub == close.first) sub = close.result;
        }
    }
}

int AssemblySchedule::getMaxHandles() const {
    std::size_t most = 0;
    for (const std::vector<int>& h : handles_) most = std::max(most, h.size());
    return static_cast<int>(most);
}

}  // namespace sinew

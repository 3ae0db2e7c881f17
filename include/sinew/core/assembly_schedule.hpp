#pragma once
// The order in which the assembly-disassembly forward dynamics (docs/closed-chain.md) joins bodies into
// subassemblies and closes loops. Built once per model; depends on the topology only.
//
// Bodies are the model's links merged across weld joints (a link welded to ground belongs to ground).
// Every non-weld tree joint and every loop becomes an "assembly joint" between an alpha body (the parent,
// or link A of a loop) and a beta body. Each assembly joint has two handles, 2j (alpha side) and 2j + 1
// (beta side). A subassembly is a set of bodies with the handles of its joints that are still pending.
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

constexpr int kGroundBody = -1;

struct AssemblyJoint {
    bool isLoop = false;
    int index = 0;  // the model's link whose tree joint this is, or the model's loop index
    int alphaBody = kGroundBody;
    int betaBody = kGroundBody;
};

struct AssemblyOperation {
    bool isClose = false;  // close a loop inside subassembly `first`, or join `first` and `second`
    int joint = 0;         // assembly joint index
    int first = 0;         // subassembly holding the alpha handle
    int second = -1;       // subassembly holding the beta handle (joins only)
    int result = 0;        // the new subassembly
    int alphaPosition = 0;  // position of handle 2*joint in `first`'s handle list
    int betaPosition = 0;   // position of handle 2*joint+1 in `second`'s (or, closing, `first`'s) list
};

class AssemblySchedule {
public:
    enum class Kind {
        Serial  // tips to root, each loop closed as soon as one subassembly holds both ends: O(N)
    };

    // Throws sinew::Error for a model the algorithm does not handle yet (virtual links) or cannot (a loop
    // between two links welded together).
    explicit AssemblySchedule(const Model& model, Kind kind = Kind::Serial);

    int getNumBodies() const { return static_cast<int>(bodyLinks_.size()); }
    int getBodyOfLink(int link) const { return linkBody_[static_cast<std::size_t>(link)]; }
    const std::vector<int>& getLinksOfBody(int body) const { return bodyLinks_[static_cast<std::size_t>(body)]; }
    const std::vector<AssemblyJoint>& getJoints() const { return joints_; }
    const std::vector<AssemblyOperation>& getOperations() const { return operations_; }
    // Subassemblies: one leaf per body (index = body), the ground leaf (index getGroundLeaf()), then one
    // per operation. Each lists its pending handles.
    int getNumSubassemblies() const { return static_cast<int>(handles_.size()); }
    int getGroundLeaf() const { return getNumBodies(); }
    const std::vector<int>& getHandles(int subassembly) const { return handles_[static_cast<std::size_t>(subassembly)]; }
    // The largest number of handles any subassembly has (the per-operation cost grows with its square).
    int getMaxHandles() const;

private:
    std::vector<int> linkBody_;               // (numLinks) body of each link or kGroundBody
    std::vector<std::vector<int>> bodyLinks_;  // (numBodies) links of each body, parents first
    std::vector<AssemblyJoint> joints_;
    std::vector<AssemblyOperation> operations_;
    std::vector<std::vector<int>> handles_;  // per subassembly
};

}  // namespace sinew

#pragma once
// The order in which the assembly-disassembly forward dynamics (docs/closed-chain.md) joins bodies into
// subassemblies and closes loops. Built once per model; depends on the topology only.
//
// Bodies are the model's links merged across weld joints (a link welded to ground belongs to ground).
// Every non-weld tree joint, every loop and the optional hang weld becomes an "assembly joint" between an
// alpha body (the parent, link A of a loop, ground for the hang) and a beta body. Each assembly joint has
// two handles, 2j (alpha side) and 2j + 1 (beta side). A subassembly is a set of bodies with the handles
// of its joints that are still pending.
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

constexpr int kGroundBody = -1;

struct AssemblyJoint {
    enum class Kind {
        Tree,  // the model's joint of link `index`
        Loop,  // the model's loop `index` (ball)
        Hang   // link `index` welded to ground where it is (the paper's body hung by the head)
    };
    Kind kind = Kind::Tree;
    int index = 0;
    int alphaBody = kGroundBody;
    int betaBody = kGroundBody;
};

struct AssemblyOperation {
    bool isClose = false;  // close a loop (or the hang) inside subassembly `first`, or join `first` and `second`
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
        // Tips to root, one operation at a time, each loop closed as soon as one subassembly holds both ends:
        // O(N) work.
        Serial,
        // Level by level: each level joins disjoint pairs of subassemblies (fewest handles first), then closes
        // the loops that became closable. The operations of a level are independent, so threads can share
        // them; a chain or a balanced tree needs O(log N) levels.
        Balanced,
        // Whichever of the two does less estimated work (sum over operations of the squared handle counts):
        // serial for trees and local loops, balanced where loops stay open across long chains.
        Automatic
    };

    // `hangLink`: a link to weld to ground where it is, or -1. Throws sinew::Error for a model the algorithm
    // does not handle yet (virtual links) or cannot (a loop between two links welded together).
    explicit AssemblySchedule(const Model& model, Kind kind = Kind::Automatic, int hangLink = -1);

    Kind getKind() const { return kind_; }
    int getNumBodies() const { return static_cast<int>(bodyLinks_.size()); }
    int getBodyOfLink(int link) const { return linkBody_[static_cast<std::size_t>(link)]; }
    const std::vector<int>& getLinksOfBody(int body) const { return bodyLinks_[static_cast<std::size_t>(body)]; }
    const std::vector<AssemblyJoint>& getJoints() const { return joints_; }
    const std::vector<AssemblyOperation>& getOperations() const { return operations_; }
    // Operations [levelStart[i], levelStart[i + 1]) form level i and are independent of each other.
    const std::vector<int>& getLevelStarts() const { return levelStarts_; }
    int getNumLevels() const { return static_cast<int>(levelStarts_.size()) - 1; }
    // Subassemblies: one leaf per body (index = body), the ground leaf (index getGroundLeaf()), then one
    // per operation. Each lists its pending handles.
    int getNumSubassemblies() const { return static_cast<int>(handles_.size()); }
    int getGroundLeaf() const { return getNumBodies(); }
    const std::vector<int>& getHandles(int subassembly) const { return handles_[static_cast<std::size_t>(subassembly)]; }
    // The largest number of handles any subassembly has (an operation costs its square).
    int getMaxHandles() const;
    // Work estimate: the sum over operations of the squared handle count of their result and inputs.
    double getCost() const;

private:
    int leafOf(int body) const;     // the body's leaf subassembly (ground's for kGroundBody)
    int currentOf(int body) const;  // the subassembly that holds the body now
    int findCurrent(int subassembly) const;
    void emitJoin(int joint);
    void emitClose(int joint);
    void closeReadyLoops(bool oneCloseLevelPerSubassembly);

    Kind kind_;
    std::vector<int> linkBody_;                // (numLinks) body of each link or kGroundBody
    std::vector<std::vector<int>> bodyLinks_;  // (numBodies) links of each body, parents first
    std::vector<AssemblyJoint> joints_;
    std::vector<AssemblyOperation> operations_;
    std::vector<int> levelStarts_;
    std::vector<std::vector<int>> handles_;  // per subassembly
    // While building: the subassembly each subassembly was merged into (itself while current).
    mutable std::vector<int> mergedInto_;
    std::vector<bool> closed_;  // per assembly joint, for loops and the hang
};

}  // namespace sinew

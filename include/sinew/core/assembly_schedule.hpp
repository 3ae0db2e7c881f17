#pragma once
// The order in which the forward dynamics (docs/closed-chain.md) folds bodies into articulated bodies, joins
// subassemblies, closes loops, and the mass properties of its bodies. Built once per model; depends on the
// topology and the links' mass properties only.
//
// Bodies are the model's links merged across weld joints (a link welded to ground belongs to ground).
// Every non-weld tree joint, every loop and the optional hang weld becomes an "assembly joint" between an
// alpha body (the parent, link A of a loop, ground for the hang) and a beta body; body b's inboard tree
// joint is assembly joint b. Each assembly joint has two handles, 2j (alpha side) and 2j + 1 (beta side).
// A subassembly is a set of bodies with the handles of its joints that are still pending.
//
// Two representations meet here. A subtree that no loop (or hang) crosses is folded into its parent body
// the articulated-body way (one articulated inertia per body, Featherstone's ABA: an Absorb operation per
// tree joint, O(1) per joint whatever the branching); if loops lie inside it, the subtree is first
// assembled and its loops closed, and the one-handle subassembly left is folded (AbsorbSubassembly). The
// bodies whose subtrees hold loop ends are assembled by the multi-handle divide-and-conquer operations
// (Leaf, Join, Close), whose cost grows with the square of the handles a subassembly carries.
//
// Virtual links (massless 6-DOF links on which forked wires meet, Link::isVirtual) are left out: they
// belong to no body, and calcForwardDynamics sets the udot of their joints to 0; whoever drives them (the
// quasi-static equilibrium of the virtual links) applies their wires' forces to the bones. A loop or a hang
// on a virtual link is an error.
#include <Eigen/Core>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

constexpr int kGroundBody = -1;
constexpr int kNoBody = -2;  // getBodyOfLink of a virtual link: not part of the dynamics

struct AssemblyJoint {
    enum class Kind {
        Tree,  // the model's joint of link `index`
        Loop,  // the model's loop `index` (ball)
        Hang   // link `index` welded to ground where it is (the paper's body hung by the head)
    };
    // What the joint lets beta do relative to alpha, which fixes its motion subspace S and constraint-force
    // basis T (docs/closed-chain.md, "Joints"): a loop is a ball, the hang a weld. A custom joint's S is its
    // H_FM at the current pose (Data::H_FM), T that subspace's orthogonal complement.
    enum class Motion { Free, Ball, Pin, Weld, Custom };
    Kind kind = Kind::Tree;
    Motion motion = Motion::Ball;
    int index = 0;
    int alphaBody = kGroundBody;
    int betaBody = kGroundBody;
};

struct AssemblyOperation {
    enum class Kind {
        // Fold tree joint `joint`'s child body (with everything already folded into it) into its parent
        // body's articulated inertia (into nothing when the parent is ground).
        Absorb,
        // The same for the child's subassembly `first`, whose one pending handle is the joint's beta handle.
        AbsorbSubassembly,
        // Body `first`'s handle equations (subassembly `result` = the body's leaf) from its articulated
        // inertia; every Absorb into the body comes before.
        Leaf,
        // Join subassemblies `first` (holding the alpha handle) and `second` (the beta handle) into `result`.
        Join,
        // Close a loop (or the hang) whose two handles are both in `first`, giving `result`.
        Close
    };
    Kind kind = Kind::Join;
    int joint = -1;         // assembly joint index (Absorb, Join, Close)
    int first = 0;          // Leaf: the body; AbsorbSubassembly: the child's subassembly; Join, Close: the
                            // subassembly holding the alpha handle
    int second = -1;        // Join: the subassembly holding the beta handle
    int result = -1;        // Leaf, Join, Close: the new subassembly
    int alphaPosition = 0;  // position of handle 2*joint in `first`'s handle list
    int betaPosition = 0;   // position of handle 2*joint+1 in `second`'s (or, closing, `first`'s) list
};

// A rigid body of the dynamics: one link and the links welded to it.
struct AssemblyBody {
    std::vector<int> links;  // parents first; links.front() is the link whose joint is the body's inboard joint
    double mass = 0;                                    // kg, all its links
    Eigen::Vector3d com = Eigen::Vector3d::Zero();      // m, centre of mass in links.front()'s frame
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // kg m^2, about com, in links.front()'s axes
};

class AssemblySchedule {
public:
    enum class Kind {
        // Tips to root: every loop-free subtree folded into its parent body (articulated-body algorithm), the
        // skeleton joined one operation at a time, each loop closed as soon as one subassembly holds both
        // ends: O(N) work.
        Serial,
        // Divide and conquer throughout, level by level: each level joins disjoint pairs of subassemblies
        // (fewest handles first), then closes the loops that became closable. The operations of a level are
        // independent, so threads can share them; a chain or a balanced tree needs O(log N) levels.
        Balanced,
        // Whichever of the two does less estimated work (getCost): serial for trees and local loops,
        // balanced where loops stay open across long chains. Serial where a body is a point mass.
        Automatic
    };

    // `hangLink`: a link to weld to ground where it is, or -1. Throws sinew::Error for what the algorithm
    // does not handle: a loop or hang on a virtual link, a loop between two links welded together, a point
    // mass in the balanced schedule.
    explicit AssemblySchedule(const Model& model, Kind kind = Kind::Automatic, int hangLink = -1);

    Kind getKind() const { return kind_; }
    int getNumBodies() const { return static_cast<int>(bodies_.size()); }
    // The body of a link: kGroundBody when welded to ground, kNoBody for a virtual link.
    int getBodyOfLink(int link) const { return linkBody_[static_cast<std::size_t>(link)]; }
    const AssemblyBody& getBody(int body) const { return bodies_[static_cast<std::size_t>(body)]; }
    const std::vector<int>& getVirtualLinks() const { return virtualLinks_; }
    const std::vector<AssemblyJoint>& getJoints() const { return joints_; }
    // How each tree joint j enters the assembly: Absorb, AbsorbSubassembly or Join.
    AssemblyOperation::Kind getTreeJointOperation(int joint) const { return treeOperation_[static_cast<std::size_t>(joint)]; }
    const std::vector<AssemblyOperation>& getOperations() const { return operations_; }
    // Operations [levelStart[i], levelStart[i + 1]) form level i and are independent of each other.
    const std::vector<int>& getLevelStarts() const { return levelStarts_; }
    int getNumLevels() const { return static_cast<int>(levelStarts_.size()) - 1; }
    // Subassemblies: one leaf per body (index = body; no handles when the body is absorbed), the ground
    // leaf (index getGroundLeaf()), then one per Join or Close. Each lists its pending handles.
    int getNumSubassemblies() const { return static_cast<int>(handles_.size()); }
    int getGroundLeaf() const { return getNumBodies(); }
    const std::vector<int>& getHandles(int subassembly) const { return handles_[static_cast<std::size_t>(subassembly)]; }
    // The largest number of handles any subassembly has (an operation costs its square).
    int getMaxHandles() const;
    // Work estimate: 1 per Absorb, and for the other operations the squared handle count of their inputs.
    double getCost() const;

private:
    // The constructor's steps, in order.
    void buildBodies(const Model& model);
    void addLoopJoints(const Model& model);
    void addHangJoint(const Model& model, int hangLink);
    void chooseTreeOperations(const Model& model, int hangLink);
    void buildLeaves(int numTreeJoints);
    // A body whose central inertia is singular (point masses, massless bodies), or -1.
    int findPointMassBody() const;
    void scheduleSerial(int numTreeJoints);
    void scheduleBalanced(int numTreeJoints);
    int leafOf(int body) const;     // the body's leaf subassembly (ground's for kGroundBody)
    int currentOf(int body) const;  // the subassembly that holds the body now
    int findCurrent(int subassembly) const;
    void emitAbsorb(int joint);
    void emitAbsorbSubassembly(int joint);
    void emitLeaf(int body);
    void emitJoin(int joint);
    void emitClose(int joint);
    void closeReadyLoops(bool oneCloseLevelPerSubassembly);

    Kind kind_;
    std::vector<int> linkBody_;         // (numLinks) body of each link, kGroundBody or kNoBody
    std::vector<AssemblyBody> bodies_;  // (numBodies)
    std::vector<int> virtualLinks_;
    std::vector<AssemblyJoint> joints_;
    std::vector<AssemblyOperation::Kind> treeOperation_;  // (tree joints)
    std::vector<AssemblyOperation> operations_;
    std::vector<int> levelStarts_;
    std::vector<std::vector<int>> handles_;  // per subassembly
    // While building: the subassembly each subassembly was merged into (itself while current).
    mutable std::vector<int> mergedInto_;
    std::vector<bool> closed_;  // per assembly joint, for loops and the hang
};

}  // namespace sinew

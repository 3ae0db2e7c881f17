#pragma once
// The per-frame table of joint loads of a tension analysis (docs/tensions-from-motion.md, "Somatosensory
// outputs"): what every joint and loop closure carries while the solved tensions, the contact forces and the
// measured loads move the body as the motion does. calcJointReactions (docs/joint-loads.md) on the frame's
// q, u, udot with those forces; one inverse-dynamics pass more per frame.
#include <memory>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/joint_reactions.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tensions/contact_columns.hpp"
#include "sinew/tools/motion_frames.hpp"
#include "sinew/tools/tension_analysis.hpp"

namespace sinew {

class JointLoadTable {
public:
    // Names the columns of `table`: per joint (link order) <joint>_mx _my _mz (N m) and _fx _fy _fz (N),
    // F_BM: the load the parent (or ground) applies to the joint's child link, at the joint centre, in the
    // child link's axes, the joint's own generalized forces included (Simbody's convention); then per loop
    // <loop>_fx _fy _fz (N), the force on its link B, in link B's axes. `contacts`: the analysis's contact
    // block (one of TensionAnalysisOptions::columns), or null without contact.
    JointLoadTable(const Model& model, std::shared_ptr<const ContactColumns> contacts, StorageTable& table);

    // The frame's row from the analysis's solution: the frame's tensions, contact variables and loop forces.
    // `analysis` must have just solved `motion` (its options' columns hold `contacts`).
    void appendFrame(const MotionFrame& motion, const TensionAnalysis& analysis, const TensionFrame& frame);
    // A frame without input: zeros, as in every other table.
    void appendMissing(double time);

    // The last frame's reactions (appendFrame).
    const JointReactionsData& getReactions() const { return reactions_; }

private:
    void addContactForces(const TensionAnalysis& analysis);

    const Model& model_;
    std::shared_ptr<const ContactColumns> contacts_;
    StorageTable& table_;
    Data data_;
    JointReactionsData reactions_;
    std::vector<SpatialVector> bodyForces_;    // (numLinks) wires' and contacts' link forces, Data::F_G convention
    std::vector<SpatialVector> linkForces_;    // (numLinks) those and the measured loads
    Eigen::VectorXd appliedGeneralized_;       // (nu) what the joints are given as applied generalized forces
};

}  // namespace sinew

#include "sinew/tools/joint_load_table.hpp"

#include <algorithm>
#include <cassert>
#include <string>
#include <utility>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/loop_force_columns.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"

namespace sinew {

JointLoadTable::JointLoadTable(const Model& model, std::shared_ptr<const ContactColumns> contacts, StorageTable& table)
    : model_(model),
      contacts_(std::move(contacts)),
      table_(table),
      data_(model),
      reactions_(model),
      bodyForces_(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero()),
      linkForces_(bodyForces_),
      appliedGeneralized_(Eigen::VectorXd::Zero(model.getNumU())) {
    table.name = "Joint loads (F_BM: on the child link at the joint centre, child link axes)";
    table.columns.clear();
    for (int i = 0; i < model.getNumLinks(); ++i)
        for (const char* column : {"_mx", "_my", "_mz", "_fx", "_fy", "_fz"})
            table.columns.push_back(model.getJoint(i).name + column);
    for (int k = 0; k < model.getNumLoops(); ++k)
        for (const char* column : {"_fx", "_fy", "_fz"}) table.columns.push_back(model.getLoop(k).name + column);
}

// Each contact's force as a link force on its foot: the wrench about the centre of pressure moved to the
// link's origin. Needs data_'s position kinematics.
void JointLoadTable::addContactForces(const TensionAnalysis& analysis) {
    const auto& blocks = analysis.getOptions().columns;
    const auto block = std::find_if(blocks.begin(), blocks.end(), [&](const std::shared_ptr<ProblemColumns>& b) {
        return b.get() == contacts_.get();
    });
    assert(block != blocks.end());
    const int start = analysis.getColumnStart(static_cast<int>(block - blocks.begin()));
    const auto beta = analysis.getSolution().x.segment(start, contacts_->count());
    for (int c = 0; c < static_cast<int>(model_.getContacts().size()); ++c) {
        const ContactWrench wrench = contacts_->calcWrench(data_, c, beta);
        const std::size_t link = static_cast<std::size_t>(model_.getContacts()[static_cast<std::size_t>(c)].link);
        SpatialVector atPressure;
        atPressure << wrench.moment, wrench.force;
        bodyForces_[link] += shiftForce(atPressure, data_.p_GB[link] - wrench.centreOfPressure);
    }
}

void JointLoadTable::appendFrame(const MotionFrame& motion, const TensionAnalysis& analysis, const TensionFrame& frame) {
    calcPositionKinematics(model_, data_, motion.q);
    calcWirePaths(model_, data_);
    calcWireLinkForces(model_, data_, frame.tension);
    bodyForces_ = data_.F_G;
    if (contacts_) addContactForces(analysis);
    // The loops carry the solution's forces (x ends with them, 3 per loop, ground axes), given as link forces:
    // where loops repeat constraints (the whole-body model's do) those forces are one choice among many, and
    // the joints' loads must be the ones that go with the tensions solved beside them.
    const Eigen::VectorXd& x = analysis.getSolution().x;
    const Eigen::Index loopStart = x.size() - 3 * model_.getNumLoops();
    for (int k = 0; k < model_.getNumLoops(); ++k)
        addLoopForce(model_, data_, k, x.segment<3>(loopStart + 3 * k), bodyForces_);
    for (std::size_t i = 0; i < linkForces_.size(); ++i)
        linkForces_[i] = motion.appliedLinkForces[i] + bodyForces_[i];

    // The joints' applied generalized forces: what the solution leaves to generalized forces, i.e. the
    // residual tau - A x, the reserves' forces, and the wires' forces on coordinates (moving points, wires
    // over an ellipsoid). Taken as tau less the generalized forces of what is given as link forces, so that
    // the equations close on every DOF whatever the frame's status: TensionFrame::residual holds the whole
    // tau on unactuated rows, not tau - A x, and TensionFrame::reserve is the phase-1 LP's advice, which no
    // solution applies. calcJointReactions then finds no loop force left to add (C f = 0).
    data_.scratchF_G = bodyForces_;
    calcGeneralizedForcesFromLinkForces(model_, data_, appliedGeneralized_);
    appliedGeneralized_ = frame.tau - appliedGeneralized_;

    calcJointReactions(model_, data_, motion.q, motion.u, motion.udot, appliedGeneralized_, linkForces_, reactions_);
    std::vector<double> row;
    row.reserve(table_.columns.size());
    for (const SpatialVector& F : reactions_.F_BM) row.insert(row.end(), F.data(), F.data() + 6);
    for (int k = 0; k < model_.getNumLoops(); ++k) {
        const Eigen::Vector3d f_B = data_.R_GB[static_cast<std::size_t>(model_.getLoop(k).linkB)].transpose() *
                                    x.segment<3>(loopStart + 3 * k);
        row.insert(row.end(), f_B.data(), f_B.data() + 3);
    }
    table_.times.push_back(motion.time);
    table_.rows.push_back(std::move(row));
}

void JointLoadTable::appendMissing(double time) {
    table_.times.push_back(time);
    table_.rows.emplace_back(table_.columns.size(), 0.0);
}

}  // namespace sinew

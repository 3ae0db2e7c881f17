#include "sinew/tools/motion_contacts.hpp"

#include <string>

#include "sinew/core/kinematics.hpp"

namespace sinew {

MotionContacts::MotionContacts(const Model& model, const CoordinateTrajectory& trajectory,
                               const ContactDetectionOptions& options, StorageTable& table)
    : model_(model),
      detection_(detectContacts(model, trajectory.q, trajectory.qdot, options)),
      columns_(std::make_shared<ContactColumns>(model)),
      table_(table),
      data_(model) {
    for (int link = 0; link < model.getNumLinks(); ++link) {
        const Joint& joint = model.getJoint(link);
        if (joint.parent == kGround && joint.type == JointType::Free && !model.getLink(link).isVirtual)
            roots_.push_back(link);
    }
    table.name = "Contact forces";
    table.columns = {"root_force_residual", "root_moment_residual"};
    for (const Contact& contact : model.getContacts())
        for (const char* column : {"_in_contact", "_fx", "_fy", "_fz", "_copx", "_copy", "_copz", "_mx", "_my", "_mz"})
            table.columns.push_back(contact.name + column);
}

void MotionContacts::prepareFrame(int index) { columns_->setInContact(detection_.inContact[static_cast<std::size_t>(index)]); }

void MotionContacts::appendFrame(const MotionFrame& motion, const TensionAnalysis& analysis, const TensionFrame& frame) {
    // A free joint's u is [angular; linear] (model.hpp): the root's residual moment, then force.
    double force = 0, moment = 0;
    for (const int root : roots_) {
        const int u = model_.getJoint(root).uStart;
        moment += frame.residual.segment<3>(u).squaredNorm();
        force += frame.residual.segment<3>(u + 3).squaredNorm();
    }
    std::vector<double> row = {std::sqrt(force), std::sqrt(moment)};
    calcPositionKinematics(model_, data_, motion.q);
    const int block = static_cast<int>(analysis.getOptions().columns.size()) - 1;
    const auto beta = analysis.getSolution().x.segment(analysis.getColumnStart(block), columns_->count());
    for (int c = 0; c < static_cast<int>(model_.getContacts().size()); ++c) {
        const ContactWrench wrench = columns_->calcWrench(data_, c, beta);
        row.push_back(columns_->getInContact()[static_cast<std::size_t>(c)] ? 1.0 : 0.0);
        for (const Eigen::Vector3d* v : {&wrench.force, &wrench.centreOfPressure, &wrench.moment})
            row.insert(row.end(), v->data(), v->data() + 3);
    }
    table_.times.push_back(motion.time);
    table_.rows.push_back(std::move(row));
}

void MotionContacts::appendMissing(double time) {
    table_.times.push_back(time);
    table_.rows.emplace_back(table_.columns.size(), 0.0);
}

}  // namespace sinew

#pragma once
// The feet of a motion without force plates, for the tension analysis (docs/tensions-from-motion.md,
// "Contact without force plates"): the frames each contact touches the ground (contact_detection.hpp),
// the contact unknowns as a column block (contact_columns.hpp) whose flags follow the frames, and the
// per-frame table of what the solution gives: the floating root's remaining residual and, per contact,
// its flag, force, centre of pressure and moment.
#include <memory>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/tensions/contact_columns.hpp"
#include "sinew/tools/contact_detection.hpp"
#include "sinew/tools/motion_frames.hpp"
#include "sinew/tools/tension_analysis.hpp"

namespace sinew {

class MotionContacts {
public:
    // Detects the contact frames of `trajectory` (its q and qdot rows) and names the columns of `table`
    // (root_force_residual N, root_moment_residual N m, then per contact <name>_in_contact, _fx _fy _fz N,
    // _copx _copy _copz m, _mx _my _mz N m, ground axes), to which the frames' rows are appended.
    // Throws sinew::Error as detectContacts does.
    MotionContacts(const Model& model, const CoordinateTrajectory& trajectory, const ContactDetectionOptions& options,
                   StorageTable& table);

    // The block to put in TensionAnalysisOptions::columns, last.
    const std::shared_ptr<ContactColumns>& getColumns() const { return columns_; }
    const ContactDetection& getDetection() const { return detection_; }

    // Before the analysis solves trajectory row `index`: its contact flags.
    void prepareFrame(int index);
    // After: the frame's row, from the analysis's solution (the block is its last options.columns entry).
    void appendFrame(const MotionFrame& motion, const TensionAnalysis& analysis, const TensionFrame& frame);
    // A frame without input: zeros, as in every other table.
    void appendMissing(double time);

private:
    const Model& model_;
    ContactDetection detection_;
    std::shared_ptr<ContactColumns> columns_;
    StorageTable& table_;
    Data data_;
    std::vector<int> roots_;  // links of the free joints on ground that are not virtual links
};

}  // namespace sinew

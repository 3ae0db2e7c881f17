#pragma once
// Wire tensions over a whole motion (docs/tensions-from-motion.md): a coordinates table processed as
// OpenSim's tools process it (coordinate_preprocessing.hpp), measured external loads, then
// TensionAnalysis::calcFrame per frame. Every frame is kept: an infeasible or failed one is flagged in the
// report with its residuals, never dropped. A motion row with a non-finite coordinate (read with
// NonFinite::Allow) is left out of the splines and still gets its row in every output table, at its own
// time, flagged kMissingInputStatus with zero tensions (outputs never hold NaN).
#include <functional>
#include <limits>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/model.hpp"
#include "sinew/io/external_loads.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tools/contact_detection.hpp"
#include "sinew/tools/tension_analysis.hpp"

namespace sinew {

// Report status of a frame whose motion row had a non-finite coordinate; 0-2 are DistributionStatus.
constexpr int kMissingInputStatus = 3;

struct TensionMotionOptions {
    TensionAnalysisOptions analysis;
    double lowpassCutoffHz = -1;  // negative: no filtering
    double startTime = -std::numeric_limits<double>::infinity();  // s
    double finalTime = std::numeric_limits<double>::infinity();
    // false: udot is the second derivative of the coordinates' quintic splines (the inverse dynamics tool);
    // true: the first derivative of quintic splines through the speeds at every processed row (OpenSim's
    // AnalyzeTool states, which StaticOptimization differentiates again).
    bool accelerationsFromSpeedSplines = false;
    // OpenSim's step_interval N: only the first and last frames and those whose row in the processed table
    // (CoordinateTrajectory::firstRow + frame) is a multiple of N are solved and reported, as AnalyzeTool
    // records an analysis at begin, at end and on the steps Analysis::proceed accepts.
    int stepInterval = 1;
    // Without external loads, the feet the model names (Model::getContacts) get contact forces as unknowns on
    // the frames they touch the ground (docs/tensions-from-motion.md, "Contact without force plates").
    bool contact = true;
    ContactDetectionOptions contactDetection;
    std::function<void(int frame, int frames)> onFrame;  // progress, optional
};

struct TensionMotionResult {
    StorageTable tensions;     // N, one column per wire (its name)
    StorageTable activations;  // static optimization: one column per wire; empty otherwise
    StorageTable reserves;     // static optimization with reserves: N m or N, one column per reserve
    // With contact: per frame the root's residual force (N) and moment (N m) and, per contact, in_contact,
    // force (N), centre of pressure (m) and moment (N m) in ground axes (motion_contacts.hpp); empty otherwise.
    StorageTable contact;
    // Per frame, what each joint and loop carries (joint_load_table.hpp, docs/tensions-from-motion.md,
    // "Somatosensory outputs"): per joint <joint>_mx _my _mz (N m), _fx _fy _fz (N), the parent's load on the
    // child link at the joint centre in the child link's axes; per loop <loop>_fx _fy _fz (N) on its link B,
    // in B's axes.
    StorageTable jointLoads;
    // Per frame, per ligament (WireKind::Ligament) with a cross-section: tension / cross-section (Pa), in wire
    // order; empty when no ligament has one.
    StorageTable ligamentStress;
    // Per frame: status (0 optimal, 1 infeasible, 2 failed, 3 missing input), Z (N² m²), active_wires, iterations,
    // ipopt (1: solved by Ipopt), unactuated_residual (|tau| on DOFs no wire reaches), then <coordinate>_residual and
    // <coordinate>_reserve per DOF (see TensionFrame; named as getSpeedNames names the speeds).
    StorageTable report;
    int flaggedFrames = 0;  // frames whose status is not optimal: the three counts below together
    int infeasibleFrames = 0, failedFrames = 0;
    int ipoptFrames = 0;  // frames solved by Ipopt (report column ipopt = 1): the fallback, or exponent != 2
    // Indices into motion.rows of the rows in the time range whose coordinates were not all finite.
    std::vector<int> missingRows;
    // Per solved frame (report rows with status 0-2), the wall-clock seconds of its inverse dynamics, wire
    // Jacobian and distribution: the paper's Table 2 figure. Kept out of the tables, which stay reproducible.
    std::vector<double> frameSeconds;
    // Per solved frame, the wall-clock seconds of its joint loads (after frameSeconds' span).
    std::vector<double> jointLoadSeconds;
};

// The run in figures for a person (what `sinew tensions` prints, the paper's Table 2): over the solved
// frames, seconds per frame and Z (report column Z), and with contact the root's residual force on the frames
// a foot is down, as a share of the body's weight.
struct TensionMotionSummary {
    int frames = 0, solvedFrames = 0;
    double medianSeconds = 0, meanSeconds = 0;  // s per solved frame
    double medianJointLoadSeconds = 0;          // s per solved frame, the joint loads alone
    double medianZ = 0, meanZ = 0, maxZ = 0;    // N² m²
    int contactFrames = 0;                      // frames with at least one contact in touch (contact table)
    double bodyWeight = 0;                      // N, |gravity| times the links' total mass
    double medianRootResidual = 0, maxRootResidual = 0;  // N over the contact frames
};
TensionMotionSummary summarizeTensionMotion(const Model& model, const TensionMotionResult& result);

// The frames (report rows solved in both: status 0-2) where `run`'s Z is at most `reference`'s, the two runs
// being of the same motion and options (the paper's comparison: the QP's Z against the LP's). Throws
// sinew::Error when their report times differ.
int countFramesWithZAtMost(const TensionMotionResult& run, const TensionMotionResult& reference);

// The table's columns must be exactly the model's coordinates, quaternions included (readCoordinateSamples
// says what is missing or extra). Throws sinew::Error when the finite rows left
// are too few for the splines.
TensionMotionResult runTensionAnalysis(const Model& model, const StorageTable& motion, const ExternalLoads* loads,
                                       const TensionMotionOptions& options);

// States given frame by frame (e.g. an OpenSim states file, osim_states.hpp): q, u = states.qdot and
// udot = states.qddot at states.times, used as they are (options' cut-off, time range and
// accelerationsFromSpeedSplines do not apply). Throws sinew::Error when the sizes do not fit the model.
TensionMotionResult runTensionAnalysis(const Model& model, const CoordinateTrajectory& states,
                                       const ExternalLoads* loads, const TensionMotionOptions& options);

}  // namespace sinew

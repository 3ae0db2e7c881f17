#pragma once
// Inverse kinematics: the coordinates q that put the model's markers where a motion capture saw them, frame
// by frame, as OpenSim's InverseKinematicsTool poses the problem (weighted marker and coordinate tasks,
// loops and couplers strictly kept, clamped coordinates within their ranges). Solved by Levenberg-Marquardt
// on the configuration manifold (ball and free joints through their quaternions), warm-started from the
// previous frame, so that coordinates no task observes stay where they were. docs/inverse-kinematics.md.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/marker.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"
#include "sinew/tools/block_arrow_cholesky.hpp"

namespace sinew {

struct MarkerTask {
    std::string marker;  // a marker of the solver's marker set
    double weight = 1;
};

// A coordinate held near a value (OpenSim's IKCoordinateTask): its target per frame comes with the
// frame's targets. Only coordinates with qdot = u (pin and custom joints).
struct CoordinateTask {
    std::string coordinate;
    double weight = 1;
};

// A frame fixed on a link held near a measured orientation (a BVH segment's frame): its cost is
// 1/2 weight |theta|^2, theta the rotation vector from the target to the frame.
struct OrientationTask {
    std::string link;
    Eigen::Matrix3d R_BF = Eigen::Matrix3d::Identity();  // the tracked frame's axes in the link frame
    double weight = 1;  // m^2/rad^2: a 1 rad error costs what a sqrt(weight) m marker error does
};

struct InverseKinematicsOptions {
    // Converged when a step moves no task's target by more than this (m; rad for coordinate tasks).
    double accuracy = 1e-5;
    int maxIterations = 100;
    double constraintTolerance = 1e-8;  // m, loop gaps allowed at convergence
};

// One frame's targets, in task order.
struct InverseKinematicsTargets {
    Eigen::Matrix3Xd markers;     // m, ground axes; a column with a NaN is a marker not seen this frame
    Eigen::VectorXd coordinates;  // rad or m
    // R_GF per orientation task (ground axes); empty when there are none; one with a NaN is not seen.
    std::vector<Eigen::Matrix3d> orientations = {};
};

struct InverseKinematicsReport {
    bool converged = false;
    int iterations = 0;
    int markersSeen = 0;
    double rmsMarkerError = 0;  // m, over the markers seen (unweighted, as OpenSim reports it)
    double maxMarkerError = 0;  // m
    int worstMarker = -1;       // task index of the largest error, -1 when no marker was seen
    double constraintViolation = 0;  // m, largest loop gap
    Eigen::VectorXd markerErrors;    // m, per marker task; NaN where not seen
    int orientationsSeen = 0;
    double rmsOrientationError = 0;  // rad, over the orientations seen
    double maxOrientationError = 0;  // rad
};

class InverseKinematicsSolver {
public:
    // Throws sinew::Error naming a task whose marker or coordinate does not exist, a coordinate task on a
    // quaternion, or a weight that is negative or not finite.
    InverseKinematicsSolver(const Model& model, std::vector<Marker> markers, std::vector<MarkerTask> markerTasks,
                            std::vector<CoordinateTask> coordinateTasks, InverseKinematicsOptions options = {},
                            std::vector<OrientationTask> orientationTasks = {});

    // Moves q (nq; in: the warm start, usually the previous frame's solution) to the frame's best fit.
    // Throws sinew::Error when the targets' sizes do not match the tasks or q is not finite.
    InverseKinematicsReport solve(const InverseKinematicsTargets& targets, Eigen::VectorXd& q);
    // Moves q's virtual links (a forked wire's massless node, which no target sees) to where the wires
    // through them balance at rest (calcVirtualLinkEquilibriumAtRest under their force laws, zero speeds),
    // warm-started from q's; nothing for a model without them.
    const VirtualLinkEquilibriumStatus& balanceVirtualLinks(Eigen::VectorXd& q);

    const std::vector<MarkerTask>& getMarkerTasks() const { return markerTasks_; }
    const Model& getModel() const { return model_; }
    const std::vector<CoordinateTask>& getCoordinateTasks() const { return coordinateTasks_; }
    const std::vector<OrientationTask>& getOrientationTasks() const { return orientationTasks_; }

private:
    struct Score {
        double cost;   // the tasks'
        double merit;  // the cost plus the loops' gaps, weighted to come first
        bool closed;   // the loops closed to roundoff
    };
    // Fills r_ and c_ (and A_, G_ with the Jacobian) at q.
    Score evaluate(const InverseKinematicsTargets& targets, const Eigen::VectorXd& q, bool withJacobian);
    // jointMotion_G_ of `links` at the pose in data_.
    void calcJointMotions(const std::vector<int>& links);
    template <bool angular, class Visit>
    void visitJacobianColumns(int link, const Eigen::Vector3d& p_G, Visit&& visit) const;
    // rows += scale x d(p_G)/du for a point p_G fixed on `link`.
    void addPointJacobian(int link, const Eigen::Vector3d& p_G, double scale, Eigen::Ref<Eigen::MatrixXd> rows) const;
    // rows += scale_G x (the link's angular velocity in G)/du.
    void addAngularJacobian(int link, const Eigen::Matrix3d& scale_G, Eigen::Ref<Eigen::MatrixXd> rows) const;
    void addPointGradient(int link, const Eigen::Vector3d& p_G, const Eigen::Vector3d& force, Eigen::VectorXd& gradient) const;
    // A task's residual rows r at the pose in data_ (false, and zeros, where not seen this frame), their
    // rows of the Jacobian (added to zeroed rows), and their share A^T r of the gradient (added).
    bool evaluateMarker(std::size_t task, const InverseKinematicsTargets& targets, Eigen::Ref<Eigen::VectorXd> r);
    void addMarkerJacobian(std::size_t task, Eigen::Ref<Eigen::MatrixXd> A) const;
    void addMarkerGradient(std::size_t task, const Eigen::Vector3d& r, Eigen::VectorXd& gradient) const;
    bool evaluateOrientation(std::size_t task, const InverseKinematicsTargets& targets, Eigen::Ref<Eigen::VectorXd> r);
    Eigen::Matrix3d calcOrientationScale(std::size_t task, const Eigen::Vector3d& r) const;
    void addOrientationJacobian(std::size_t task, const Eigen::Vector3d& r, Eigen::Ref<Eigen::MatrixXd> A) const;
    void addOrientationGradient(std::size_t task, const Eigen::Vector3d& r, Eigen::VectorXd& gradient) const;
    // Every coordinate task's rows.
    void evaluateCoordinates(const InverseKinematicsTargets& targets, const Eigen::VectorXd& q,
                             Eigen::Ref<Eigen::VectorXd> r, Eigen::Ref<Eigen::MatrixXd> A, bool withJacobian);
    std::pair<Eigen::Vector3d, Eigen::Vector3d> calcLoopPoints(std::size_t loop) const;
    void addLoopJacobian(std::size_t loop, Eigen::Ref<Eigen::MatrixXd> G) const;
    void addLoopGradient(std::size_t loop, const Eigen::Vector3d& multiplier, Eigen::VectorXd& gradient) const;
    // The loops' gaps into c_ (and, with the Jacobian, G_) at the pose in data_.
    void fillLoopGaps(bool withJacobian);
    Eigen::Index markerRow(std::size_t task) const { return 3 * static_cast<Eigen::Index>(task); }
    Eigen::Index coordinateRow(std::size_t task) const { return markerRow(markerTasks_.size()) + static_cast<Eigen::Index>(task); }
    Eigen::Index orientationRow(std::size_t task) const {
        return coordinateRow(coordinateTasks_.size()) + 3 * static_cast<Eigen::Index>(task);
    }
    bool isObserved(Eigen::Index col) const;
    std::pair<int, double> findFreeColumn(int u) const;
    void refreshCurvature(const InverseKinematicsTargets& targets, const Eigen::VectorXd& q);
    bool isSmallStep(const Eigen::VectorXd& delta) const;
    // 1/2 sum of the weights of the tasks seen x accuracy^2: the cost of a fit that misses every target by
    // the accuracy.
    double calcCostAtAccuracy(const InverseKinematicsTargets& targets) const;
    void checkFrame(const InverseKinematicsTargets& targets, const Eigen::VectorXd& q) const;
    void fillReport(InverseKinematicsReport& report) const;
    // A step in the free unknowns as speeds (nu): 0 for locked, coupled and virtual-link speeds.
    Eigen::VectorXd toSpeeds(const Eigen::VectorXd& delta) const;
    void closeLoops(Eigen::VectorXd& q);
    // observed_, observedIndex_, observedA_ and observedG_ at the last evaluation.
    void gatherObservedColumns();
    // observed_ and blockSizes_ from observedByIndex_: its unknowns reordered into the independent blocks and
    // the trunk for cholesky_.
    void orderObservedColumns();
    // The damped, constrained Gauss-Newton step in the free unknowns from the last evaluation, clamped
    // coordinates kept within their ranges by an active set. damping is raised to what the step's Hessian
    // needed to be positive definite.
    Eigen::VectorXd solveStep(double& damping, const Eigen::VectorXd& q);
    // One pass of it over the observed unknowns, the entries `fixed` held at fixedStep.
    Eigen::VectorXd solveKkt(double& damping, const std::vector<bool>& fixed, const Eigen::VectorXd& fixedStep);

    const Model& model_;
    std::vector<Marker> markers_;
    std::vector<MarkerTask> markerTasks_;
    std::vector<CoordinateTask> coordinateTasks_;
    InverseKinematicsOptions options_;
    std::vector<OrientationTask> orientationTasks_;
    std::vector<int> taskLink_;  // per orientation task: its link
    Data data_;
    std::vector<int> taskMarker_;      // per marker task: index into markers_
    std::vector<int> taskCoordinate_;  // per coordinate task: its index in q
    std::vector<int> freeColumn_;      // per u: the unknown it moves, or -1 (locked, coupled or a virtual link)
    std::vector<int> jointOfU_;        // per u: its joint
    std::vector<int> couplerOfU_;      // per u: the coupler whose dependent coordinate it is, or -1
    // Free unknowns of clamped coordinates with a finite range, with the coordinate's index in q.
    std::vector<std::pair<int, int>> boundedColumns_;
    int numFree_ = 0;
    // Per evaluation: weighted residual r, its Jacobian A (rows x free unknowns), the loop gaps c and their
    // Jacobian G.
    Eigen::VectorXd r_, c_;
    Eigen::MatrixXd A_, G_;
    Eigen::VectorXd multipliers_;    // the loops' Lagrange multipliers from the last step
    std::vector<JointMotion> jointMotion_G_;  // per link at the last evaluation, about its joint centre
    std::vector<int> jacobianLinks_;   // the links whose joints move a target or loop
    std::vector<int> loopChainLinks_;  // those whose joints move a loop
    Eigen::MatrixXd curvature_;       // the Lagrangian's curvature beyond A^T A where last refreshed
    double curvatureResiduals_ = 0;   // |[r; multipliers]| there
    Eigen::VectorXd curvaturePose_, curvatureSpeed_;  // refreshCurvature's stepped pose and unit step
    bool useCurvature_ = true;        // in this solve's steps
    std::vector<Eigen::Index> observedByIndex_;  // the free unknowns a target or loop observes, at the last step
    std::vector<Eigen::Index> partitionedFor_;   // the observedByIndex_ that observed_'s order was made for
    std::vector<Eigen::Index> observed_;       // observedByIndex_ in cholesky_'s order (orderObservedColumns)
    std::vector<Eigen::Index> observedIndex_;  // per free unknown: its place in observed_, or -1
    Eigen::MatrixXd observedA_, observedG_;    // A_'s and G_'s columns of observed_
    std::vector<Eigen::Index> loopColumns_;    // the free unknowns the loops move, while closing them
    Eigen::MatrixXd stepHessian_;     // the step's: A^T A + curvature_ (observed x observed)
    Eigen::MatrixXd H_;               // stepHessian_ damped, with the active set's rows fixed
    std::vector<int> columnLink_;             // per free unknown: the link whose joint it belongs to
    std::vector<std::vector<int>> childLinks_;  // per link
    std::vector<Eigen::Index> blockSizes_;    // observed_'s independent subtrees, then the trunk (cholesky_)
    BlockArrowCholesky cholesky_;             // of H_
    VirtualLinkEquilibriumData equilibrium_;  // balanceVirtualLinks'
    Eigen::VectorXd markerErrors_;
    int markersSeen_ = 0;
    Eigen::VectorXd orientationErrors_;  // rad, per orientation task; NaN where not seen
};

// A whole capture through the solver: every frame of `targets` in order, each warm-started from the last
// (the first from q0). No target sees a virtual link (a forked wire's massless node): each frame places them
// where the wires through them balance at rest (calcVirtualLinkEquilibrium under their force laws, zero
// speeds), as the hang holds them, warm-started from the last frame's; left where q0 has them, they would
// stay behind at the start while the body moves on. onFrame reports progress.
struct InverseKinematicsMotion {
    std::vector<Eigen::VectorXd> q;
    std::vector<InverseKinematicsReport> reports;
};
InverseKinematicsMotion solveInverseKinematics(InverseKinematicsSolver& solver, const Eigen::VectorXd& q0,
                                               const std::vector<InverseKinematicsTargets>& targets,
                                               const std::function<void(int frame, int frames)>& onFrame = {});

}  // namespace sinew

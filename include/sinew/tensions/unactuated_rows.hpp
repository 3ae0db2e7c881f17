#pragma once
// The rows of a frame's tension problem that no variable can move (docs/tensions-from-motion.md): a
// floating root under internal wire forces and no residual actuators. Such a row of A is zero to rounding;
// left in, it would look like a DOF needing enormous tensions. Its generalized force is not distributed: the
// row's target becomes what the variables can still balance there, and the rest is the frame's unactuated
// residual, reported in Z (the paper's Eq. 10) and never hidden.
#include <Eigen/Core>
#include <Eigen/LU>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"
#include "sinew/tensions/distribution_problem.hpp"

namespace sinew {

class UnactuatedRows {
public:
    // threshold: a row whose largest |generalized force per unit variable| is below this times the frame's
    // largest is unactuated (relative).
    UnactuatedRows(const Model& model, double threshold);

    // Marks `unactuated` (nu: 1 on unactuated rows) and rewrites those rows' targets; returns the unactuated
    // residual, |tau - target| over them. Columns [externalBegin, externalEnd) of problem.A act from outside
    // the body (reserves, contacts: problem_columns.hpp) and are judged by their entries; the others (wires,
    // loops) are internal. A DOF of a joint on ground moves the whole body, and the virtual links hanging
    // from ground must move with it for no wire to change length: wires through a virtual link reach that
    // DOF's row (they pull the body but not the virtual link) although, once the virtual links'
    // equilibrium rows hold, they cannot move the body as a whole. What the internal columns do along that
    // rigid motion r of everything actuates the DOF, and what none can balance there is r . tau: the
    // equilibrium rows' targets (loads on virtual links, if any) move with the body. `data` holds the
    // frame's position kinematics. Allocates nothing.
    double apply(const Data& data, const Eigen::VectorXd& tau, int externalBegin, int externalEnd,
                 DistributionProblem& problem, std::vector<char>& unactuated);

private:
    void judgeByRigidMotion(const Data& data, const DistributionProblem& problem, const Eigen::VectorXd& tau,
                            int rootLink, int externalBegin, int externalEnd);

    const Model& model_;
    double threshold_;
    std::vector<int> virtualLinksOnGround_;  // virtual links whose joints hang from ground
    std::vector<Eigen::FullPivLU<JointMotion>> virtualLinkMotion_;  // their motion subspaces, factorized per frame
    // (nu x 6) per root mobility, u moving everything rigidly; by rows, so that a column's entries each add
    // one fixed-size row
    Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> rigidMotion_;
    Eigen::VectorXd rowSize_;      // (nu) largest |generalized force per unit variable| per row
    Eigen::VectorXd unbalanced_;   // (nu) per row, the generalized force no variable could balance if unactuated
};

}  // namespace sinew

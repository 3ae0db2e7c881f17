#pragma once
// Virtual links in quasi-static equilibrium: a virtual link is massless, so the wires that meet on it must
// exert no net force or moment on it. Its pose is solved at every evaluation by a warm-started, damped Newton
// iteration with the analytic stiffness; the equilibrated tensions then act on the bones. The treatment, its
// velocity and its limits are in docs/closed-chain.md, section "Virtual links".
#include <Eigen/Core>
#include <Eigen/LU>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

// How the last equilibrium solve ended: an expected numerical outcome, not an error. A solve stalls (not
// converged, residual left) where no exact equilibrium exists: a damped wire's tension jumps from 0 to
// damping x speed as it goes taut, and the residual can jump over zero there.
struct VirtualLinkEquilibriumStatus {
    bool converged = true;  // residual <= 1e-11 forceScale and the velocity settled
    int iterations = 0;     // Newton iterations taken
    // N, largest entry of the scaled residual: net wire force on a virtual link, and net moment divided by
    // its length scale (VirtualLinkEquilibriumData::lengthScale).
    double residual = 0;
    double forceScale = 0;  // N, largest sum over one virtual link of the magnitudes of its wire forces
    int slackLinks = 0;     // virtual links on which no wire pulls: their pose is left where it was
};

// The solver's buffers, sized once from the model; one per Data. The warm start is not kept here but in the
// Data the solve works on: the pose and twist of each virtual link (Data::R_GB, p_GB, w_GB, v_GB).
struct VirtualLinkEquilibriumData {
    // Throws sinew::Error, naming the wire, for a wire through a virtual link that is not a plain polyline.
    explicit VirtualLinkEquilibriumData(const Model& model);

    // From the model:
    std::vector<int> links;        // the virtual links' model indices (nv), group by group
    std::vector<int> wires;        // the wires with at least one point on a virtual link
    std::vector<int> slotOfLink;   // per model link: its position in `links`, or -1 for a real link
    std::vector<std::vector<int>> wiresOfSlot;  // per virtual link: the wires with a point on it (a stiffness column's)
    // Groups of virtual links that no wire joins to another group's (on the whole body, each forked muscle's
    // link is a group of its own): a group's residual depends on its own links' poses alone, and the stiffness
    // is block diagonal by group. `links` is ordered group by group, group g being slots [groupStart[g],
    // groupStart[g + 1]).
    std::vector<int> groupStart;
    std::vector<std::vector<int>> wiresOfGroup;
    // m, per virtual link: RMS distance of its wire points from its origin (1 m when all are at the origin).
    // Rotations are scaled by it (l dtheta, moment / l) so that every unknown is in m and every residual in N.
    std::vector<double> lengthScale;

    // Per evaluation (6 nv entries per vector, [rotational; translational] per virtual link, scaled):
    Eigen::VectorXd residual;    // N, [moment about the link origin / l; force], net wire load on each link
    // N/m, K = -d(residual)/d(l dtheta, dp) at frozen wire speeds (6nv x 6nv; zero off the groups' blocks)
    Eigen::MatrixXd stiffness;
    Eigen::VectorXd boneRate;    // N/s, d(residual)/dt from the bones' motion, virtual links held still
    Eigen::VectorXd step, twist;  // Newton step (m), and the virtual links' twist [l w; v] (m/s)
    Eigen::PartialPivLU<Eigen::MatrixXd> factor;  // of the regularised stiffness
    std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> groupFactor;  // of each group's block, for a solve at rest
    Eigen::VectorXd tension;       // N, per model wire (entries of `wires` only)
    Eigen::VectorXd tensionSlope;  // N/m, d(tension)/d(length) at fixed speed, per model wire (ditto)
    // Per model wire point (entries of `wires` only): the segment leaving the point (unit vector, length m),
    // and displacement buffers of up to six directional derivatives at once (a column each).
    std::vector<Eigen::Vector3d> segmentDirection;
    std::vector<double> segmentLength;
    std::vector<Eigen::Matrix<double, 3, 6>> dp_GP, dSegmentDirection;
    std::vector<Eigen::Matrix3d> R_GV0;  // poses before a line-search trial (nv)
    std::vector<Eigen::Vector3d> p_GV0;
    VirtualLinkEquilibriumStatus status;
};

// Solves every virtual link's pose and twist so that the wires through it are in equilibrium, warm-started
// from the pose and twist in `data`. Needs, for the wire points on real links of the wires in eq.wires,
// Data::p_GP and v_GP (calcWirePaths and calcWireSpeeds, or a caller's own kinematics). Leaves in `data` the
// virtual links' R_GB, p_GB, p_GM, w_GB, v_GB, and for the wires through them p_GP, v_GP, dLdp_GP,
// wireLength and wireSpeed, so that calcWireTensions and calcWireLinkForces give the equilibrated forces.
// The twist is the quasi-static one: the rate of the equilibrium pose as the bones move, from K twist =
// boneRate. Allocates nothing. Throws sinew::Error only when a force law does.
const VirtualLinkEquilibriumStatus& calcVirtualLinkEquilibrium(const Model& model, Data& data, double time,
                                                               VirtualLinkEquilibriumData& eq);

// The same with every speed zero (the bones at rest), for a pose whose virtual links no one observed (an
// inverse-kinematics fit, a picture of a motion table): where the wires' force laws hold them at `time`.
// Needs calcPositionKinematics at the pose; places the points of the wires through the virtual links itself
// and fills Data's velocities (zero). The other wires' paths are left as they were. Each group of virtual
// links (VirtualLinkEquilibriumData::groupStart) is solved on its own; status.iterations is the most a group took.
const VirtualLinkEquilibriumStatus& calcVirtualLinkEquilibriumAtRest(const Model& model, Data& data, double time,
                                                                     VirtualLinkEquilibriumData& eq);

// The pieces of the solve, for tests: at the poses and twists of the virtual links in `data`, the wire paths
// and speeds through them, their tensions and eq.residual (calcVirtualLinkResidual); eq.stiffness and
// eq.boneRate at the state of the last residual (calcVirtualLinkStiffness).
void calcVirtualLinkResidual(const Model& model, Data& data, double time, VirtualLinkEquilibriumData& eq);
void calcVirtualLinkStiffness(const Model& model, const Data& data, VirtualLinkEquilibriumData& eq);

// Writes the virtual links' poses and twists from `data` into q (nq) and u (nu) at their free joints' slots.
void getVirtualLinkCoordinates(const Model& model, const Data& data, const VirtualLinkEquilibriumData& eq,
                               Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> u);

// For simulators: the larger of `worst` and the status's residual (N); throws sinew::Error naming the time
// when the equilibrium broke down (a non-finite residual), which no later frame could repair.
double recordVirtualLinkResidual(double worst, const VirtualLinkEquilibriumStatus& status, double time);

}  // namespace sinew

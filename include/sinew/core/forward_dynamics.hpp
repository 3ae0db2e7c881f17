#pragma once
// O(N) forward dynamics of a closed-chain model: the articulated-body algorithm on loop-free subtrees and
// assembly-disassembly on the rest (Featherstone's divide-and-conquer algorithm in the multi-handle form
// that Yamane and Nakamura's assembly-disassembly computes); equations and conventions in
// docs/closed-chain.md. Simbody-free.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

#include "sinew/core/assembly_schedule.hpp"
#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"

namespace sinew {

// Buffers for one schedule, sized at construction; calcForwardDynamics allocates nothing.
struct ForwardDynamicsData {
    explicit ForwardDynamicsData(const Model& model, const AssemblySchedule& schedule);

    // Per assembly joint: the point its handles' quantities are taken about (m, in ground), and the bias
    // c = dS/dt u of its relative acceleration about that point. Body b's quantities are taken about the
    // point of its inboard joint, jointPoint[b] (its reference point o_b).
    std::vector<Eigen::Vector3d> jointPoint;
    std::vector<SpatialVector> jointBias;
    // Per assembly joint of a custom joint: its motion subspace S (6 x nu) about the joint point, ground axes.
    std::vector<JointMotion> jointMotion;
    // Per assembly joint: set where the inertia its motion acts on was singular (point masses).
    std::vector<char> singular;
    // Per body (numBodies), about o_b, ground axes: spatial velocity; articulated inertia and bias force
    // (the body's rigid inertia and p = v x* I v - f_external, plus what the bodies absorbed into it add,
    // RBDA eqs. 7.20-7.21); and, for bodies with a leaf (the skeleton), the inverse of that inertia.
    std::vector<SpatialVector> velocity;
    std::vector<Matrix6d> articulatedInertia;
    std::vector<SpatialVector> articulatedBias;
    std::vector<Matrix6d> inverseInertia;
    // Per assembly joint absorbed through a ball: the inverse of the child's rotational articulated
    // inertia about the joint centre (3 x 3), shared by the assembly and the acceleration passes.
    std::vector<Eigen::Matrix3d> rotationalInverse;
    // Per subassembly: the handle equations a_h = sum_k Phi_hk f_k + b_h, Phi stored h x h row-major.
    std::vector<std::vector<Matrix6d>> Phi;
    std::vector<std::vector<SpatialVector>> b;
    // Per operation: Y = T (T^T W T)^-1 T^T and the force offset g of the joint it joins, closes or absorbs
    // as a subassembly; for closures, the redundant directions and conditioning found (reduced into the
    // outputs below).
    std::vector<Matrix6d> Y;
    std::vector<SpatialVector> g;
    std::vector<int> operationRedundancy;
    std::vector<double> operationConditioning;
    // Per operation, per handle of its result: workspace (joins and closes: Phi_h,joint T and that times
    // E, first K columns used; leaves: the bottom rows of M(r_h - o) I^-1, and [r_h - o]x).
    std::vector<std::vector<Matrix6d>> scratchU;
    std::vector<std::vector<Matrix6d>> scratchUE;
    // Per handle (2 x assembly joints): the spatial force on the handle's body through its joint, about the
    // joint's point.
    std::vector<SpatialVector> handleForce;

    // Coordinate constraints (getCoordinateConstraints: the couplers, then the locked coordinates), m in all,
    // enforced by multipliers on top of the loops' solve (docs/closed-chain.md, "Coordinate constraints").
    // Per row: s f'(q_ind) and the acceleration right-hand side; the udot per unit multiplier (nu x m),
    // G A G^T and its factorisation, the free udot, and tau + G^T lambda.
    std::vector<CoordinateConstraint> constraints;
    Eigen::VectorXd constraintSlope, constraintRhs;
    Eigen::MatrixXd constraintResponse;
    Eigen::MatrixXd constraintMatrix;
    Eigen::LDLT<Eigen::MatrixXd> constraintSolver;
    Eigen::VectorXd freeUdot, constraintTau;

    // Outputs.
    Eigen::VectorXd udot;  // (nu) generalized accelerations; 0 for virtual links' joints
    // (numBodies) spatial accelerations about each body's reference point jointPoint[b], ground axes
    std::vector<SpatialVector> bodyAcceleration;
    std::vector<Eigen::Vector3d> loopForce;    // (numLoops) N, force on link B at the loop point, in ground
    // (m) each coordinate constraint's multiplier lambda, in `constraints`' order: the generalized force it
    // applies to the coordinate it constrains (N m or N); a coupler's independent coordinate gets -s f'(q) lambda.
    Eigen::VectorXd coordinateConstraintForce;
    SpatialVector hangForce = SpatialVector::Zero();  // holding the hung link: [moment about its origin; force]
    // Constraint directions that repeat others (e.g. a second ball loop on the axis of a hinge): solved in
    // the least-squares sense, accelerations exact, the loop forces along them minimum-norm.
    int redundantConstraints = 0;
    // Smallest over the loop closures of (smallest kept eigenvalue / largest) of T^T W T: near the 1e-9
    // cutoff, a loop is nearly redundant and its force, and the accelerations, lose digits accordingly.
    double loopConditioning = 1;
};

// udot for generalized forces `tau` (nu), gravity, and external spatial forces on the links, `linkForces`
// (numLinks, [moment about the link's origin; force], ground axes, e.g. from wires: calcWireLinkForces). Needs
// calcPositionKinematics and calcVelocityKinematics in `data`. `threads` > 1 shares each level of the
// schedule between threads (useful with a Balanced schedule); the answer does not depend on it. Virtual
// links take no part (see AssemblySchedule): their joints' udot is 0, and forces on them in `linkForces`
// are ignored. Couplers and locked coordinates hold at the acceleration level (q_dep'' = d^2/dt^2 s f(q_ind);
// a locked coordinate's udot = 0), at the cost of m + 2 more passes for m of them (docs/closed-chain.md,
// "Coordinate constraints"). Throws sinew::Error naming
// the joint where the mass matrix is singular (a point mass at a ball joint's centre, say).
void calcForwardDynamics(const Model& model, const AssemblySchedule& schedule, const Data& data,
                         const Eigen::VectorXd& tau, const std::vector<SpatialVector>& linkForces,
                         ForwardDynamicsData& fd, int threads = 1);

}  // namespace sinew

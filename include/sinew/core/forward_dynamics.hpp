#pragma once
// O(N) forward dynamics of a closed-chain model by assembly-disassembly (Featherstone's divide-and-conquer
// algorithm in the multi-handle form that Yamane and Nakamura's assembly-disassembly computes; equations and
// conventions in docs/closed-chain.md). Simbody-free.
#include <Eigen/Core>
#include <vector>

#include "sinew/core/assembly_schedule.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"

namespace sinew {

// Buffers for one schedule, sized at construction; calcForwardDynamics allocates nothing.
struct ForwardDynamicsData {
    explicit ForwardDynamicsData(const Model& model, const AssemblySchedule& schedule);

    // Per body (numBodies), about its centre of mass (m, in ground): inverse spatial inertia, spatial
    // velocity, and the bias force p = v x* I v - f_external.
    std::vector<Eigen::Vector3d> massCenter;
    std::vector<Matrix6d> inertiaInverse;
    std::vector<SpatialVector> velocity;
    std::vector<SpatialVector> bias;
    // Per assembly joint: the point its handles' quantities are taken about (m, in ground), and the bias
    // c = dS/dt u of its relative acceleration about that point.
    std::vector<Eigen::Vector3d> jointPoint;
    std::vector<SpatialVector> jointBias;
    // Per subassembly: the handle equations a_h = sum_k Phi_hk f_k + b_h, Phi stored h x h row-major.
    std::vector<std::vector<Matrix6d>> Phi;
    std::vector<std::vector<SpatialVector>> b;
    // Per operation: Y = T (T^T W T)^-1 T^T and the force offset g of the joint it joins or closes; for
    // closures, the redundant directions and conditioning found (reduced into the outputs below).
    std::vector<Matrix6d> Y;
    std::vector<SpatialVector> g;
    std::vector<int> operationRedundancy;
    // Per operation, per handle of its result: Phi_h,joint T and that times E (first K columns used).
    std::vector<std::vector<Matrix6d>> scratchU;
    std::vector<std::vector<Matrix6d>> scratchUE;
    std::vector<double> operationConditioning;
    // Per handle (2 x assembly joints): the spatial force on the handle's body through its joint, about the
    // joint's point.
    std::vector<SpatialVector> handleForce;

    // Outputs.
    Eigen::VectorXd udot;                      // (nu) generalized accelerations
    std::vector<SpatialVector> bodyAcceleration;  // (numBodies) spatial accelerations about massCenter, ground axes
    std::vector<Eigen::Vector3d> loopForce;    // (numLoops) N, force on link B at the loop point, in ground
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
// schedule between threads (useful with a Balanced schedule); the answer does not depend on it.
void calcForwardDynamics(const Model& model, const AssemblySchedule& schedule, const Data& data,
                         const Eigen::VectorXd& tau, const std::vector<SpatialVector>& linkForces,
                         ForwardDynamicsData& fd, int threads = 1);

}  // namespace sinew

#pragma once
// A hand-written articulated-body algorithm (Featherstone, Rigid Body Dynamics Algorithms, 2008, Table 7.1)
// for trees of ball joints under a ball or free root: the floor that sinew's bare-tree forward dynamics is
// timed against (ForwardDynamics/aba/<model>). Everything is in ground's Plücker coordinates about ground's
// origin, so a body's quantities pass to its parent without a transform; fixed-size Eigen blocks only.
// sinew's conventions: a ball joint's u is the angular velocity of M in F, in F; a free joint's q is a
// quaternion then p_FM, its u the angular velocity then dp_FM/dt, both in F.
#include <Eigen/Core>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew_benchmarks {

class ReferenceAba {
public:
    // Throws sinew::Error unless every joint is a ball joint or, at the root only, a free joint.
    explicit ReferenceAba(const sinew::Model& model);

    // udot (nu) from q (nq), u (nu) and tau (nu), under the model's gravity.
    void calcAccelerations(const Eigen::VectorXd& q, const Eigen::VectorXd& u, const Eigen::VectorXd& tau,
                           Eigen::VectorXd& udot);

private:
    using Vector6 = Eigen::Matrix<double, 6, 1>;
    using Matrix6 = Eigen::Matrix<double, 6, 6>;
    using Matrix63 = Eigen::Matrix<double, 6, 3>;

    // Per body, in the order of the model's links (parents first). S and U hold the rotation columns; a free
    // root's translation columns live in calcAccelerations.
    struct Body {
        int parent = -1;
        bool free = false;
        int qStart = 0, uStart = 0;
        double mass = 0;
        Eigen::Vector3d com_B, p_PF, p_BM;
        Eigen::Matrix3d inertia_B, R_PF, R_BM;
        // per evaluation
        Eigen::Matrix3d R_GB, R_GF;
        Eigen::Vector3d p_GB;
        Matrix63 S, U;             // rotation columns (about the joint centre) and IA S
        Eigen::Matrix3d Dinv;      // (S^T IA S)^-1
        Eigen::Vector3d residual;  // tau - S^T pA
        Vector6 V, c, pA, a;
        Matrix6 IA;
    };

    std::vector<Body> bodies_;
    Eigen::Vector3d gravity_;
};

}  // namespace sinew_benchmarks
